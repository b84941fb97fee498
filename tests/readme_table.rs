//! The README's table of thesis numbers is the output of `ars_programs::thesis_table`
//! (regenerate it with `make readme-table`), not typed by hand.

#[test]
fn the_readme_table_is_what_the_project_computes() {
    let table = ars_programs::thesis_table().unwrap();
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    assert!(readme.contains(&table), "README.md's thesis table is stale: run `make readme-table`\n{table}");
}
