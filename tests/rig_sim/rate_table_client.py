#!/usr/bin/env python3
"""An outside ATL client (pyserial), as the 1270VS control panel talks to the table: 9600 8N1,
commands ended by CR LF, every reply read up to the prompt terminator b"\\r\\n>\\r\\n".
Usage: rate_table_client.py PORT. Exits non-zero with a message on the first mismatch."""
import sys
import time

import serial

TERMINATOR = b"\r\n>\r\n"


def ask(port, command):
    port.write(command.encode("ascii") + b"\r\n")
    reply = port.read_until(TERMINATOR)
    if not reply.endswith(TERMINATOR):
        sys.exit(f"{command!r}: no prompt, got {reply!r}")
    return reply


def expect(port, command, wanted):
    reply = ask(port, command)
    if reply != wanted:
        sys.exit(f"{command!r}: expected {wanted!r}, got {reply!r}")


def main(path):
    with serial.Serial(path, 9600, bytesize=8, parity="N", stopbits=1, timeout=5) as port:
        expect(port, "ACL 200", b"\r\n>\r\n")
        expect(port, "JOG 50", b"\r\n>\r\n")
        expect(port, "JOG?", b"50.000\r\n>\r\n")
        expect(port, "JOG 500", b"?OUT OF RANGE JOG 500 LIMITS -360 360 deg/s\r\n>\r\n")
        expect(port, "JOG?", b"50.000\r\n>\r\n")
        # Wait on the table's own report, as a driver would (0.25 s ramp + 0.3 s settling).
        deadline = time.monotonic() + 10.0
        while float(ask(port, "RAT?")[:-len(TERMINATOR)]) < 49.99:
            if time.monotonic() > deadline:
                sys.exit("the table never reached 50 deg/s")
        expect(port, "STA?", b"11\r\n>\r\n")
        expect(port, "STO", b"\r\n>\r\n")
        deadline = time.monotonic() + 10.0
        while ask(port, "RAT?") != b"0.0000\r\n>\r\n":
            if time.monotonic() > deadline:
                sys.exit("the table never stopped")
        position = ask(port, "PPO")[:-len(TERMINATOR)]
        if not 0.0 <= float(position) < 360.0 or len(position.split(b".")[1]) != 4:
            sys.exit(f"PPO: bad position {position!r}")
        expect(port, "FOO", b"?UNKNOWN COMMAND\r\n>\r\n")
    print("ATL session OK")


if __name__ == "__main__":
    main(sys.argv[1])
