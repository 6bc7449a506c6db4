#!/usr/bin/env python3
"""adahrs study end to end on the short test sequence (tests/data/studies, nominal units): two
shards merged with `study merge` give the unsharded results.csv and summary.json byte for byte;
results.csv has one row per unit and strategy; the rig time is the duration `adahrs sequence
check` prints for the sequence; a shard spec 3/2 and an unknown strategy are refused naming the
option or the file and JSON path; an ADS study of two truth units (tolerance_minimax vs improved,
shipped ads_calibration) fails every unit with the first and keeps every altitude grid point of
every unit within tolerance with the second,
and an IMU study file paired with an ADS one is refused naming --vs and $.unit_kind.
Usage: study_command_test.py ADAHRS"""
import csv
import json
import pathlib
import re
import subprocess
import sys
import tempfile

from app_checks import expect

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATA = ROOT / "tests/data/studies"
UNITS = 3


def run(*args):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, timeout=300)


def study(adahrs, out, *extra):
    result = run(adahrs, "study", "--strategy", DATA / "short_thermal_order0.json",
                 "--vs", DATA / "short_improved.json", "--units", UNITS, "--seed", 3,
                 "--out", out, *extra)
    expect(result.returncode == 0, result.stderr)
    return result


def main(adahrs):
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        whole = study(adahrs, tmp / "whole", "--threads", 2)
        expect(f"study: {UNITS}/{UNITS} units" in whole.stderr, whole.stderr)
        expect("units/min" in whole.stderr and "ETA" in whole.stderr, whole.stderr)
        study(adahrs, tmp / "s1", "--shard", "1/2", "--threads", 1)
        study(adahrs, tmp / "s2", "--shard", "2/2", "--threads", 1)
        merged = run(adahrs, "study", "merge", tmp / "s2", tmp / "s1", "--out", tmp / "merged")
        expect(merged.returncode == 0, merged.stderr)
        for name in ("results.csv", "summary.json"):
            expect((tmp / "whole" / name).read_bytes() == (tmp / "merged" / name).read_bytes(), name)

        with open(tmp / "whole" / "results.csv", newline="") as f:
            rows = list(csv.DictReader(f))
        expect(len(rows) == 2 * UNITS, len(rows))
        expect([r["unit_index"] for r in rows] == [str(k // 2) for k in range(2 * UNITS)])
        expect({r["strategy"] for r in rows} == {"short_thermal_order0", "short_improved"})
        shard1 = list(csv.DictReader(open(tmp / "s1" / "results.csv", newline="")))
        expect({r["unit_index"] for r in shard1} == {"0", "2"}, shard1)

        check = run(adahrs, "sequence", "check", DATA / "short_imu_calibration.json")
        expect(check.returncode == 0, check.stderr)
        duration_s = float(re.search(r"estimated duration \S+ \(([0-9.]+) s\)", check.stdout).group(1))
        summary = json.loads((tmp / "whole" / "summary.json").read_text())
        for s in summary["strategies"]:
            expect(abs(s["rig_time_s"] - duration_s) < 0.5, (s["rig_time_s"], duration_s))
        expect("paired" in summary, summary)

        bad_shard = run(adahrs, "study", "--strategy", DATA / "short_improved.json", "--units", 2,
                        "--seed", 1, "--shard", "3/2", "--out", tmp / "bad")
        expect(bad_shard.returncode != 0)
        expect('--shard "3/2"' in bad_shard.stderr, bad_shard.stderr)
        unknown = run(adahrs, "study", "--strategy", DATA / "unknown_strategy.json", "--units", 2,
                      "--seed", 1, "--out", tmp / "bad")
        expect(unknown.returncode != 0)
        expect("unknown_strategy.json" in unknown.stderr and "$.strategy" in unknown.stderr, unknown.stderr)

        ads = run(adahrs, "study", "--strategy", DATA / "ads_tolerance_minimax.json",
                  "--vs", DATA / "ads_improved.json", "--units", 2, "--seed", 5, "--threads", 2,
                  "--out", tmp / "ads")
        expect(ads.returncode == 0, ads.stderr)
        ads_summary = json.loads((tmp / "ads" / "summary.json").read_text())
        expect(ads_summary["unit_kind"] == "ads", ads_summary)
        expect(ads_summary["strategies"][0]["yield"]["all"] == 0.0, ads_summary)
        ads_rows = list(csv.DictReader(open(tmp / "ads" / "results.csv", newline="")))
        expect([r["strategy"] for r in ads_rows] == ["ads_tolerance_minimax", "ads_improved"] * 2)
        for cubic, improved in zip(ads_rows[0::2], ads_rows[1::2]):
            expect(float(cubic["worst_altitude_tol"]) > 1.0, cubic)
            expect(float(improved["worst_altitude_tol"]) < 1.0, improved)
        mixed = run(adahrs, "study", "--strategy", DATA / "short_improved.json",
                    "--vs", DATA / "ads_improved.json", "--units", 1, "--seed", 1,
                    "--out", tmp / "bad")
        expect(mixed.returncode != 0)
        expect("--vs" in mixed.stderr and "$.unit_kind" in mixed.stderr, mixed.stderr)
    print("ok")


if __name__ == "__main__":
    main(sys.argv[1])
