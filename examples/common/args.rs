//! The examples' command line: `[--duration S] [--csv PATH] [--plot DIR] [--every N]`.

use std::path::PathBuf;
use std::process::exit;

/// Parsed options.
#[derive(Debug, Clone)]
pub struct Args {
    /// Simulated seconds to run.
    pub duration: f64,
    /// Where to write the CSV, if asked.
    pub csv: Option<PathBuf>,
    /// Folder to write the PNG plots into, if asked.
    pub plot: Option<PathBuf>,
    /// Keep one CSV row every N steps.
    pub every: usize,
}

fn usage(program: &str, default_duration: f64) -> String {
    format!(
        "usage: {program} [--duration S] [--csv PATH] [--plot DIR] [--every N]\n\
         \x20 --duration S  simulated seconds to run (default {default_duration})\n\
         \x20 --csv PATH    write the data as CSV\n\
         \x20 --plot DIR    write the figures as PNG into DIR\n\
         \x20 --every N     keep one CSV row every N steps (default 1)"
    )
}

/// Parses the command line; prints the usage and exits on `--help` or a mistake.
pub fn parse(default_duration: f64) -> Args {
    parse_except(default_duration, &[])
}

/// As [`parse`], ignoring the example's own flags `extra` (flags without values).
pub fn parse_except(default_duration: f64, extra: &[&str]) -> Args {
    let mut argv = std::env::args().filter(|a| !extra.contains(&a.as_str()));
    let program = argv.next().unwrap_or_else(|| "example".into());
    let mut args = Args { duration: default_duration, csv: None, plot: None, every: 1 };
    let fail = |msg: String| -> ! {
        eprintln!("{msg}\n{}", usage(&program, default_duration));
        exit(2)
    };
    while let Some(flag) = argv.next() {
        let mut value = |name: &str| argv.next().unwrap_or_else(|| fail(format!("{name} needs a value")));
        match flag.as_str() {
            "--duration" => {
                let v = value("--duration");
                args.duration = match v.parse::<f64>() {
                    Ok(d) if d.is_finite() && d > 0.0 => d,
                    _ => fail(format!("--duration must be a positive number of seconds, got {v:?}")),
                };
            }
            "--csv" => args.csv = Some(value("--csv").into()),
            "--plot" => args.plot = Some(value("--plot").into()),
            "--every" => {
                let v = value("--every");
                args.every = match v.parse::<usize>() {
                    Ok(n) if n > 0 => n,
                    _ => fail(format!("--every must be a positive whole number, got {v:?}")),
                };
            }
            "-h" | "--help" => {
                println!("{}", usage(&program, default_duration));
                exit(0)
            }
            other => fail(format!("unknown option {other:?}")),
        }
    }
    args
}

/// Writes CSV `rows` under `header` to `path` and says so.
pub fn write_csv(path: &std::path::Path, header: &str, rows: impl IntoIterator<Item = String>) -> std::io::Result<()> {
    use std::io::Write;
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(out, "{header}")?;
    for row in rows {
        writeln!(out, "{row}")?;
    }
    out.flush()?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

/// A CSV cell: the number, or empty.
pub fn cell(v: Option<f64>) -> String {
    v.map(|x| x.to_string()).unwrap_or_default()
}
