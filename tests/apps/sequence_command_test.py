#!/usr/bin/env python3
"""adahrs sequence check: a shipped sequence prints its plan (exit 0); an invalid one prints
every problem with its JSON path and limit (exit 1). Usage: sequence_command_test.py ADAHRS"""
import json
import os
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]


def run(adahrs, path):
    return subprocess.run([adahrs, "sequence", "check", str(path)], capture_output=True,
                          text=True, timeout=30)


def main(adahrs):
    good = run(adahrs, ROOT / "calib/sequences/imu_sensor_calibration.json")
    assert good.returncode == 0, good.stderr
    assert "imu_sensor_calibration (imu sequence, 12 steps): valid" in good.stdout, good.stdout
    # 7 rates x 3 axes, each a "set table rate" action, plus 3 cross-axis rate commands.
    assert good.stdout.count("set table rate") == 24, good.stdout
    assert "estimated duration" in good.stdout, good.stdout

    bad = {"format_version": 1, "name": "bad", "description": "", "unit_kind": "imu",
           "steps": [{"kind": "target_temperature", "target_c": 95, "band_c": 1, "soak_s": 0},
                     {"kind": "accel", "orientation": 14, "packets": 10}]}
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "bad.json")
        with open(path, "w") as f:
            json.dump(bad, f)
        result = run(adahrs, path)
    assert result.returncode == 1, result
    assert "sequence refused, 2 problems" in result.stderr, result.stderr
    assert "$.steps[0].target_c: temperature 95 degC beyond the unit's rating" in result.stderr
    assert "(limit: unit rating -40…85 degC)" in result.stderr, result.stderr
    assert "$.steps[1].orientation: orientation 14" in result.stderr, result.stderr
    print("ok")


if __name__ == "__main__":
    main(sys.argv[1])
