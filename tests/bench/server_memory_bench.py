#!/usr/bin/env python3
"""membraned's resident memory (VmRSS of the process, from /proc) in two situations.

watchers: one job with a large mesh, then W `membrane jobs watch` clients fetching it at once:
  the RSS before them, the highest sampled while they run (every 10 ms), and after.
expiry:   J jobs of mixed sizes, C at a time, then their results expire (--result-ttl-seconds
  passes and a `jobs list` drops them): the RSS at start, after the jobs, and once expired.

Usage: server_memory_bench.py --bin DIR [--scenario watchers|expiry] [--env K=V ...]
  [--watchers 6] [--jobs 24] [--concurrent 4]
DIR holds membraned, membrane-decode and membrane (a build's server/ and client/ copied
together, or --bin-server and --bin-client apart). --env sets membraned's environment
(MALLOC_ARENA_MAX=1, LD_PRELOAD=/usr/lib/x86_64-linux-gnu/libjemalloc.so.2, ...).
Prints one line of figures per scenario; nothing is asserted.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile
import threading
import time


def rss_kb(pid):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


class Server:
    def __init__(self, server_dir, workdir, env, flags):
        self.log = os.path.join(workdir, "membraned.log")
        e = dict(os.environ)
        e.update(env)
        self.proc = subprocess.Popen(
            [os.path.join(server_dir, "membraned"), "--listen=127.0.0.1:0",
             "--decoder_path=" + os.path.join(server_dir, "membrane-decode")] + flags,
            stdout=open(self.log, "w"), stderr=subprocess.STDOUT, env=e)
        for _ in range(600):
            m = re.search(r"event=server_started.* port=(\d+)", open(self.log).read())
            if m:
                self.address = "127.0.0.1:" + m.group(1)
                return
            time.sleep(0.05)
        sys.exit("membraned did not start:\n" + open(self.log).read())

    def rss_kb(self):
        return rss_kb(self.proc.pid)

    def stop(self):
        self.proc.terminate()
        self.proc.wait(30)


class Sampler:
    """The highest RSS of `pid` seen every 10 ms while running."""

    def __init__(self, pid):
        self.pid, self.peak, self.stop_flag = pid, 0, False
        self.thread = threading.Thread(target=self.run)
        self.thread.start()

    def run(self):
        while not self.stop_flag:
            self.peak = max(self.peak, rss_kb(self.pid))
            time.sleep(0.01)

    def stop(self):
        self.stop_flag = True
        self.thread.join()
        return self.peak


def run(client, args, workdir):
    r = subprocess.run([client] + args, cwd=workdir, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"membrane {' '.join(args)} failed ({r.returncode}): {r.stderr}")
    return r.stdout


def settle(server, seconds=2.0):
    """The lowest RSS over `seconds` (the allocator returns memory lazily)."""
    low = server.rss_kb()
    end = time.time() + seconds
    while time.time() < end:
        time.sleep(0.1)
        low = min(low, server.rss_kb())
    return low


def watchers(a, client, server_dir, workdir, env):
    server = Server(server_dir, workdir, env, ["--workers=1"])
    cloud = os.path.join(workdir, "big.ply")
    run(client, ["synth", "sphere", "-o", cloud, "--points", str(a.points)], workdir)
    run(client, ["reconstruct", cloud, "-o", os.path.join(workdir, "m.drc"), "--server",
                 server.address, "--voxel-size", str(a.voxel_size), "--quantization", "0",
                 "--compression-level", "0", "-q"], workdir)
    job = run(client, ["jobs", "list", "--server", server.address], workdir).split()[0]
    mesh_mb = os.path.getsize(os.path.join(workdir, "m.drc")) / 1e6
    before = settle(server)
    sampler = Sampler(server.proc.pid)
    procs = [subprocess.Popen([client, "jobs", "watch", job, "--server", server.address, "-q",
                               "-o", os.path.join(workdir, f"w{i}.drc")], cwd=workdir,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
             for i in range(a.watchers)]
    codes = [p.wait() for p in procs]
    peak = sampler.stop()
    after = settle(server)
    server.stop()
    print(f"watchers={a.watchers} mesh_mb={mesh_mb:.1f} rss_before_mb={before / 1e3:.1f} "
          f"rss_peak_mb={peak / 1e3:.1f} added_mb={(peak - before) / 1e3:.1f} "
          f"rss_after_mb={after / 1e3:.1f} exit_codes={sorted(set(codes))}")


def expiry(a, client, server_dir, workdir, env):
    ttl = 5
    server = Server(server_dir, workdir, env,
                    [f"--workers={a.concurrent}", f"--queue={a.jobs}",
                     f"--result-ttl-seconds={ttl}", "--job-threads=1"])
    start = settle(server, 1.0)
    clouds = []
    for i, (shape, points) in enumerate([("sphere", 20000), ("torus", 60000),
                                          ("two-spheres", 100000), ("sphere", 150000)]):
        path = os.path.join(workdir, f"c{i}.ply")
        run(client, ["synth", shape, "-o", path, "--points", str(points)], workdir)
        clouds.append(path)
    sampler = Sampler(server.proc.pid)
    began = time.time()
    procs = []
    for j in range(a.jobs):
        procs.append(subprocess.Popen(
            [client, "reconstruct", clouds[j % len(clouds)], "-o",
             os.path.join(workdir, f"m{j}.drc"), "--server", server.address, "-q",
             "--timeout", "600"], cwd=workdir, stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL))
    codes = [p.wait() for p in procs]
    jobs_seconds = time.time() - began
    peak = sampler.stop()
    after_jobs = settle(server)
    time.sleep(ttl + 0.5)  # the TTL is what is measured here: real time must pass
    run(client, ["jobs", "list", "--server", server.address], workdir)  # expires them
    expired = settle(server, 12.0)  # jemalloc's pages decay over 10 s
    server.stop()
    print(f"jobs={a.jobs} concurrent={a.concurrent} rss_start_mb={start / 1e3:.1f} "
          f"rss_peak_mb={peak / 1e3:.1f} rss_after_jobs_mb={after_jobs / 1e3:.1f} "
          f"rss_expired_mb={expired / 1e3:.1f} jobs_seconds={jobs_seconds:.1f} "
          f"exit_codes={sorted(set(codes))}")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--bin", help="directory of membraned, membrane-decode and membrane")
    p.add_argument("--bin-server")
    p.add_argument("--bin-client")
    p.add_argument("--scenario", choices=["watchers", "expiry"], default="watchers")
    p.add_argument("--env", action="append", default=[])
    p.add_argument("--watchers", type=int, default=6)
    p.add_argument("--points", type=int, default=200000)
    p.add_argument("--voxel-size", type=float, default=0.006)
    p.add_argument("--jobs", type=int, default=24)
    p.add_argument("--concurrent", type=int, default=4)
    a = p.parse_args()
    server_dir = os.path.abspath(a.bin_server or a.bin)
    client = os.path.abspath(os.path.join(a.bin_client or a.bin, "membrane"))
    env = dict(kv.split("=", 1) for kv in a.env)
    with tempfile.TemporaryDirectory() as workdir:
        print(f"env={' '.join(a.env) or '-'} ", end="")
        {"watchers": watchers, "expiry": expiry}[a.scenario](a, client, server_dir, workdir, env)


if __name__ == "__main__":
    main()
