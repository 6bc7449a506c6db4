#!/usr/bin/env python3
"""adahrs sequence check: a shipped sequence prints its plan (exit 0); an invalid one prints
every problem with its JSON path and limit (exit 1). With --station, the station's instrument
limits: the shipped stations pass the shipped sequences of their bench, a station with a narrow
chamber refuses a shipped sequence naming the step and the limit, and `adahrs run` on that station
refuses it before it opens a single port (the station's ports do not even exist here).
Usage: sequence_command_test.py ADAHRS"""
import json
import os
import pathlib
import subprocess
import sys
import tempfile

from app_checks import expect

ROOT = pathlib.Path(__file__).resolve().parents[2]


def run(adahrs, path, *options):
    return subprocess.run([adahrs, "sequence", "check", str(path), *options],
                          capture_output=True, text=True, timeout=30)


def check_station_limits(adahrs, tmp):
    imu_station = ROOT / "docs/examples/station-virtual-rig.json"
    ads_station = ROOT / "docs/examples/station-virtual-rig-ads.json"
    for name, station in (("imu_burn_in", imu_station), ("imu_sensor_calibration", imu_station),
                          ("ads_burn_in", ads_station), ("ads_calibration", ads_station)):
        result = run(adahrs, ROOT / f"calib/sequences/{name}.json", "--station", str(station))
        expect(result.returncode == 0, (name, result.stderr))
        expect(f"{name} (" in result.stdout and "valid" in result.stdout, result.stdout)

    narrow = json.loads(imu_station.read_text())
    narrow["instruments"]["imu_chamber"]["limits"].update({"min_c": -10, "max_c": 40})
    narrow_path = pathlib.Path(tmp) / "narrow.json"
    narrow_path.write_text(json.dumps(narrow))
    burn_in = ROOT / "calib/sequences/imu_burn_in.json"
    refused = run(adahrs, burn_in, "--station", str(narrow_path))
    expect(refused.returncode == 1, refused)
    # The profile (step 3) ramps to -40 and 85 degC; the unit's rating allows both, the chamber
    # of this station neither.
    expect("beyond the chamber (Watlow F4)'s range (limit: chamber (Watlow F4) -10…40 degC)"
            in refused.stderr, refused.stderr)
    for target in ("-40", "85"):
        expect(f"temperature {target} degC beyond the chamber" in refused.stderr, refused.stderr)
    expect("$.steps[3].profile_steps[0].target_c" in refused.stderr, refused.stderr)
    expect("unit's rating" not in refused.stderr, refused.stderr)

    malformed = dict(narrow)
    malformed["instruments"]["imu_chamber"]["limits"] = {"max_c": 40}
    malformed_path = pathlib.Path(tmp) / "malformed.json"
    malformed_path.write_text(json.dumps(malformed))
    bad = run(adahrs, burn_in, "--station", str(malformed_path))
    expect(bad.returncode != 0, bad)
    expect("malformed.json" in bad.stderr and "$.instruments.imu_chamber.limits.min_c" in bad.stderr, bad.stderr)

    run_dir = pathlib.Path(tmp) / "run"
    started = subprocess.run([adahrs, "run", "--station", str(narrow_path), "--sequence",
                              str(burn_in), "--run-dir", str(run_dir)],
                             capture_output=True, text=True, timeout=30)
    expect(started.returncode != 0, started)
    expect("(limit: chamber (Watlow F4) -10…40 degC)" in started.stderr, started.stderr)
    # Refused before anything: no port was opened (the station's runs/rig/ports/... do not
    # exist, so opening one would have failed with another message) and no run was started.
    expect("runs/rig/ports" not in started.stderr, started.stderr)
    expect(not (run_dir / "meta.json").exists(), lambda: list(run_dir.iterdir()))


def main(adahrs):
    good = run(adahrs, ROOT / "calib/sequences/imu_sensor_calibration.json")
    expect(good.returncode == 0, good.stderr)
    expect("imu_sensor_calibration (imu sequence, 12 steps): valid" in good.stdout, good.stdout)
    # 7 rates x 3 axes, each a "set table rate" action, plus 3 cross-axis rate commands.
    expect(good.stdout.count("set table rate") == 24, good.stdout)
    expect("estimated duration" in good.stdout, good.stdout)

    bad = {"format_version": 1, "name": "bad", "description": "", "unit_kind": "imu",
           "steps": [{"kind": "target_temperature", "target_c": 95, "band_c": 1, "soak_s": 0},
                     {"kind": "accel", "orientation": 14, "packets": 10}]}
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "bad.json")
        with open(path, "w") as f:
            json.dump(bad, f)
        result = run(adahrs, path)
    expect(result.returncode == 1, result)
    expect("sequence refused, 2 problems" in result.stderr, result.stderr)
    expect("$.steps[0].target_c: temperature 95 degC beyond the unit's rating" in result.stderr)
    expect("(limit: unit rating -40…85 degC)" in result.stderr, result.stderr)
    expect("$.steps[1].orientation: orientation 14" in result.stderr, result.stderr)
    with tempfile.TemporaryDirectory() as tmp:
        check_station_limits(adahrs, tmp)
    print("ok")


if __name__ == "__main__":
    main(sys.argv[1])
