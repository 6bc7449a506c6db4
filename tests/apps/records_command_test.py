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

from app_checks import expect

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
        # The recording format's version-2 headers (docs/recording-format.md) and two raw rows.
        imu_header = ("t_s,unit,seq,step,tag,orientation,chamber_c,table_rate_dps,"
                      + ",".join(f"{c}_t{k}" for c in ("az1", "ax1", "ay1", "az2", "ax2", "ay2") for k in (1, 2))
                      + ",gx,gy,gz,tx,ty,tz,mode," + ",".join(f"comp{i}" for i in range(9)) + ",comp_flags")
        row = ",".join(["1000", "2000"] * 6 + ["4194304"] * 3 + ["30000"] * 3 + ["0"] + [""] * 10)
        (run_dir / "imu.csv").write_text(imu_header + "\n"
                                         + f"0.01,IMU-0007,1,2,3,11,25.0,0,{row}\n"
                                         + f"0.02,IMU-0007,2,2,3,11,25.0,0,{row}\n")
        (run_dir / "ads.csv").write_text("t_s,unit,seq,step,tag,chamber_c,ps_ref_pa,qc_ref_pa,ps_counts,pt_counts,"
                                         "ps_temp_counts,pt_temp_counts,oat_counts,mode,alt_ft,cas_kt,comp_flags\n")
        digest = hashlib.sha256(b"".join((run_dir / n).read_bytes()
                                         for n in ("meta.json", "imu.csv", "ads.csv"))).hexdigest()
        db = tmp / "records.sqlite"

        first = run(adahrs, "records", "add-run", run_dir, "--db", db)
        expect(first.returncode == 0, first.stderr)
        expect(f"recording sha256 {digest}): recorded" in first.stdout, first.stdout)
        again = run(adahrs, "records", "add-run", run_dir, "--db", db)
        expect("already recorded" in again.stdout, again.stdout)

        show = run(adahrs, "units", "show", "IMU-0007", "--db", db)
        expect(show.returncode == 0, show.stderr)
        expect(show.stdout.startswith("IMU-0007 (imu)"), show.stdout)
        expect("runs: 1" in show.stdout and "imu_sensor_calibration" in show.stdout, show.stdout)
        expect("constants versions: 0" in show.stdout, show.stdout)

        unknown = run(adahrs, "units", "show", "IMU-0404", "--db", db)
        expect(unknown.returncode == 1 and str(db) in unknown.stderr, unknown.stderr)
        expect("no unit IMU-0404" in unknown.stderr, unknown.stderr)
        missing = run(adahrs, "units", "show", "IMU-0007", "--db", tmp / "none.sqlite")
        expect(missing.returncode == 1 and "none.sqlite: no such file" in missing.stderr, missing)
    print("ok")


if __name__ == "__main__":
    main(sys.argv[1])
