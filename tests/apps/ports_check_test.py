#!/usr/bin/env python3
"""`adahrs ports check` against the virtual rig as an outside process: every role of a station
written for the rig's ports identifies (units by the serial names of the rig's manifest); with the
rate table silenced through the control port, its row fails with "no reply", every other row still
passes, and the exit status is 1.

Usage: ports_check_test.py ADAHRS_BINARY
"""
import json
import os
import pathlib
import signal
import subprocess
import sys
import tempfile
import time

import serial

TIME_SCALE = 200


def fail(message):
    print("FAIL:", message)
    sys.exit(1)


def port(path, baud=9600, flow="none"):
    return {"path": path, "baud": baud, "data_bits": 8, "parity": "N", "stop_bits": 1, "flow": flow}


def station_for(manifest, config):
    """A station file for every role of the rig (docs/station.md), addresses from the rig config."""
    links = manifest["links"]
    instruments = {}
    for instrument in manifest["instruments"]:
        role, kind = instrument["role"], instrument["kind"]
        section = config["instruments"][kind]
        entry = {"type": kind, "port": port(links[role]), "address": 0, "timeout_ms": 1000, "retries": 2}
        if kind == "watlow_f4":
            entry["address"] = section["modbus_address"]
        if kind == "watlow_942":
            entry["port"] = port(links[role], flow="xonxoff")
        if kind == "druck_adts_prologix":
            entry["address"] = instrument["gpib_address"]  # from the manifest, as an outside client would
            if instrument["gpib_address"] != section["gpib_address"]:
                raise SystemExit(f"FAIL: manifest gpib_address {instrument['gpib_address']}, config {section['gpib_address']}")
            entry["port"] = port(links[role], baud=115200)
        instruments[role] = entry
    units = [{"role": u["role"], "kind": u["kind"], "slot": u["slot"], "timeout_ms": 500,
              "port": port(links[u["role"]], baud=u["baud"])} for u in manifest["units"]]
    return {"name": "ports check test", "time_scale": TIME_SCALE,
            "site": {"latitude_deg": manifest["station"]["latitude_deg"],
                     "height_m": manifest["station"]["height_m"]},
            "instruments": instruments, "units": units,
            "operator": {"type": "virtual_fixture", "port": port(links["control"], baud=115200)}}


def rows_of(output):
    rows = {}
    for line in output.splitlines()[1:]:
        fields = line.split(None, 1)
        if len(fields) == 2:
            rows[fields[0]] = fields[1]
    return rows


def check(adahrs, station_path):
    result = subprocess.run([adahrs, "ports", "check", "--station", station_path],
                            capture_output=True, text=True, timeout=60)
    print(result.stdout + result.stderr)
    return result.returncode, rows_of(result.stdout)


def main():
    adahrs = sys.argv[1]
    config = json.loads(subprocess.run([adahrs, "rig", "--print-default-config"],
                                       capture_output=True, text=True, check=True).stdout)
    with tempfile.TemporaryDirectory() as tmp:
        manifest_path = pathlib.Path(tmp) / "manifest.json"
        rig = subprocess.Popen([adahrs, "rig", "--manifest", str(manifest_path), "--time-scale",
                                str(TIME_SCALE)], stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)
        try:
            deadline = time.monotonic() + 30
            while not manifest_path.exists():
                if rig.poll() is not None or time.monotonic() > deadline:
                    fail("the rig did not write its manifest")
                time.sleep(0.02)
            manifest = json.loads(manifest_path.read_text())
            station_path = os.path.join(tmp, "station.json")
            with open(station_path, "w") as f:
                json.dump(station_for(manifest, config), f, indent=2)

            code, rows = check(adahrs, station_path)
            if code != 0:
                fail(f"exit status {code} with every role healthy")
            for unit in manifest["units"]:
                if not rows.get(unit["role"], "").rstrip().endswith("ok"):
                    fail(f"{unit['role']} row: {rows.get(unit['role'])}")
                if unit["serial"] not in rows[unit["role"]]:
                    fail(f"{unit['role']} row does not name {unit['serial']}")
            for role in ("rate_table", "imu_chamber", "ads_chamber", "adts", "operator"):
                if not rows.get(role, "").rstrip().endswith("ok"):
                    fail(f"{role} row: {rows.get(role)}")

            with serial.Serial(manifest["links"]["control"], timeout=5) as control:
                control.write(b"fault rate_table silent on\n")
                reply = control.readline().decode().strip()
                if reply != "OK rate_table silent on":
                    fail(f"control port: {reply}")

            code, rows = check(adahrs, station_path)
            if code != 1:
                fail(f"exit status {code} with the rate table silent")
            if "FAILED" not in rows["rate_table"] or "no reply" not in rows["rate_table"]:
                fail(f"rate_table row: {rows['rate_table']}")
            for role, text in rows.items():
                if role != "rate_table" and not text.rstrip().endswith("ok"):
                    fail(f"{role} row fails with only the rate table silent: {text}")
        finally:
            rig.send_signal(signal.SIGTERM)
            rig.wait(timeout=10)
    print("PASS")


if __name__ == "__main__":
    main()
