#!/usr/bin/env python3
"""adahrs simulate static-thermal end to end: the simulator's recording is one the project's own
tools take as they take a rig's — its meta.json carries a run id, start time and status
"complete", a sequence that `adahrs sequence check` passes, units with role and slot, and the
station's local gravity at top level (a WGS-84 figure computed here independently), and
`adahrs records add-run` records it.
Usage: simulate_command_test.py ADAHRS"""
import json
import math
import pathlib
import subprocess
import sys
import tempfile


def run(*args):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, timeout=120)


def normal_gravity_mps2(latitude_deg, height_m):
    """WGS-84 normal gravity (Somigliana) with the free-air term of NIMA TR8350.2 Eq. 4-3."""
    a, b = 6378137.0, 6356752.3142
    ge, gp = 9.7803253359, 9.8321849378
    s2 = math.sin(math.radians(latitude_deg)) ** 2
    g0 = (a * ge * (1 - s2) + b * gp * s2) / math.sqrt(a * a * (1 - s2) + b * b * s2)
    f = 1 / 298.257223563
    m = 0.00344978650684
    return g0 * (1 - 2 / a * (1 + f + m - 2 * f * s2) * height_m + 3 * height_m ** 2 / a ** 2)


def main(adahrs):
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        out = tmp / "st"
        r = run(adahrs, "simulate", "static-thermal", "--out", out, "--imu-units", "2",
                "--ads-units", "1", "--latitude-deg", "52")
        if r.returncode != 0:
            return print("FAIL: simulate:", r.stderr) or 1
        meta = json.loads((out / "meta.json").read_text())
        if meta.get("status") != "complete" or not meta.get("run_id", "").startswith("st-"):
            failures.append(f"status/run_id: {meta.get('status')} {meta.get('run_id')}")
        g = normal_gravity_mps2(52.0, 0.0)
        if abs(meta.get("local_gravity_mps2", 0.0) - g) > 1e-6:
            failures.append(f"local_gravity_mps2 {meta.get('local_gravity_mps2')} vs {g:.7f}")
        roles = [(u["role"], u["kind"], u["serial"], u["slot"]) for u in meta["units"]]
        if roles != [("imu1", "imu", "IMU-0001", 1), ("imu2", "imu", "IMU-0002", 2),
                     ("ads1", "ads", "ADS-0001", 1)]:
            failures.append(f"units: {roles}")
        (tmp / "sequence.json").write_text(json.dumps(meta["sequence"]))
        r = run(adahrs, "sequence", "check", tmp / "sequence.json")
        if r.returncode != 0 or "valid" not in r.stdout:
            failures.append(f"sequence check: {r.returncode} {r.stdout} {r.stderr}")
        r = run(adahrs, "records", "add-run", out, "--db", tmp / "records.sqlite")
        if r.returncode != 0 or "(3 units, 3 steps" not in r.stdout:
            failures.append(f"records add-run: {r.returncode} {r.stdout} {r.stderr}")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
