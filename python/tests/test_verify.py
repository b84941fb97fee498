"""python -m ars.verify: this installation computes the committed bits, and a table
that does not hold them is reported run by run, with where the output differs."""

import json
import subprocess
import sys

import ars
from ars import _native, verify


def test_python_m_ars_verify_finds_every_golden_run_identical():
    run = subprocess.run(
        [sys.executable, "-m", "ars.verify"],
        check=False,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert run.returncode == 0, run.stdout + run.stderr
    lines = run.stdout.splitlines()
    platform = _native._platform()
    assert lines[0].startswith(
        f"ARS {ars.__version__} (commit {platform['ars_commit']}) on libode 0.16"
    )
    assert platform["libc"] in lines[0] and platform["cpu"] in lines[0]
    names = [name for name, _, _ in _native._golden_runs()] + [verify.PYTHON_RUN]
    assert len(names) == 7
    for name in names:
        assert any(
            line.split()[0] == name and line.endswith(": identical") for line in lines[1:]
        ), name
    assert lines[-1] == "every golden run is identical to the table"


def test_a_table_that_does_not_hold_the_bits_is_reported_with_the_first_difference():
    output = verify.original_api_output()
    table = json.loads(_native._golden_with(verify.PYTHON_RUN, verify.PYTHON_RUN_DURATION, output))
    entry = next(e for e in table["runs"] if e["name"] == verify.PYTHON_RUN)
    # Pretend the table was written by a machine whose elbow differed from line 2000 on.
    for block in entry["blocks"]:
        if block["end"] >= 2000:
            cells = block["last"].split(",")
            cells[2] = repr(float(cells[2]) + 1e-12)
            block["last"] = ",".join(cells)
            block["sha256"] = "0" * 64
    entry["sha256"] = "0" * 64
    verdict = _native._golden_compare(verify.PYTHON_RUN, output, json.dumps(table))
    assert verdict.startswith("DIFFERENT: first in lines"), verdict
    assert 'column "elbow rate"' in verdict and "expected" in verdict, verdict
    lines, different = verify.report(json.dumps(table))
    assert different == 1 and "DIFFERENT" in next(
        line for line in lines if verify.PYTHON_RUN in line
    )
    assert _native._golden_compare("no such run", output).startswith("not in the golden table")
