#!/usr/bin/env python3
"""adahrs study with an external strategy (docs/strategies-external.md "Studying it"): the shipped
Python reference strategy's study file against the built-in reference on the same 6 drawn units
(truth profile, the shipped calibration sequence): every unit's worst acceleration and body-rate
errors are the same (the two fits agree far below the firmware's quantisation), so the paired
difference is zero with a zero-width interval; against the improved built-in the paired
difference in worst acceleration error is negative with its whole 95 % interval below zero (the
improved strategy's advantage; 50 units measured -7.3 mg, interval -8.4 to -6.3, on 2026-12-08).
Usage: external_study_test.py ADAHRS"""
import csv
import json
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
PYTHON_STUDY = ROOT / "strategies/python/python_reference_study.json"
EXAMPLES = ROOT / "docs/examples/studies"
UNITS = 6


def fail(message):
    print("FAIL:", message)
    sys.exit(1)


def study(adahrs, vs, out):
    r = subprocess.run([str(a) for a in (adahrs, "study", "--strategy", PYTHON_STUDY, "--vs", vs,
                                         "--units", UNITS, "--seed", 2, "--threads", 2,
                                         "--out", out)],
                       capture_output=True, text=True, timeout=900)
    print(r.stdout[-1500:], r.stderr[-1500:])
    if r.returncode != 0:
        fail(f"study against {vs.name}: exit status {r.returncode}")
    summary = json.loads((out / "summary.json").read_text())
    with open(out / "results.csv") as f:
        rows = list(csv.DictReader(f))
    return summary, rows


def main(adahrs):
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        summary, rows = study(adahrs, EXAMPLES / "imu_reference.json", tmp / "vs-reference")
        by_unit = {}
        for row in rows:
            if row["fitted"] != "1":
                fail(f"{row['serial']} {row['strategy']} not fitted: {row['failure']}")
            by_unit.setdefault(row["serial"], []).append(
                (float(row["worst_accel_mg"]), float(row["worst_rate_dps"])))
        if len(by_unit) != UNITS or any(len(v) != 2 or v[0] != v[1] for v in by_unit.values()):
            fail(f"the Python and built-in reference strategies' errors differ: {by_unit}")
        paired = summary["paired"]["worst_accel_mg"]
        if (paired["mean"], paired["ci95_low"], paired["ci95_high"]) != (0.0, 0.0, 0.0):
            fail(f"paired difference against the built-in reference: {paired}")
        summary, _ = study(adahrs, EXAMPLES / "imu_improved.json", tmp / "vs-improved")
        paired = summary["paired"]
        print("improved - python reference:", paired["worst_accel_mg"])
        if paired["difference"] != "imu_improved - python_reference_study" or \
                not paired["worst_accel_mg"]["ci95_high"] < 0.0:
            fail(f"the improved strategy's advantage is not shown: {paired}")
    print("PASS")


if __name__ == "__main__":
    main(sys.argv[1])
