#!/usr/bin/python3
"""How long the web console takes to show a list of many jobs: membraned (no tokens) is given
JOBS real jobs (small spheres, submitted with the membrane client, a few at once), then headless
Chromium (chromedriver) loads the page RUNS times, each in a fresh tab state; per load it reads
when the first list was on screen (the page's own mark, data-list-shown-ms: after the frame that
laid the rows out, in ms since navigation start) and checks that every job has its row. Also
times GET /api/jobs alone.

With --web-dir DIR given more than once, the jobs are kept in a store, and membraned is started
again on that store with each DIR as its page's files, one after the other: pages side by side
on the same jobs.

Usage: web_console_load.py MEMBRANED MEMBRANE [--jobs 1000] [--runs 5] [--web-dir DIR ...]
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request
from concurrent.futures import ThreadPoolExecutor

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "server"))
from webdriver_client import WebDriver, free_port  # noqa: E402


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("membraned")
    parser.add_argument("membrane")
    parser.add_argument("--jobs", type=int, default=1000)
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--web-dir", action="append", default=[])
    args = parser.parse_args()
    work = tempfile.mkdtemp(prefix="web-console-load-")
    processes = []
    driver = None
    try:
        store = os.path.join(work, "store")
        servers = []  # the one running last

        def start_server(web_dir=None):
            """membraned on the jobs' store (with --web-dir), its gRPC and HTTP ports."""
            log = open(os.path.join(work, "membraned.log"), "w+")
            extra = [f"--store-dir={store}"] if args.web_dir else []
            if web_dir:
                extra.append(f"--web-dir={web_dir}")
            servers.append(subprocess.Popen(
                [args.membraned, "--listen=127.0.0.1:0", "--http-listen=127.0.0.1:0", "--workers=2",
                 f"--queue={args.jobs + 10}", "--result-ttl-seconds=86400"] + extra, stderr=log))
            for _ in range(300):
                log.seek(0)
                m = re.search(r"event=server_started .* port=(\d+) .* http_port=(\d+)", log.read())
                if m:
                    return int(m.group(1)), int(m.group(2))
                time.sleep(0.1)
            raise AssertionError("membraned did not start")
        port, http_port = start_server()
        cloud = os.path.join(work, "sphere.drc")
        subprocess.run([args.membrane, "synth", "sphere", "--points", "500", "-o", cloud],
                       check=True, stdout=subprocess.DEVNULL)

        def submit(i):
            return subprocess.run([args.membrane, "reconstruct", cloud, "-o",
                                   os.path.join(work, f"m{i % 8}.drc"), "--server",
                                   f"127.0.0.1:{port}", "-q"],
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode
        started = time.monotonic()
        with ThreadPoolExecutor(4) as pool:
            codes = list(pool.map(submit, range(args.jobs)))
        assert codes.count(0) == args.jobs, f"{args.jobs - codes.count(0)} jobs failed"
        print(f"{args.jobs} jobs submitted and finished in {time.monotonic() - started:.0f} s")

        def measure(http_port, name):
            page = f"http://127.0.0.1:{http_port}/"
            api = []
            for _ in range(args.runs):
                t = time.monotonic()
                with urllib.request.urlopen(page + "api/jobs", timeout=60) as response:
                    size = len(response.read())
                api.append((time.monotonic() - t) * 1000)
            print(f"{name}GET /api/jobs: {size} bytes, median {statistics.median(api):.1f} ms "
                  f"(runs: {', '.join(f'{x:.1f}' for x in api)})")

            driver_port = free_port()
            processes.append(subprocess.Popen(["chromedriver", f"--port={driver_port}"],
                                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
            nonlocal driver
            driver = WebDriver(driver_port)
            for _ in range(100):
                try:
                    if driver.call("GET", "/status", timeout=5)["ready"]:
                        break
                except (OSError, RuntimeError):
                    time.sleep(0.1)
            driver.start(work)
            shown, ready, complete = [], [], []
            for run in range(args.runs + 1):
                driver.go("about:blank")
                driver.go(page)
                for _ in range(600):
                    mark = driver.js("return document.body.dataset.listShownMs")
                    if mark:
                        break
                    time.sleep(0.05)
                rows = driver.js("return document.querySelectorAll('#jobs tbody tr').length")
                assert rows == args.jobs, f"{rows} rows for {args.jobs} jobs"
                loaded = driver.js("return performance.getEntriesByType('navigation')[0].loadEventEnd")
                # A page that lays its first rows out first marks when all are on screen too.
                whole = mark
                if driver.js("return typeof FIRST_ROWS !== 'undefined'"):
                    for _ in range(600):
                        whole = driver.js("return document.body.dataset.listCompleteMs")
                        if whole:
                            break
                        time.sleep(0.05)
                if run == 0:
                    continue  # the first load also starts the browser's caches: not counted
                shown.append(int(mark))
                complete.append(int(whole or mark))
                ready.append(loaded)
            driver.quit()
            driver = None
            print(f"{name}page with {args.jobs} jobs: list on screen after median {statistics.median(shown)} ms "
                  f"(runs: {', '.join(map(str, shown))}); all rows on screen after median "
                  f"{statistics.median(complete)} ms (runs: {', '.join(map(str, complete))}); "
                  f"load event at median {statistics.median(ready):.0f} ms")

        if not args.web_dir:
            measure(http_port, "")
        for web_dir in args.web_dir:
            server = servers.pop()
            server.terminate()
            server.wait(60)
            port, http_port = start_server(web_dir)
            measure(http_port, f"--web-dir {web_dir}: ")
        return 0
    finally:
        if driver is not None:
            driver.quit()
        for p in reversed(processes + servers):
            p.terminate()
            try:
                p.wait(20)
            except subprocess.TimeoutExpired:
                p.kill()
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
