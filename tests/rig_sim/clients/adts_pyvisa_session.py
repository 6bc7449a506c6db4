"""A pyserial client initialising a Prologix adapter the way pyvisa-py does, then querying the
ADTS at GPIB address 1 (protocols.md §6.2). Prints one line per answer."""
import sys

import serial

port = serial.Serial(sys.argv[1], 115200, timeout=3)


def send(line):
    port.write((line + "\n").encode())


for command in ["++mode 1", "++auto 0", "++read_tmo_ms 500", "++eos 3", "++eoi 1", "++eot_enable 0"]:
    send(command)
send("++ver")
print(port.readline().decode().strip())
for command in ["*IDN?", "SOUR:STAT ON", "SOUR:STAT?", "UNIT:PRES HPA", "MEAS:PRES? ALT"]:
    send("++addr 1")
    send(command)
    if "?" in command:
        send("++read eoi")
        answer = port.readline().decode().strip()
        # Altitude at ground in control carries the controller noise (σ ≈ 0.4 ft): print a check.
        print(f"|ALT| < 5 ft: {abs(float(answer)) < 5}" if command.startswith("MEAS") else answer)
