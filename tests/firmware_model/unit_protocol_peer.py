#!/usr/bin/env python3
"""Independent decoder of the unit serial protocol, written from docs/unit-protocol.md only.

Standard library only (struct, json): a bitwise CRC-16/CCITT-FALSE from its definition, the
resynchronisation rule of section 3.2, and the payload layouts of sections 4, 5 and 6.
Usage: unit_protocol_peer.py STREAM_FILE  -> prints a JSON object {"frames": [...], "errors": {...}}.
"""
import json
import struct
import sys

SYNC = b"\xa5\x5a"
IMU, ADS, REQUEST, RESPONSE = 0x01, 0x02, 0x20, 0x21
ALLOWED_LENGTHS = {
    IMU: lambda n: n in (43, 81),
    ADS: lambda n: n in (21, 31),
    REQUEST: lambda n: 1 <= n <= 250,
    RESPONSE: lambda n: 2 <= n <= 250,
}


def crc16_ccitt_false(data):
    crc = 0xFFFF
    for byte in data:
        crc ^= byte << 8
        for _ in range(8):
            crc = ((crc << 1) ^ 0x1021) if crc & 0x8000 else (crc << 1)
            crc &= 0xFFFF
    return crc


def decode_imu(payload):
    fields = struct.unpack_from("<12H3i3HB", payload, 0)
    out = {
        "t1_cnt": list(fields[0:12:2]),
        "t2_cnt": list(fields[1:12:2]),
        "gyro_cnt": list(fields[12:15]),
        "temp_cnt": list(fields[15:18]),
        "mode": fields[18],
    }
    if len(payload) == 81:
        values = struct.unpack_from("<9iH", payload, 43)
        out["values"] = list(values[:9])
        out["flags"] = values[9]
    return out


def decode_ads(payload):
    fields = struct.unpack_from("<5iB", payload, 0)
    out = {"codes": list(fields[:5]), "mode": fields[5]}
    if len(payload) == 31:
        values = struct.unpack_from("<2iH", payload, 21)
        out["values"] = list(values[:2])
        out["flags"] = values[2]
    return out


def decode_stream(data):
    frames = []
    errors = {"bad_crc": 0, "bad_length": 0, "unknown_type": 0, "skipped": 0}
    pos = 0
    while pos < len(data):
        if data[pos:pos + 2] != SYNC:
            if len(data) - pos < 2:
                break
            pos += 1
            errors["skipped"] += 1
            continue
        if len(data) - pos < 4:
            break
        length, ptype = data[pos + 2], data[pos + 3]
        if ptype not in ALLOWED_LENGTHS:
            errors["unknown_type"] += 1
            pos += 1
            continue
        if not ALLOWED_LENGTHS[ptype](length):
            errors["bad_length"] += 1
            pos += 1
            continue
        end = pos + 6 + length + 2
        if end > len(data):
            break
        (crc_sent,) = struct.unpack_from("<H", data, end - 2)
        if crc16_ccitt_false(data[pos + 2:end - 2]) != crc_sent:
            errors["bad_crc"] += 1
            pos += 1
            continue
        sequence, tag = data[pos + 4], data[pos + 5]
        payload = data[pos + 6:end - 2]
        frame = {"type": ptype, "sequence": sequence, "tag": tag, "crc": crc_sent}
        if ptype == IMU:
            frame["imu"] = decode_imu(payload)
        elif ptype == ADS:
            frame["ads"] = decode_ads(payload)
        else:
            frame["payload"] = list(payload)
        frames.append(frame)
        pos = end
    return {"frames": frames, "errors": errors}


def main():
    with open(sys.argv[1], "rb") as stream:
        data = stream.read()
    json.dump(decode_stream(data), sys.stdout)
    return 0


if __name__ == "__main__":
    sys.exit(main())
