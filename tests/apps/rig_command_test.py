#!/usr/bin/env python3
"""`adahrs rig` as an outside program sees it: starts, writes the manifest with symlinks, answers
on the ports (a pyserial client decodes the unit stream with the independent peer decoder and gets
an IDENTIFY answer; the control port switches a fault), and stops cleanly on SIGTERM, leaving
neither manifest nor port links; a dead rig's manifest is cleared at start, a live one's refused.

Usage: rig_command_test.py ADAHRS_BINARY
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

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "firmware_model"))
import unit_protocol_peer as peer  # noqa: E402

IDENTIFY = 0x06


def fail(message):
    print("FAIL:", message)
    sys.exit(1)


def request_frame(sequence, payload):
    body = bytes([len(payload), peer.REQUEST, sequence, 0]) + bytes(payload)
    crc = peer.crc16_ccitt_false(body)
    return peer.SYNC + body + bytes([crc & 0xFF, crc >> 8])


def read_for(port, seconds):
    data = bytearray()
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        data += port.read(65536)
    return bytes(data)


def control(port, line):
    port.write((line + "\n").encode())
    reply = port.readline().decode().strip()
    print(f"control: {line} -> {reply}")
    return reply


def main(adahrs):
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        # A config of our own: the built-in one with two IMUs, the second in orientation 12.
        default = json.loads(subprocess.run([adahrs, "rig", "--print-default-config"], check=True,
                                            capture_output=True, text=True).stdout)
        default["units"]["imu"] = default["units"]["imu"][:2]
        default["units"]["imu"][1]["orientation"] = 12
        default["units"]["imu"][0]["serial_number"] = 4711
        config = tmp / "rig.json"
        config.write_text(json.dumps(default))

        # A bad key is refused with the file and JSON path before anything starts.
        bad = dict(default, station=dict(default["station"], latitude=1.0))
        (tmp / "bad.json").write_text(json.dumps(bad))
        refused = subprocess.run([adahrs, "rig", "--config", str(tmp / "bad.json"), "--manifest",
                                  str(tmp / "bad_manifest.json")], capture_output=True, text=True)
        if refused.returncode == 0 or "$.station.latitude" not in refused.stderr:
            fail(f"bad config not refused properly: {refused.returncode} {refused.stderr!r}")

        manifest_path = tmp / "out" / "manifest.json"
        run_dir = tmp / "run"
        # A manifest whose rig still runs (this test's own pid stands in for it) is refused.
        manifest_path.parent.mkdir()
        manifest_path.write_text(json.dumps({"pid": os.getpid(), "links": {}}))
        busy = subprocess.run([adahrs, "rig", "--config", str(config), "--manifest", str(manifest_path)],
                              capture_output=True, text=True, timeout=30)
        if busy.returncode == 0 or f"pid {os.getpid()} still runs" not in busy.stderr:
            fail(f"a live rig's manifest was not refused: {busy.returncode} {busy.stderr!r}")
        # A dead rig's manifest and port link (pty numbers are reused) are cleared before the new
        # rig writes its own, so nobody waiting for the manifest picks up the old ports.
        # No process has a pid above 2**22 (Linux's largest pid_max).
        (run_dir / "ports").mkdir(parents=True)
        stale_link = run_dir / "ports" / "imu9"
        stale_link.symlink_to("/dev/pts/9999")
        manifest_path.write_text(json.dumps({"pid": 2 ** 22 + 17, "links": {"imu9": str(stale_link)}}))
        rig = subprocess.Popen([adahrs, "rig", "--config", str(config), "--manifest",
                                str(manifest_path), "--time-scale", "20", "--run-dir",
                                str(run_dir)], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True)
        try:
            # Wait for the manifest of the rig started here: its pid tells it from a stale one.
            deadline = time.monotonic() + 15
            manifest = None
            while manifest is None or manifest.get("pid") != rig.pid:
                if rig.poll() is not None or time.monotonic() > deadline:
                    fail(f"no manifest; rig exit {rig.poll()}: {rig.stderr.read()}")
                time.sleep(0.05)
                try:
                    manifest = json.loads(manifest_path.read_text())
                except FileNotFoundError:
                    manifest = None
            if os.path.lexists(stale_link):
                fail(f"the stale manifest or link survived: pid {manifest['pid']}, rig {rig.pid}")
            roles = set(manifest["ports"])
            if not {"imu1", "imu2", "ads1", "control"} <= roles or "imu3" in roles:
                fail(f"roles {sorted(roles)}")
            for role, device in manifest["ports"].items():
                link = run_dir / "ports" / role
                if os.readlink(link) != device or manifest["links"][role] != str(link):
                    fail(f"link {link} -> {os.readlink(link)}, port {device}")
            if not (run_dir / "truth" / "IMU-4711.json").exists():
                fail("no truth file for IMU-4711")

            # The unit through its stable link, as a station file would name it.
            with serial.Serial(str(run_dir / "ports" / "imu1"), 115200, timeout=0.05) as imu:
                imu.reset_input_buffer()
                decoded = peer.decode_stream(read_for(imu, 1.0))
                frames = [f for f in decoded["frames"] if f["type"] == peer.IMU]
                # 1 s wall at 20x is 2,000 packets; half of it proves the stream on a busy machine.
                if len(frames) < 1000:
                    fail(f"only {len(frames)} IMU packets in 1 s at 20x")
                gaps = sum((b["sequence"] - a["sequence"] - 1) % 256
                           for a, b in zip(frames, frames[1:]))
                if gaps or decoded["errors"]["bad_crc"]:
                    fail(f"{gaps} packets lost, errors {decoded['errors']}")
                print(f"imu1: {len(frames)} packets decoded, none lost")

                imu.write(request_frame(0x33, [IDENTIFY]))
                response = None
                for _ in range(50):
                    for f in peer.decode_stream(read_for(imu, 0.05))["frames"]:
                        if f["type"] == peer.RESPONSE and f["sequence"] == 0x33:
                            response = f["payload"]
                    if response:
                        break
                if not response or response[:2] != [IDENTIFY, 0]:
                    fail(f"IDENTIFY answered {response}")
                serial_number = int.from_bytes(bytes(response[3:7]), "little")
                if response[2] != 0x01 or serial_number != 4711:
                    fail(f"IDENTIFY kind {response[2]} serial {serial_number}")
                print("imu1: IDENTIFY ACK, IMU serial 4711")

                with serial.Serial(manifest["ports"]["control"], 115200, timeout=5) as ctl:
                    if not control(ctl, "time").startswith("OK "):
                        fail("time")
                    if control(ctl, "fault imu1 silent on") != "OK imu1 silent on":
                        fail("fault on")
                    time.sleep(0.1)
                    imu.reset_input_buffer()
                    if read_for(imu, 0.3):
                        fail("silent unit still sends")
                    control(ctl, "fault imu1 silent off")
                    if not read_for(imu, 0.3):
                        fail("unit does not resume")
                    if not control(ctl, "fault imu1 garbage maybe").startswith("ERR "):
                        fail("bad fault value accepted")

            # imu2 has no reader: its pty fills within a second at 20x, and after 2 s of wall time
            # without progress the host discards its stream (docs/rig.md). Give it that time.
            time.sleep(3.5)
            rig.send_signal(signal.SIGTERM)
            out, err = rig.communicate(timeout=10)
        except BaseException:
            rig.kill()
            rig.wait()
            raise
        if rig.returncode != 0 or "rig stopped by signal 15" not in out:
            fail(f"exit {rig.returncode}; stdout {out!r}; stderr {err!r}")
        print("rig stopped cleanly on SIGTERM")
        if "left by the rig of pid 4194321, which no longer runs" not in out:
            fail(f"the stale manifest's removal is not in the log: {out!r}")
        # Stopped, the rig leaves neither its manifest nor its port links behind.
        if manifest_path.exists() or (run_dir / "ports").exists():
            fail(f"left behind: manifest {manifest_path.exists()}, ports {list((run_dir / 'ports').iterdir())}")
        # The exit report: per port what the host lost and what the unit itself sent or dropped.
        # imu2 was never read, so the host discarded its stream; imu1's unit never had a full
        # transmit buffer (one request in the whole run).
        report = {line.split()[0]: dict(w.split("=") for w in line.split()[1:])
                  for line in out.splitlines() if "host_bytes_unread=" in line}
        if not {"imu1", "imu2", "ads1", "control"} <= set(report):
            fail(f"exit report lists {sorted(report)}: {out!r}")
        if int(report["imu2"]["host_bytes_unread"]) == 0:
            fail(f"imu2 was never read, yet nothing was discarded unread: {report['imu2']}")
        # imu1 was read throughout by a client that keeps up: nothing overflowed its backlog.
        if report["imu1"]["host_bytes_overflowed"] != "0":
            fail(f"imu1 was read, yet bytes overflowed: {report['imu1']}")
        if int(report["imu1"]["packets_sent"]) < 1000 or report["imu1"]["packets_dropped"] != "0":
            fail(f"imu1 unit counters {report['imu1']}")
        # The summary splits the two: bytes nobody read (imu2's) are not a client's loss.
        summary = [line for line in out.splitlines() if line.startswith("host: ") and "discarded" in line]
        if len(summary) != 1:
            fail(f"no host summary in {out!r}")
        discarded = int(summary[0].split()[1])
        cut = int(summary[0].split("with no client reading, ")[1].split()[0])
        if discarded != sum(int(r["host_bytes_unread"]) for r in report.values()) or \
                cut != sum(int(r["host_bytes_overflowed"]) for r in report.values()):
            fail(f"summary {summary[0]!r} is not the sum of the ports' {report}")
        print("exit report:", report["imu1"], report["imu2"])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
