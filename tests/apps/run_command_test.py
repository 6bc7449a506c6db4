#!/usr/bin/env python3
"""`adahrs run` as an operator sees it, against `adahrs rig` started as a separate process:
refuses a missing option and a run directory that already holds a run; SIGTERM, SIGHUP or Ctrl-C
(SIGINT) in the middle of a sequence leaves the rig's table at rest, meta.json "interrupted" and a
journal entry, exits with status 128 + the signal, names it and says how to resume, and
`adahrs run --resume` then completes the run (meta.json status "complete").

Usage: run_command_test.py ADAHRS_BINARY
"""
import json
import pathlib
import signal
import subprocess
import sys
import tempfile
import time

import serial


def fail(message):
    print("FAIL:", message)
    sys.exit(1)


def station_for(manifest, config):
    """A station file for every role of the rig (as tests/support/rig_process.h writes it)."""
    def port(path, baud, flow):
        return {"path": path, "baud": baud, "data_bits": 8, "parity": "N", "stop_bits": 1,
                "flow": flow}
    instruments = {}
    for inst in manifest["instruments"]:
        role, kind = inst["role"], inst["kind"]
        section = config["instruments"][kind]
        address, baud, flow = 0, 9600, "none"
        if kind == "watlow_f4":
            address = section["modbus_address"]
        if kind == "druck_adts_prologix":
            address, baud = section["gpib_address"], 115200
        if kind == "watlow_942":
            flow = "xonxoff"
        instruments[role] = {"type": kind, "port": port(manifest["links"][role], baud, flow),
                             "address": address, "timeout_ms": 1000, "retries": 2}
    units = [{"role": u["role"], "kind": u["kind"], "slot": u["slot"], "timeout_ms": 500,
              "port": port(manifest["links"][u["role"]], u["baud"], "none")}
             for u in manifest["units"]]
    return {"name": "run command test", "time_scale": manifest["time_scale"],
            "site": {"latitude_deg": manifest["station"]["latitude_deg"],
                     "height_m": manifest["station"]["height_m"]},
            "instruments": instruments, "units": units,
            "operator": {"type": "virtual_fixture",
                         "port": port(manifest["links"]["control"], 115200, "none")}}


def interrupt(adahrs, manifest, tmp, run_dir, sig, status):
    """Starts the sequence into run_dir, sends `sig` once the table turns, and checks the stop."""
    args = [adahrs, "run", "--station", str(tmp / "station.json"), "--sequence",
            str(tmp / "sequence.json"), "--run-dir", str(run_dir)]
    run = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    journal = run_dir / "journal.jsonl"
    deadline = time.monotonic() + 30
    while "set table rate 50" not in (journal.read_text() if journal.exists() else ""):
        if time.monotonic() > deadline or run.poll() is not None:
            run.kill()
            out, err = run.communicate()
            fail(f"the run never reached the gyro step's rate: {out[-2000:]} {err}")
        time.sleep(0.01)
    run.send_signal(sig)
    out, err = run.communicate(timeout=60)
    print(err)
    if run.returncode != status:
        fail(f"exit status {run.returncode} after {sig.name}, expected {status}")
    if f"interrupted by {sig.name}" not in err or f"adahrs run --resume {run_dir}" not in err:
        fail(f"no signal name or resume instruction after {sig.name}: {err}")
    meta = json.loads((run_dir / "meta.json").read_text())
    if meta["status"] != "interrupted":
        fail(f"meta.json status {meta['status']} after {sig.name}")
    if "interrupted" not in journal.read_text():
        fail(f"no journal entry of the interruption after {sig.name}")
    # The safe stop commanded the table to rest; its rate loop settles the last
    # 1e-4 deg/s within a fraction of a simulated second (tau 0.05 s), which at 10x can
    # still be under way when this query comes: poll for up to 2 s of wall time.
    deadline = time.monotonic() + 2.0
    with serial.Serial(manifest["links"]["control"], 115200, timeout=5) as control:
        while True:
            control.write(b"env\n")
            env = control.readline().decode()
            rate = float(env.split("table_rate_dps=")[1].split()[0])
            if rate == 0.0 or time.monotonic() > deadline:
                break
            time.sleep(0.05)
    print(f"rig after {sig.name}:", env.strip())
    if rate != 0.0:
        fail(f"table still turning 2 s after {sig.name}: {rate} deg/s")


def main():
    adahrs = sys.argv[1]
    with tempfile.TemporaryDirectory(prefix="adahrs-run-cli-") as tmp:
        tmp = pathlib.Path(tmp)
        missing = subprocess.run([adahrs, "run", "--station", "x.json"], capture_output=True,
                                 text=True)
        if missing.returncode == 0 or "--sequence" not in missing.stderr + missing.stdout:
            fail(f"missing options accepted: {missing.returncode} {missing.stderr}")

        config = json.loads(subprocess.check_output([adahrs, "rig", "--print-default-config"]))
        # 10x: the 40 simulated seconds of the sequence take 4 s of wall time, room for a Ctrl-C,
        # and the executor's 60 s clock-time wait margin is 6 s of wall time. At 20x (3 s) a
        # loaded 2-core machine failed this test about once in 10-60 runs: a unit logger that
        # did not read for 2-3 s wall (cause not pinned down: docs/executor.md, "Known problem")
        # ran out of margin, not the behaviour under test.
        rig = subprocess.Popen([adahrs, "rig", "--manifest", str(tmp / "rig" / "manifest.json"),
                                "--time-scale", "10"], stdout=subprocess.DEVNULL,
                               stderr=subprocess.STDOUT)
        try:
            manifest_path = tmp / "rig" / "manifest.json"
            deadline = time.monotonic() + 30
            while not manifest_path.exists():
                if time.monotonic() > deadline or rig.poll() is not None:
                    fail("the rig did not start")
                time.sleep(0.05)
            manifest = json.loads(manifest_path.read_text())
            (tmp / "station.json").write_text(json.dumps(station_for(manifest, config)))
            (tmp / "sequence.json").write_text(json.dumps({
                "format_version": 1, "name": "cli", "description": "Ctrl-C and resume",
                "unit_kind": "imu", "steps": [
                    {"kind": "accel", "orientation": 11, "packets": 500},
                    {"kind": "gyro", "orientation": 31, "packets": 500, "rate_min_dps": 50,
                     "rate_max_dps": 50, "rate_increment_dps": 10, "table_accel_dps2": 100}]}))
            run_dir = tmp / "run"
            args = [adahrs, "run", "--station", str(tmp / "station.json"), "--sequence",
                    str(tmp / "sequence.json"), "--run-dir", str(run_dir)]
            # SIGTERM (`kill`) and SIGHUP (a closed terminal) stop a run as Ctrl-C does; the
            # last run, stopped by SIGINT, is the one refused and resumed below.
            for sig, status in ((signal.SIGTERM, 143), (signal.SIGHUP, 129), (signal.SIGINT, 130)):
                interrupted = run_dir if sig == signal.SIGINT else tmp / f"run-{sig.name}"
                interrupt(adahrs, manifest, tmp, interrupted, sig, status)
            again = subprocess.run(args, capture_output=True, text=True)
            if again.returncode == 0 or "--resume" not in again.stderr:
                fail(f"a second run into the same directory was not refused: {again.stderr}")
            resumed = subprocess.run([adahrs, "run", "--resume", str(run_dir)],
                                     capture_output=True, text=True, timeout=120)
            if resumed.returncode != 0:
                fail(f"resume failed: {resumed.stderr}")
            meta = json.loads((run_dir / "meta.json").read_text())
            if meta["status"] != "complete":
                fail(f"meta.json status after resume {meta['status']}")
        finally:
            rig.send_signal(signal.SIGTERM)
            rig.wait(timeout=30)
    print("PASS")


if __name__ == "__main__":
    main()
