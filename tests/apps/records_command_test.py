#!/usr/bin/env python3
"""adahrs records add-run / units show end to end: a run directory (meta.json format 2) is recorded
once, its checksum equals hashlib's over meta.json, imu.csv, ads.csv; the unit's history lists the
run; unknown units and missing databases are refused naming the database file.
Usage: records_command_test.py ADAHRS"""
import hashlib
import json
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]


def run(*args):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, timeout=30)


def main(adahrs):
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        run_dir = tmp / "run"
        run_dir.mkdir()
        sequence = json.loads((ROOT / "calib/sequences/imu_sensor_calibration.json").read_text())
        meta = {"format_version": 2, "run_id": "r-1", "started_utc": "2024-05-01T08:00:00Z",
                "status": "complete", "station": {"name": "virtual lab"}, "sequence": sequence,
                "sequence_file": "imu_sensor_calibration.json", "time_base": "s",
                "sample_rate_hz": 100, "local_gravity_mps2": 9.79,
                "units": [{"role": "imu1", "kind": "imu", "serial": "IMU-0007",
                           "serial_number": 7, "firmware": "1.0.0", "slot": 1,
                           "constants_version": 0, "mode": 0}],
                "instruments": [], "rejected_intervals": []}
        (run_dir / "meta.json").write_text(json.dumps(meta))
        (run_dir / "imu.csv").write_text("t_s\n")
        (run_dir / "ads.csv").write_text("t_s\n")
        digest = hashlib.sha256(b"".join((run_dir / n).read_bytes()
                                         for n in ("meta.json", "imu.csv", "ads.csv"))).hexdigest()
        db = tmp / "records.sqlite"

        first = run(adahrs, "records", "add-run", run_dir, "--db", db)
        assert first.returncode == 0, first.stderr
        assert f"recording sha256 {digest}): recorded" in first.stdout, first.stdout
        again = run(adahrs, "records", "add-run", run_dir, "--db", db)
        assert "already recorded" in again.stdout, again.stdout

        show = run(adahrs, "units", "show", "IMU-0007", "--db", db)
        assert show.returncode == 0, show.stderr
        assert show.stdout.startswith("IMU-0007 (imu)"), show.stdout
        assert "runs: 1" in show.stdout and "imu_sensor_calibration" in show.stdout, show.stdout
        assert "constants versions: 0" in show.stdout, show.stdout

        unknown = run(adahrs, "units", "show", "IMU-0404", "--db", db)
        assert unknown.returncode == 1 and str(db) in unknown.stderr, unknown.stderr
        assert "no unit IMU-0404" in unknown.stderr, unknown.stderr
        missing = run(adahrs, "units", "show", "IMU-0007", "--db", tmp / "none.sqlite")
        assert missing.returncode == 1 and "none.sqlite: no such file" in missing.stderr, missing
    print("ok")


if __name__ == "__main__":
    main(sys.argv[1])
