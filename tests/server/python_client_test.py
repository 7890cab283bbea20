#!/usr/bin/env python3
"""client/python/membrane_client.py against a live membraned: a Draco cloud in, a closed PLY
mesh out (checked by `membrane check`), the CRC-32C as the C++ client computes it, and a bad
upload refused with one line and exit 3.

Usage: python_client_test.py SOURCE_DIR MEMBRANED MEMBRANE
"""
import os
import re
import subprocess
import sys
import tempfile
import time

SOURCE_DIR, MEMBRANED, MEMBRANE = sys.argv[1:4]
CLIENT = os.path.join(SOURCE_DIR, "client", "python", "membrane_client.py")
sys.path.insert(0, os.path.dirname(CLIENT))
import membrane_client  # noqa: E402

failures = []


def expect(condition, what):
    if not condition:
        failures.append(what)
        print(f"FAILED: {what}")


def start_membraned(scratch):
    log_path = os.path.join(scratch, "membraned.log")
    log = open(log_path, "w")
    server = subprocess.Popen([MEMBRANED, "--listen=127.0.0.1:0", "--workers=1",
                               "--grace-seconds=1"], stderr=log, stdout=log)
    # The port is in the server_started line; wait for that line, not for a fixed time.
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline:
        with open(log_path) as f:
            match = re.search(r"event=server_started .*?\bport=(\d+)", f.read())
        if match:
            return server, f"127.0.0.1:{match.group(1)}"
        if server.poll() is not None:
            break
        time.sleep(0.05)
    server.kill()
    raise SystemExit(f"membraned did not start: {open(log_path).read()}")


def main():
    # The known CRC-32C check value ("123456789" -> 0xE3069283, RFC 3720).
    expect(membrane_client.crc32c(b"123456789") == 0xE3069283, "crc32c check value")
    with tempfile.TemporaryDirectory() as scratch:
        server, address = start_membraned(scratch)
        try:
            cloud = os.path.join(scratch, "torus.drc")
            subprocess.run([MEMBRANE, "synth", "torus", "-o", cloud, "--points", "20000"],
                           check=True, stdout=subprocess.DEVNULL)
            mesh = os.path.join(scratch, "torus.ply")
            run = subprocess.run([sys.executable, CLIENT, cloud, "-o", mesh, "--server",
                                  address, "--stats-json", os.path.join(scratch, "s.json")],
                                 capture_output=True, text=True)
            expect(run.returncode == 0, f"python client exit {run.returncode}: {run.stderr}")
            with open(mesh, "rb") as f:
                head = f.read(64)
            expect(head.startswith(b"ply\nformat binary_little_endian"), f"PLY header {head!r}")
            check = subprocess.run([MEMBRANE, "check", mesh], capture_output=True, text=True)
            expect(check.returncode == 0, f"membrane check: {check.stdout} {check.stderr}")
            expect("genus 1" in check.stdout or "[1]" in check.stdout,
                   f"a torus comes back genus 1: {check.stdout}")

            garbage = os.path.join(scratch, "garbage.drc")
            with open(garbage, "wb") as f:
                f.write(b"not a draco file at all" * 10)
            bad = subprocess.run([sys.executable, CLIENT, garbage, "-o",
                                  os.path.join(scratch, "bad.ply"), "--server", address],
                                 capture_output=True, text=True)
            lines = [l for l in bad.stderr.splitlines() if l.startswith("membrane_client: ")]
            expect(bad.returncode == 3, f"garbage upload exit {bad.returncode}: {bad.stderr}")
            expect(len(lines) == 1 and "INVALID_ARGUMENT" in lines[0],
                   f"one INVALID_ARGUMENT line: {bad.stderr}")
        finally:
            server.terminate()
            server.wait(timeout=30)
    if failures:
        return 1
    print("python client: reconstruct to PLY, CRC-32C and a refused upload as expected")
    return 0


if __name__ == "__main__":
    sys.exit(main())
