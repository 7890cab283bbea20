#!/usr/bin/python3
"""The web console (membraned --http-listen) in a real browser: headless Chromium, driven by
chromedriver over the WebDriver protocol (plain HTTP and JSON: no Selenium), against a live
membraned with tokens. The page is loaded before any job exists and asks for the token; the test
then submits jobs with the membrane client and checks, in the page: the job's row, its progress
as it runs (the stages and generations tables growing), the mesh drawn in the 3D canvas (a
screenshot of the canvas: pixels of both shells' colours, not all background), the input points
overlaid, the .ply download (the file the browser saved is the API's bytes), and cancel (of a
job held in its decode by a gated decoder, as the C++ server tests hold theirs:
tests/server/gated_decoder.h).

Usage: web_console_test.py SOURCE_DIR MEMBRANED MEMBRANE [--screenshot PNG]
Exit 77 (ctest: skipped) with a message when chromedriver or Chromium cannot start.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from webdriver_client import WebDriver, decode_png, free_port, hue_family  # noqa: E402

SKIP = 77
BACKGROUND = (0x20, 0x26, 0x2F)  # the viewer's clear colour (console.js)
SHELL_BLUE, SHELL_ORANGE = (0x6F, 0xA8, 0xDC), (0xE6, 0x91, 0x38)  # shells 0 and 1
TOKEN = "tok-station-1"


def wait_for(what, predicate, seconds, step=0.1):
    """Polls `predicate` until it returns a true value (returned) or `seconds` pass (fails)."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        value = predicate()
        if value:
            return value
        time.sleep(step)
    raise AssertionError(f"timed out after {seconds} s waiting for {what}")


def gated_decoder(work, decoder):
    """A decoder for membraned's --decoder_path that holds each decode until a line is written
    to its gate, a FIFO: the script opens the gate read-write (so that the open does not wait
    for a writer), reads one line, then runs `decoder` with its arguments and input. Returns the
    script's path and the gate, open read-write: a line written waits in the FIFO for the next
    decode. A held job is running, in its decode stage, for as long as the test wants."""
    gate = os.path.join(work, "decode.gate")
    os.mkfifo(gate, 0o600)
    script = os.path.join(work, "gated-decode.sh")
    with open(script, "w") as f:
        f.write(f"#!/bin/sh\nexec 3<>'{gate}'\nread line <&3\nexec 3<&-\nexec '{decoder}' \"$@\"\n")
    os.chmod(script, 0o700)
    return script, os.open(gate, os.O_RDWR)


def row(driver, job_id):
    """The job's row in the page's table: its cells' text, state and action links."""
    return driver.js("""
        const row = document.getElementById('job-' + arguments[0]);
        if (!row) return null;
        return {state: row.dataset.state, cells: [...row.cells].map(c => c.textContent),
                actions: [...row.querySelectorAll('a.download, button.cancel')].map(e => e.textContent),
                preview: !!row.querySelector('img.preview')};""", job_id)


def progress(driver):
    """The selected job's progress as the page shows it: rows of the stages and generations
    tables, and the state it names."""
    return driver.js("""return {
        stages: document.querySelectorAll('#stages tbody tr').length,
        generations: document.querySelectorAll('#generations tbody tr').length,
        state: document.getElementById('detail-state').textContent};""")


def main():
    if len(sys.argv) < 4:
        print(__doc__)
        return 2
    membraned, membrane = sys.argv[2], sys.argv[3]
    screenshot = sys.argv[sys.argv.index("--screenshot") + 1] if "--screenshot" in sys.argv else None
    chromedriver = shutil.which("chromedriver")
    if chromedriver is None or not (shutil.which("chromium") or os.path.exists("/usr/bin/chromium")):
        print("SKIP: chromium and chromedriver are not installed (deploy/install-deps.sh test)")
        return SKIP
    work = tempfile.mkdtemp(prefix="web-console-test-")
    downloads = os.path.join(work, "downloads")
    os.mkdir(downloads)
    with open(os.path.join(work, "tokens"), "w") as f:
        f.write(f"station-1 {TOKEN}\n")
    with open(os.path.join(work, "token"), "w") as f:
        f.write(TOKEN + "\n")
    processes = []
    driver = None
    decoder, gate = gated_decoder(work, os.path.join(os.path.dirname(membraned), "membrane-decode"))
    try:
        log = open(os.path.join(work, "membraned.log"), "w+")
        server = subprocess.Popen([membraned, "--listen=127.0.0.1:0", "--http-listen=127.0.0.1:0",
                                   "--workers=1", "--token-file=" + os.path.join(work, "tokens"),
                                   "--decoder_path=" + decoder],
                                  stderr=log)
        processes.append(server)

        def started():
            log.seek(0)
            m = re.search(r"event=server_started .* port=(\d+) .* http_port=(\d+)", log.read())
            return m and (int(m.group(1)), int(m.group(2)))
        grpc_port, http_port = wait_for("membraned to start", started, 30)
        page = f"http://127.0.0.1:{http_port}/"

        driver_port = free_port()
        processes.append(subprocess.Popen([chromedriver, f"--port={driver_port}"],
                                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        driver = WebDriver(driver_port)

        def driver_ready():
            try:
                return driver.call("GET", "/status", timeout=5)["ready"]
            except (OSError, RuntimeError):  # not listening yet
                return False
        try:
            wait_for("chromedriver", driver_ready, 20)
            driver.start(downloads)
        except Exception as e:  # no browser here: say so and skip, as the other optional tools do
            print(f"SKIP: Chromium cannot start under chromedriver: {e}")
            return SKIP

        # The page before any job: it asks for the token once, then lists nothing.
        started_at = time.monotonic()
        driver.go(page)
        wait_for("the token form", lambda: driver.js(
            "return !document.getElementById('token-form').hidden"), 10)
        driver.js("""document.getElementById('token').value = arguments[0];
                     document.querySelector('#token-form button').click();""", TOKEN)
        wait_for("the empty job list", lambda: driver.js(
            "return !document.getElementById('no-jobs').hidden"), 10)
        print(f"page loaded and authenticated in {time.monotonic() - started_at:.2f} s")

        # A job of two spheres that runs for a few seconds: its row appears, and selected, its
        # stages and generations arrive while it runs. Its decode goes through the gate at once.
        os.write(gate, b"go\n")
        cloud = os.path.join(work, "two.ply")
        subprocess.run([membrane, "synth", "two-spheres", "--points", "40000", "-o", cloud],
                       check=True, stdout=subprocess.DEVNULL)
        client = subprocess.Popen([membrane, "reconstruct", cloud, "-o", os.path.join(work, "two.drc"),
                                   "--server", f"127.0.0.1:{grpc_port}", "--voxel-size", "0.016",
                                   "--token-file", os.path.join(work, "token"), "-q"],
                                  stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        processes.append(client)
        job_id = wait_for("the job's row", lambda: driver.js(
            "const r = document.querySelector('#jobs tbody tr'); return r && r.dataset.id;"), 30)
        first = row(driver, job_id)
        print(f"job {job_id} row: {first['cells'][1:5]}")
        assert first["cells"][2] == "station-1", first
        assert first["state"] in ("QUEUED", "RUNNING", "SUCCEEDED"), first
        driver.js("document.getElementById('job-' + arguments[0]).click()", job_id)
        seen = []
        end = time.monotonic() + 120
        while True:
            now = progress(driver)
            if not seen or (now["stages"], now["generations"]) != (seen[-1]["stages"],
                                                                   seen[-1]["generations"]):
                seen.append(now)
            if now["state"] in ("SUCCEEDED", "FAILED", "CANCELLED"):
                break
            assert time.monotonic() < end, f"the job did not end within 120 s: {seen}"
            time.sleep(0.05)
        print("progress seen: " + ", ".join(f"{p['stages']} stages/{p['generations']} generations"
                                            for p in seen))
        running = [p for p in seen if p["state"] not in ("SUCCEEDED", "FAILED", "CANCELLED")]
        assert len(running) >= 2, f"the page showed no progress while the job ran: {seen}"
        assert now["state"] == "SUCCEEDED", now
        # The list may report the end before the events request brings the last stages.
        final = wait_for("the last stages", lambda: (lambda p: p if p["stages"] >= 6 else None)(
            progress(driver)), 30)
        assert final["generations"] >= 5, final
        assert client.wait(60) == 0, client.stderr.read().decode()

        # The mesh in the 3D view: two shells in their two colours.
        wait_for("the mesh in the viewer", lambda: driver.js(
            "return document.body.dataset.meshShown") == job_id, 60)
        assert driver.js("return document.body.dataset.meshShells") == "2"
        width, height, pixels = decode_png(driver.element_png("#canvas"))
        drawn = [px for line in pixels for px in line
                 if max(abs(px[k] - BACKGROUND[k]) for k in range(3)) > 8]
        families = {hue_family(px) for px in drawn if max(px) - min(px) > 40}
        share = len(drawn) / (width * height)
        print(f"canvas {width}x{height}: {share:.1%} of pixels drawn, hue families {sorted(families)}")
        assert share > 0.05, "the 3D canvas is all background"
        assert {hue_family(SHELL_BLUE), hue_family(SHELL_ORANGE)} <= families, families

        # The row now: SUCCEEDED, downloads, its preview. Then the input points over the mesh, on
        # demand, and the .ply link, which saves the API's bytes.
        done = wait_for("the finished row with its preview", lambda: (
            lambda r: r if r and r["state"] == "SUCCEEDED" and r["preview"] else None)(
                row(driver, job_id)), 30)
        assert done["actions"] == [".drc", ".ply"], done
        if screenshot:
            with open(screenshot, "wb") as f:
                f.write(driver.page_png())
            print(f"screenshot: {screenshot}")
        driver.js("document.getElementById('show-points').click()")
        points = wait_for("the input points", lambda: driver.js(
            "return document.body.dataset.pointsShown"), 30)
        assert int(points) == 20000, points  # the sample of the 40000 (server/point_sample.h)

        driver.js("document.querySelector('#job-' + arguments[0] + ' a[data-ext=ply]').click()", job_id)
        saved = os.path.join(downloads, job_id + ".ply")
        wait_for("the downloaded .ply", lambda: os.path.exists(saved) and not any(
            n.endswith(".crdownload") for n in os.listdir(downloads)), 30)
        request = urllib.request.Request(f"{page}api/jobs/{job_id}/mesh.ply",
                                         headers={"Authorization": "Bearer " + TOKEN})
        with urllib.request.urlopen(request, timeout=30) as response:
            expected = response.read()
        with open(saved, "rb") as f:
            got = f.read()
        assert got == expected, f"the download has {len(got)} bytes, the API {len(expected)}"
        print(f"download {job_id}.ply: {len(got)} bytes, the API's")

        # A job held in its decode (nothing is written to the gate for it), cancelled with its
        # row's button: membraned kills the held decoder.
        held = subprocess.Popen([membrane, "reconstruct", cloud, "-o", os.path.join(work, "held.drc"),
                                 "--server", f"127.0.0.1:{grpc_port}",
                                 "--token-file", os.path.join(work, "token"), "-q"],
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        processes.append(held)
        held_id = wait_for("the held job's row", lambda: (lambda i: i if i != job_id else None)(
            driver.js("const r = document.querySelector('#jobs tbody tr'); return r && r.dataset.id;")), 30)
        wait_for("its cancel button", lambda: (row(driver, held_id) or {}).get("actions") == ["cancel"], 30)
        driver.js("document.querySelector('#job-' + arguments[0] + ' button.cancel').click()", held_id)
        wait_for("the cancelled row", lambda: (row(driver, held_id) or {}).get("state") == "CANCELLED", 30)
        assert held.wait(60) == 5, held.stderr.read().decode()
        print(f"job {held_id} cancelled from the page")
        print("PASS")
        return 0
    finally:
        # A decode still at the gate (a failed run's) goes on, to find its input closed.
        os.write(gate, b"go\n" * 4)
        os.close(gate)
        if driver is not None:
            driver.quit()
        for p in reversed(processes):
            if p.poll() is None:
                p.terminate()
                try:
                    p.wait(20)
                except subprocess.TimeoutExpired:
                    p.kill()
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
