"""A pyserial client with XON/XOFF flow control speaking the Watlow 942 ASCII protocol
(protocols.md §3.3): the tty driver consumes the 942's XON/XOFF, leaving only the values."""
import sys
import time

import serial

port = serial.Serial(sys.argv[1], 9600, timeout=3, xonxoff=True)


def ask(line):
    port.write((line + "\r").encode())
    return port.read_until(b"\r").decode().strip()


def tell(line):
    port.write((line + "\r").encode())
    time.sleep(0.3)


tell("= SP1 40")
print(ask("? SP1"))
print(ask("? ER2"))
tell("= SP1 999")
print(ask("? ER2"))
print(ask("? MDL"))
