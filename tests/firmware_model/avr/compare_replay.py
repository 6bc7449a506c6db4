#!/usr/bin/env python3
"""The 16-bit-int proof: the firmware's golden replay on an AVR (simavr) against the host.

Usage: compare_replay.py --simavr SIMAVR --elf REPLAY.elf --host REPLAY_HOST GOLDEN.json...

Runs the same C99 replay program (golden_replay.c) built for the host (int of 32 bits) and for an
ATmega2560 (avr-gcc, int of 16 bits) executed by simavr, and fails unless
  1. the two transcripts are identical, line for line (every output word, flag, cycle count,
     block status and protocol byte);
  2. every compensator output of the replay equals the golden JSON's: the nine or two value words,
     the flags and the model's cycle count of every frame in every mode;
  3. every frame the units sent carries a valid CRC-16/CCITT-FALSE (Python's binascii.crc_hqx, an
     implementation independent of the firmware's), and every data packet in a compensated mode
     carries the golden values of its frame.
Prints the counts it compared and the AVR's unused RAM. Exit status 0 only if all hold.
"""
import argparse
import binascii
import json
import re
import struct
import subprocess
import sys

UART_LINE = re.compile(r"\x1b\[32m(.*?)\.\r?\n\x1b\[0m")


def fail(message):
    print(f"compare_replay: FAIL: {message}")
    sys.exit(1)


def avr_transcript(simavr, elf):
    run = subprocess.run([simavr, "-m", "atmega2560", "-f", "16000000", elf],
                         capture_output=True, timeout=240)
    text = run.stderr.decode("latin-1")
    lines = UART_LINE.findall(text)
    if run.returncode != 0 or not lines:
        fail(f"simavr exited {run.returncode} with {len(lines)} UART lines; stderr tail:\n"
             f"{text[-2000:]}")
    ram = [line for line in lines if line.startswith("ram_free ")]
    return [line for line in lines if not line.startswith("ram_free ")], ram


def host_transcript(host):
    run = subprocess.run([host], capture_output=True, timeout=120)
    if run.returncode != 0:
        fail(f"{host} exited {run.returncode}: {run.stderr.decode(errors='replace')}")
    return run.stdout.decode().splitlines()


def frames(lines):
    """(tag, bytes) of every 'rsp'/'dat' frame of a transcript, in order."""
    out = []
    i = 0
    while i < len(lines):
        words = lines[i].split()
        if words and words[0] in ("rsp", "dat"):
            length = int(words[1])
            data = bytearray()
            i += 1
            while len(data) < length:
                data += bytes(int(h, 16) for h in lines[i].split())
                i += 1
            out.append((words[0], bytes(data)))
        else:
            i += 1
    return out


def signed(hex_word):
    v = int(hex_word, 16)
    return v - (1 << 32) if v >= 1 << 31 else v


def check_replay(lines, goldens):
    """Compensator outputs against the golden documents; returns (frame modes, words) compared."""
    set_index, modes, words = -1, 0, 0
    for line in lines:
        w = line.split()
        if w[0] == "set":
            set_index = int(w[1])
        elif w[0] in ("imu", "ads"):
            frame, mode, flags, cycles = int(w[1]), int(w[2]), int(w[3], 16), int(w[4])
            expected = goldens[set_index][w[0]]["frames"][frame]["modes"][mode]
            got = {"value": [signed(h) for h in w[5:]], "flags": flags, "cycles": cycles}
            for key in ("value", "flags", "cycles"):
                if got[key] != expected[key]:
                    fail(f"set {set_index} {w[0]} frame {frame} mode {mode} {key}: golden "
                         f"{expected[key]}, replay {got[key]}")
            modes += 1
            words += len(got["value"]) + 2
    return modes, words


def check_frames(lines, goldens):
    """CRCs of every frame; golden values in the compensated data packets."""
    checked = values = 0
    # Data packets follow in the order of the sessions (make_replay_program.py): per set, the IMU
    # frames in modes 0..3, then the ADS frames in modes 0..1.
    expected = []
    for golden in goldens:
        for unit, modes in (("imu", range(4)), ("ads", range(2))):
            for mode in modes:
                for frame in golden[unit]["frames"]:
                    expected.append((unit, mode, frame["modes"][mode]))
    data_packets = []
    for tag, frame in frames(lines):
        body, crc = frame[2:-2], struct.unpack("<H", frame[-2:])[0]
        if frame[:2] != b"\xa5\x5a" or binascii.crc_hqx(body, 0xFFFF) != crc:
            fail(f"{tag} frame {frame.hex()} fails its CRC-16/CCITT-FALSE")
        checked += 1
        if tag == "dat":
            data_packets.append(frame)
    if len(data_packets) != len(expected):
        fail(f"{len(data_packets)} data packets, expected {len(expected)}")
    for frame, (unit, mode, golden_mode) in zip(data_packets, expected):
        payload = frame[6:-2]
        mode_offset, count = (42, 9) if unit == "imu" else (20, 2)
        if payload[mode_offset] != mode:
            fail(f"{unit} data packet in mode {payload[mode_offset]}, expected {mode}")
        if mode == 0:
            continue
        got = list(struct.unpack(f"<{count}i", payload[mode_offset + 1:mode_offset + 1 + 4 * count]))
        flags = struct.unpack("<H", payload[mode_offset + 1 + 4 * count:][:2])[0]
        if got != golden_mode["value"] or flags != golden_mode["flags"]:
            fail(f"{unit} data packet mode {mode}: {got} flags {flags}, golden "
                 f"{golden_mode['value']} flags {golden_mode['flags']}")
        values += count + 1
    return checked, len(data_packets), values


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--simavr", required=True)
    parser.add_argument("--elf", required=True)
    parser.add_argument("--host", required=True)
    parser.add_argument("golden", nargs="+")
    args = parser.parse_args()
    goldens = []
    for path in args.golden:
        with open(path) as file:
            goldens.append(json.load(file))

    avr, ram = avr_transcript(args.simavr, args.elf)
    host = host_transcript(args.host)
    for number, (a, h) in enumerate(zip(avr, host), 1):
        if a != h:
            fail(f"transcript line {number} differs:\n  host (int 32): {h}\n  avr  (int 16): {a}")
    if len(avr) != len(host):
        fail(f"the AVR wrote {len(avr)} lines, the host {len(host)}")
    if not host or not host[-1].startswith("end"):
        fail("the transcript does not reach its end")
    modes, words = check_replay(host, goldens)
    crcs, data_packets, values = check_frames(host, goldens)
    print(f"compare_replay: {len(host)} transcript lines identical on the host (int 32 bits) and "
          f"the ATmega2560 (int 16 bits, simavr)")
    print(f"compare_replay: {modes} frame-modes of the golden vectors ({words} words: values, "
          f"flags, cycle counts) equal the golden JSON on both")
    print(f"compare_replay: {crcs} frames with valid CRCs ({data_packets} data packets, "
          f"{values} compensated words in them equal to the golden values)")
    print(f"compare_replay: AVR {ram[0] if ram else 'ram_free ?'} bytes never touched (of 8192)")


if __name__ == "__main__":
    main()
