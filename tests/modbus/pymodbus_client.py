"""A pymodbus client against `stc run --realtime --modbus` (the plant
program of crates/stc/tests/controller.rs): reads and writes coils and
registers and waits for the program's reaction. Usage: HOST PORT.
Exits 0 when every check passed; prints what failed otherwise."""

import sys
import time

from pymodbus.client import ModbusTcpClient


def eventually(what, check, limit=10.0):
    end = time.monotonic() + limit
    while time.monotonic() < end:
        if check():
            return
        time.sleep(0.02)
    sys.exit(f"{what}: not within {limit} s")


def main():
    host, port = sys.argv[1], int(sys.argv[2])
    c = ModbusTcpClient(host, port=port, timeout=5)
    if not c.connect():
        sys.exit("cannot connect")

    def count():
        r = c.read_input_registers(10, count=2)
        assert not r.isError(), r
        return (r.registers[0] << 16) | r.registers[1]

    first = count()
    eventually("the cycle counter moves", lambda: count() > first)

    r = c.write_coil(0, True)
    assert not r.isError(), r
    eventually("lamp follows start", lambda: c.read_coils(1, count=1).bits[0])

    r = c.write_registers(0, [-7 & 0xFFFF])
    assert not r.isError(), r
    eventually(
        "level = 2 * setpoint",
        lambda: c.read_input_registers(0, count=1).registers[0] == (-14 & 0xFFFF),
    )

    r = c.read_holding_registers(5000, count=1)
    assert r.isError() and r.exception_code == 2, r
    r = c.read_discrete_inputs(0, count=1)
    assert r.isError() and r.exception_code == 2, r
    c.close()
    print("ok")


main()
