#!/usr/bin/env python3
"""`adahrs unit mode` against the virtual rig's units, started as their own process (`adahrs rig`),
checked on the wire by an independent pyserial client that decodes with the standard-library peer
(tests/firmware_model/unit_protocol_peer.py, written from docs/unit-protocol.md): the mode the
command reads is the one the unit's IDENTIFY answer and its data packets carry; a mode set is read
back and the data packets change format (ADS surface 31-byte payloads with mode 1, raw 21 bytes
with mode 0); a mode the unit does not define and a calibrated mode without constants are refused
with the unit's NAK, the port and the mode named, and nothing changes; a silent unit and an absent
port are named. The ADS gets its constants through `adahrs download` (fit of a synthetic run).

Usage: unit_mode_command_test.py ADAHRS_BINARY
"""
import json
import pathlib
import signal
import subprocess
import sys
import tempfile
import time

import serial

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "firmware_model"))
sys.path.insert(0, str(HERE))
import unit_protocol_peer as peer  # noqa: E402
from fit_command_test import write_run  # noqa: E402  (an ADS-0007 run with exact codes)
from rig_command_test import read_for, request_frame  # noqa: E402
from run_command_test import station_for  # noqa: E402

IDENTIFY, SET_MODE = 0x06, 0x01


def fail(message):
    print("FAIL:", message)
    sys.exit(1)


def run(*args, timeout=60):
    r = subprocess.run([str(a) for a in args], capture_output=True, text=True, timeout=timeout)
    print(f"$ {' '.join(str(a) for a in args[1:])} -> {r.returncode}\n{r.stdout}{r.stderr}", end="")
    return r


class Client:
    """The independent client: its own frames and CRC, the peer's decoder."""

    def __init__(self, path):
        self.port = serial.Serial(path, 115200, timeout=0.05)
        self.sequence = 0x40

    def close(self):
        self.port.close()

    def request(self, payload):
        self.sequence = (self.sequence + 1) % 256
        self.port.reset_input_buffer()
        self.port.write(request_frame(self.sequence, payload))
        for _ in range(60):
            for f in peer.decode_stream(read_for(self.port, 0.05))["frames"]:
                if f["type"] == peer.RESPONSE and f["sequence"] == self.sequence:
                    return f["payload"]
        fail(f"no answer to {payload}")

    def identify_mode(self):
        answer = self.request([IDENTIFY])
        if answer[:2] != [IDENTIFY, 0] or len(answer) != 17:
            fail(f"IDENTIFY answered {answer}")
        return answer[15]

    def packets(self, kind):
        """(payload length, mode) of the data packets of one second."""
        self.port.reset_input_buffer()
        read_for(self.port, 0.1)  # whatever was in flight
        frames = peer.decode_stream(read_for(self.port, 1.0))["frames"]
        key = "imu" if kind == peer.IMU else "ads"
        return {(len(f[key].get("values", [])), f[key]["mode"]) for f in frames if f["type"] == kind}


def main(adahrs):
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        config = json.loads(subprocess.run([adahrs, "rig", "--print-default-config"], check=True,
                                           capture_output=True, text=True).stdout)
        config["units"]["imu"] = config["units"]["imu"][:1]
        config["units"]["ads"][0]["serial_number"] = 7  # the fitted run's ADS-0007
        (tmp / "rig.json").write_text(json.dumps(config))
        manifest_path = tmp / "manifest.json"
        rig = subprocess.Popen([adahrs, "rig", "--config", tmp / "rig.json", "--manifest",
                                manifest_path, "--time-scale", "2", "--run-dir", tmp / "rig"],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        try:
            deadline = time.monotonic() + 15
            while not manifest_path.exists() or json.loads(manifest_path.read_text())["pid"] != rig.pid:
                if rig.poll() is not None or time.monotonic() > deadline:
                    fail(f"no manifest; rig exit {rig.poll()}")
                time.sleep(0.05)
            manifest = json.loads(manifest_path.read_text())
            imu_port, ads_port = manifest["links"]["imu1"], manifest["links"]["ads1"]
            check(adahrs, tmp, manifest, config, imu_port, ads_port)
        finally:
            rig.send_signal(signal.SIGTERM)
            rig.communicate(timeout=15)


def expect_refused(r, *words):
    if r.returncode == 0 or not all(w in r.stderr for w in words):
        fail(f"expected a refusal naming {words}: {r.returncode} {r.stderr!r}")


def check(adahrs, tmp, manifest, config, imu_port, ads_port):
    # Read: the command's mode is the unit's, as the independent client sees it.
    r = run(adahrs, "unit", "mode", "--port", imu_port)
    if r.returncode != 0 or "imu serial 1 " not in r.stdout or "mode 0 (raw)" not in r.stdout:
        fail("IMU mode not read")
    imu = Client(imu_port)
    if imu.identify_mode() != 0 or imu.packets(peer.IMU) != {(0, 0)}:
        fail("the IMU is not raw on the wire")
    imu.close()
    # A calibrated mode without constants: the unit's NAK, nothing changes.
    r = run(adahrs, "unit", "mode", "--port", imu_port, "--set", "3")
    expect_refused(r, imu_port, "SET_MODE 3", "NAK no valid constants")
    imu = Client(imu_port)
    if imu.identify_mode() != 0 or imu.packets(peer.IMU) != {(0, 0)}:
        fail("a refused mode changed the IMU")
    imu.close()

    # The ADS gets constants (fitted from a synthetic run of its serial) and is left in mode 1.
    write_run(tmp / "run")
    if run(adahrs, "fit", "--run", tmp / "run", "--ads-strategy", "reference", "--out",
           tmp / "fit").returncode != 0:
        fail("fit")
    (tmp / "station.json").write_text(json.dumps(station_for(manifest, config)))
    if run(adahrs, "download", "--station", tmp / "station.json", "--unit", "ads1", "--constants",
           tmp / "fit" / "ADS-0007.json", timeout=120).returncode != 0:
        fail("download")
    r = run(adahrs, "unit", "mode", "--port", ads_port)
    if r.returncode != 0 or "ads serial 7 " not in r.stdout or "mode 1 (surface)" not in r.stdout \
            or "constants committed" not in r.stdout:
        fail("ADS mode not read")
    for mode, values in ((0, 0), (1, 2), (0, 0)):
        r = run(adahrs, "unit", "mode", "--port", ads_port, "--set", str(mode))
        if r.returncode != 0 or f"mode {mode} " not in r.stdout:
            fail(f"ADS mode {mode} not set")
        ads = Client(ads_port)
        seen = (ads.identify_mode(), ads.packets(peer.ADS))
        ads.close()
        if seen != (mode, {(values, mode)}):
            fail(f"after --set {mode} the wire says mode {seen[0]}, packets {seen[1]}")
        print(f"ads1 mode {mode}: IDENTIFY and every data packet agree ({values} values)")
    # The independent client sets the mode; the command reads it.
    ads = Client(ads_port)
    if ads.request([SET_MODE, 1]) != [SET_MODE, 0, 1]:
        fail("SET_MODE 1 by the independent client")
    ads.close()
    r = run(adahrs, "unit", "mode", "--port", ads_port)
    if "mode 1 (surface)" not in r.stdout:
        fail("the command does not read the mode the independent client set")
    # A mode the ADS does not define.
    expect_refused(run(adahrs, "unit", "mode", "--port", ads_port, "--set", "2"),
                   ads_port, "SET_MODE 2", "NAK bad argument")
    # Out of the protocol's range, refused before the port is opened.
    expect_refused(run(adahrs, "unit", "mode", "--port", ads_port, "--set", "4"), "--set")
    # An absent port; a silent unit.
    expect_refused(run(adahrs, "unit", "mode", "--port", tmp / "no-such-port"),
                   str(tmp / "no-such-port"), "open")
    with serial.Serial(manifest["ports"]["control"], 115200, timeout=5) as ctl:
        ctl.write(b"fault ads1 silent on\n")
        if not ctl.readline().startswith(b"OK"):
            fail("fault ads1 silent on")
        expect_refused(run(adahrs, "unit", "mode", "--port", ads_port, "--timeout-ms", "100"),
                       ads_port, "IDENTIFY", "no reply")
        ctl.write(b"fault ads1 silent off\n")
        ctl.readline()


if __name__ == "__main__":
    main(sys.argv[1])
    print("ok")
