#!/usr/bin/env python3
"""The demo's recordings against their sample-time bound (docs/recording-format.md "Sample time"),
checked by scripts/check-sample-times, which reads the CSV files itself (not the C++ reader).

First the checker against recordings made here with known frames: one read in bursts within its
line's buffering passes; the same with phantom counter turns planted into one unit (frame and
t_sample_s one turn ahead from a row on, as a counter that slipped writes them) fails, naming the
unit and the row. Then a demo's four recordings (IMU and ADS calibration and
acceptance) hold the bound on every row: those of the demo directory ADAHRS_DEMO_DIR names (e.g.
`scripts/demo`'s runs/demo, which scripts/demo also checks when it ends), or, with
ADAHRS_DEMO_RUN=1, of an `adahrs demo --quick` run here at its default top speed (900x in
lockstep; several minutes of wall time on the 2-core VM, too long for every suite run).

Usage: demo_sample_times_test.py /path/to/adahrs
"""
import csv
import json
import os
import subprocess
import sys
import tempfile

CHECKER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts",
                       "check-sample-times")


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def write_run(run_dir, planted_unit=None, planted_from_line=None):
    """Two units' true frames [1000, 3000) read in bursts of 1 s on a 1.2 s line."""
    os.makedirs(run_dir, exist_ok=True)
    units = [{"serial": s, "line_buffering_s": 1.2, "clock_drift_ppm": 0.0}
             for s in ("IMU-0001", "IMU-0002")]
    with open(os.path.join(run_dir, "meta.json"), "w") as f:
        json.dump({"format_version": 4, "units": units}, f)
    with open(os.path.join(run_dir, "imu.csv"), "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["t_s", "unit", "seq", "frame", "t_sample_s"])
        line = 1
        for frame in range(1000, 3000):
            for serial in ("IMU-0001", "IMU-0002"):
                line += 1
                t_s = 0.01 * ((frame // 100 + 1) * 100)
                written = frame
                if serial == planted_unit and line >= planted_from_line:
                    written += 256
                out.writerow([f"{t_s:.4f}", serial, frame % 256, written, f"{0.01 * written:.2f}"])


def run_checker(*run_dirs):
    return subprocess.run([sys.executable, CHECKER, *run_dirs], capture_output=True, text=True)


def check_the_checker(scratch):
    clean = os.path.join(scratch, "clean")
    write_run(clean)
    result = run_checker(clean)
    if result.returncode != 0:
        fail("a recording within its buffering was refused:\n" + result.stdout + result.stderr)
    planted = os.path.join(scratch, "planted")
    write_run(planted, "IMU-0002", 1001)
    result = run_checker(planted)
    if result.returncode != 1 or "imu.csv:1001: IMU-0002" not in result.stdout:
        fail("planted phantom turns were not named by unit and row:\n" + result.stdout +
             result.stderr)
    if "OUT OF BOUNDS" in "".join(l for l in result.stdout.splitlines(True) if "IMU-0001" in l):
        fail("the clean unit beside the planted one was refused:\n" + result.stdout)
    print("checker: passes the clean recording, names the planted turn at imu.csv:1001")


def check_demo(adahrs, scratch):
    demo_dir = os.environ.get("ADAHRS_DEMO_DIR")
    if not demo_dir and os.environ.get("ADAHRS_DEMO_RUN") != "1":
        print("demo: not checked here (set ADAHRS_DEMO_DIR=DIR, or ADAHRS_DEMO_RUN=1 to run one)")
        return
    if not demo_dir:
        demo_dir = os.path.join(scratch, "demo")
        result = subprocess.run([adahrs, "demo", "--out", demo_dir, "--quick"],
                                capture_output=True, text=True, timeout=1800)
        if result.returncode != 0:
            fail(f"adahrs demo --quick exited {result.returncode}:\n" + result.stdout[-4000:] +
                 result.stderr[-4000:])
        for line in result.stdout.splitlines():
            if line.startswith("run "):
                print("demo: " + line)
    runs_dir = os.path.join(demo_dir, "runs")
    runs = sorted(os.path.join(runs_dir, d) for d in os.listdir(runs_dir)
                  if os.path.exists(os.path.join(runs_dir, d, "meta.json")))
    if len(runs) != 4:
        fail(f"{runs_dir}: expected the demo's four recordings, found {runs}")
    result = run_checker(*runs)
    print(result.stdout, end="")
    if result.returncode != 0:
        fail("the demo's recordings leave their sample-time bound:\n" + result.stderr)


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory(prefix="adahrs_demo_sample_times_") as scratch:
        check_the_checker(scratch)
        check_demo(sys.argv[1], scratch)
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
