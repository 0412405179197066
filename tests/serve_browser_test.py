#!/usr/bin/env python3
"""The viewer in a real browser: starts `gvdp serve` (CPU backend, small frames) on a free loopback
port, drives its page in headless Chromium (Debian's chromium-headless-shell, over the DevTools
protocol on a pipe: no extra package), presses keys and drags, and asserts from screenshots and
from the stats endpoint that frames arrive and the camera moved; then sends malformed requests and
checks the server still serves, and that SIGTERM stops it cleanly.

usage: serve_browser_test.py --gvdp BIN [--screenshots DIR] [--backend cpu] [--width W --height H]
Exit 0: passed; 1: failed; 77: no chromium-headless-shell (skipped)."""
import argparse
import base64
import json
import os
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
import zlib


def fail(message):
    print(f"FAIL: {message}", flush=True)
    raise SystemExit(1)


def check(condition, message):
    if not condition:
        fail(message)
    print(f"ok: {message}", flush=True)


def decode_png(data):
    """RGB(A) 8-bit non-interlaced PNG (what Chromium writes) -> (width, height, channels, rows)."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, color, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and color in (2, 6) and interlace == 0, "unexpected PNG format"
            channels = 3 if color == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw, stride, rows, prev = zlib.decompress(idat), width * channels, [], bytearray(width * channels)
    for y in range(height):
        start = y * (stride + 1)
        kind, line = raw[start], bytearray(raw[start + 1:start + 1 + stride])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = prev[i]
            c = prev[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return width, height, channels, rows


def region(png, rect):
    """The RGB values of a rectangle (x, y, w, h in CSS pixels = screenshot pixels)."""
    width, height, channels, rows = decode_png(png)
    x0, y0 = max(0, int(rect["x"])), max(0, int(rect["y"]))
    x1, y1 = min(width, int(rect["x"] + rect["width"])), min(height, int(rect["y"] + rect["height"]))
    return [tuple(rows[y][x * channels:x * channels + 3]) for y in range(y0, y1) for x in range(x0, x1)]


class Browser:
    """Chromium's DevTools protocol over --remote-debugging-pipe (fd 3 in, fd 4 out)."""

    def __init__(self, binary, profile):
        to_chrome, self.out = os.pipe()
        self.inp, from_chrome = os.pipe()

        def fds():
            a, b = os.dup(to_chrome), os.dup(from_chrome)
            os.dup2(a, 3)
            os.dup2(b, 4)

        self.proc = subprocess.Popen(
            [binary, "--remote-debugging-pipe", "--no-sandbox", "--disable-gpu",
             "--no-first-run", f"--user-data-dir={profile}", "--window-size=1280,800",
             "about:blank"],
            preexec_fn=fds, close_fds=False, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_chrome)
        os.close(from_chrome)
        self.next_id, self.buffer, self.session, self.events = 0, b"", None, []
        target = self.call("Target.createTarget", url="about:blank")["targetId"]
        self.session = self.call("Target.attachToTarget", targetId=target, flatten=True)["sessionId"]
        self.call("Page.enable")
        self.call("Emulation.setDeviceMetricsOverride", width=1280, height=800,
                  deviceScaleFactor=1, mobile=False)

    def message(self):
        while b"\0" not in self.buffer:
            chunk = os.read(self.inp, 1 << 16)
            if not chunk:
                fail("the browser closed its pipe")
            self.buffer += chunk
        text, self.buffer = self.buffer.split(b"\0", 1)
        return json.loads(text)

    def call(self, method, **params):
        self.next_id += 1
        request = {"id": self.next_id, "method": method, "params": params}
        if self.session:
            request["sessionId"] = self.session
        os.write(self.out, json.dumps(request).encode() + b"\0")
        while True:
            m = self.message()
            if m.get("id") == self.next_id:
                if "error" in m:
                    fail(f"{method}: {m['error']}")
                return m.get("result", {})
            self.events.append(m)

    def evaluate(self, expression, errors_are_false=False):
        r = self.call("Runtime.evaluate", expression=expression, returnByValue=True,
                      awaitPromise=True)
        if "exceptionDetails" in r:
            if errors_are_false:
                return False
            fail(f"page error in {expression!r}: {r['exceptionDetails']}")
        return r["result"].get("value")

    def wait_for(self, expression, what, seconds=90):
        """The expression's value once it is truthy."""
        end = time.time() + seconds
        while time.time() < end:
            # The page may still be loading (no element yet): that is not ready, not an error.
            value = self.evaluate(expression, errors_are_false=True)
            if value:
                return value
            time.sleep(0.2)
        fail(f"timed out waiting for {what} ({expression})")

    def key(self, kind, code, key, vk):
        self.call("Input.dispatchKeyEvent", type=kind, code=code, key=key,
                  windowsVirtualKeyCode=vk, nativeVirtualKeyCode=vk)

    def mouse(self, kind, x, y, buttons=0):
        self.call("Input.dispatchMouseEvent", type=kind, x=x, y=y, button="left",
                  buttons=buttons, clickCount=1 if kind != "mouseMoved" else 0)

    def screenshot(self):
        return base64.b64decode(self.call("Page.captureScreenshot", format="png")["data"])

    def close(self):
        self.proc.kill()
        self.proc.wait()


def http(url, method="GET"):
    """(status, body) of a request; HTTP errors are answers too."""
    request = urllib.request.Request(url, method=method, data=b"" if method == "POST" else None)
    try:
        with urllib.request.urlopen(request, timeout=30) as r:
            return r.status, r.read()
    except urllib.error.HTTPError as e:
        return e.code, e.read()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--gvdp", required=True)
    parser.add_argument("--screenshots", default="")
    parser.add_argument("--backend", default="cpu")
    parser.add_argument("--width", type=int, default=160)
    parser.add_argument("--height", type=int, default=100)
    args = parser.parse_args()
    chromium = shutil.which("chromium-headless-shell") or shutil.which("chromium")
    if not chromium:
        print("SKIP: no chromium-headless-shell (scripts/setup.sh installs it)")
        return 77
    work = tempfile.mkdtemp(prefix="gvdp_serve_browser_")
    server = subprocess.Popen(
        [args.gvdp, "serve", "--port", "0", "--backend", args.backend, "--scheduler", "sp",
         "--width", str(args.width), "--height", str(args.height)],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    browser = None
    try:
        banner = server.stdout.readline()
        print(banner.strip(), flush=True)
        check("http://127.0.0.1:" in banner, "the server binds to loopback and prints its address")
        base = banner[banner.index("http://"):].split()[0].rstrip("/")
        browser = Browser(chromium, os.path.join(work, "profile"))
        browser.call("Page.navigate", url=base + "/")
        browser.wait_for(f"document.getElementById('view').naturalWidth === {args.width}",
                         "the first frame on the page")
        browser.wait_for("document.getElementById('overlay').textContent.includes('FPS')",
                         "the overlay's figures")
        # The picture's rectangle inside its box (object-fit: contain), once the picture has a size
        # and a box: between two frames (a new one decoding) it may have neither for a moment, and
        # under load (CI, 2 cores shared with a render) the rectangle once came back as NaN.
        rect = browser.wait_for(
            "(() => { const v = document.getElementById('view'), r = v.getBoundingClientRect();"
            " if (!v.naturalWidth || !v.naturalHeight || !r.width || !r.height) return null;"
            " const s = Math.min(r.width / v.naturalWidth, r.height / v.naturalHeight);"
            " const w = v.naturalWidth * s, h = v.naturalHeight * s;"
            " return {x: r.x + (r.width - w) / 2, y: r.y + (r.height - h) / 2, width: w, height: h};"
            " })()", "the picture's rectangle")
        shot_a = browser.screenshot()
        pixels_a = region(shot_a, rect)
        check(len(set(pixels_a)) > 50, f"the frame on the page is a picture ({len(set(pixels_a))} colours)")
        stats0 = json.loads(http(base + "/api/stats")[1])

        # Drive: click the picture, hold W for 2 s, drag to the right.
        cx, cy = rect["x"] + rect["width"] / 2, rect["y"] + rect["height"] / 2
        browser.mouse("mousePressed", cx, cy, 1)
        browser.mouse("mouseReleased", cx, cy)
        browser.key("keyDown", "KeyW", "w", 87)
        time.sleep(2.0)
        browser.key("keyUp", "KeyW", "w", 87)
        browser.mouse("mousePressed", cx, cy, 1)
        for step in range(1, 11):
            browser.mouse("mouseMoved", cx + 12 * step, cy, 1)
        browser.mouse("mouseReleased", cx + 120, cy)
        # The seat is the page's while it sends input (and 3 s after).
        browser.wait_for("document.getElementById('role').textContent.includes('you drive')",
                         "the page saying it drives", seconds=2.5)
        frame_before = stats0["frame"]
        browser.wait_for(f"fetch('/api/stats').then(r => r.json()).then(s => s.frame > {frame_before} + 3)",
                         "frames after the input")
        time.sleep(1.0)
        stats1 = json.loads(http(base + "/api/stats")[1])
        c0, c1 = stats0["camera"], stats1["camera"]
        moved = ((c1["x"] - c0["x"]) ** 2 + (c1["y"] - c0["y"]) ** 2 + (c1["z"] - c0["z"]) ** 2) ** 0.5
        check(moved > 0.5, f"W moved the camera {moved:.2f} units")
        check(abs(c1["yaw"] - c0["yaw"]) > 0.2, f"the drag turned the camera {c1['yaw'] - c0['yaw']:+.2f} rad")
        check(stats1["unfinishedPixels"] == 0, "no unfinished pixels")
        shot_b = browser.screenshot()
        pixels_b = region(shot_b, rect)
        changed = sum(1 for a, b in zip(pixels_a, pixels_b) if a != b) / max(1, len(pixels_a))
        check(changed > 0.2, f"the picture changed after the input ({100 * changed:.0f}% of its pixels)")
        overlay = browser.evaluate("document.getElementById('overlay').textContent")
        for word in ("FPS", "bricks produced", "pool", "unfinished", "coarser", "input to frame"):
            check(word in overlay, f"the overlay shows '{word}'")

        # A second client watches: its input is refused while the page drives (holding a key).
        browser.key("keyDown", "KeyD", "d", 68)
        time.sleep(0.5)
        status, body = http(base + "/api/input?client=other&move=1,0,0", "POST")
        browser.key("keyUp", "KeyD", "d", 68)
        check(status == 409, f"a second client's input is refused while the page drives ({status} {body.decode().strip()})")

        # The timeline button shows the PNG of a frame's timeline.
        browser.evaluate("document.getElementById('timeline').click()")
        browser.wait_for("document.getElementById('timelinePanel').style.display === 'flex' && "
                         "document.getElementById('timelineImage').naturalWidth > 0",
                         "the timeline picture")
        shot_timeline = browser.screenshot()
        browser.evaluate("document.getElementById('timelinePanel').click()")

        # Settings from the page: another scene, a budget and a camera path.
        browser.evaluate("document.getElementById('scene').value = 'aligned-spheres';"
                         "document.getElementById('budget').value = '40';"
                         "document.getElementById('path').value = 'forward';"
                         "document.getElementById('apply').click()")
        browser.wait_for("fetch('/api/stats').then(r => r.json()).then(s => s.scene === "
                         "'aligned-spheres' && s.budgetMs === 40 && s.path === 'forward')",
                         "the scene, budget and camera path chosen on the page")

        # Malformed requests: 400 or 404 with one line, and the server still serves.
        for path, method, want in [
            ("/api/frame?after=abc", "GET", 400), ("/api/frame?after=1e99", "GET", 400),
            ("/api/view?client=x&width=100000", "POST", 400),
            ("/api/view?client=x&width=64&height=-3", "POST", 400),
            ("/api/view?client=x&scene=moon", "POST", 400),
            ("/api/input?client=x&move=nan,0,0", "POST", 400),
            ("/api/stats?client=../../x", "GET", 400), ("/api/frame?zzz=1", "GET", 400),
            ("/../../etc/passwd", "GET", 404), ("/%2e%2e/%2e%2e/etc/passwd", "GET", 404),
            ("/viewer.html", "GET", 404),
        ]:
            status, body = http(base + path, method)
            text = body.decode(errors="replace")
            check(status == want and text.count("\n") == 1,
                  f"{method} {path} -> {status} {text.strip()}")
        status, _ = http(base + "/api/frame?after=0")
        check(status == 200, "the server still serves frames")
        browser.wait_for("fetch('/api/stats').then(r => r.json()).then(s => s.frame > 0)", "frames")

        if args.screenshots:
            os.makedirs(args.screenshots, exist_ok=True)
            for name, data in [("viewer_before.png", shot_a), ("viewer_after.png", shot_b),
                               ("viewer_timeline.png", shot_timeline),
                               ("viewer_last.png", browser.screenshot())]:
                with open(os.path.join(args.screenshots, name), "wb") as f:
                    f.write(data)
    finally:
        if browser:
            browser.close()
        if server.poll() is None:
            server.send_signal(signal.SIGTERM)
            try:
                rest, _ = server.communicate(timeout=20)
            except subprocess.TimeoutExpired:
                server.kill()
                fail("the server did not stop within 20 s of SIGTERM")
            print(rest.strip(), flush=True)
        shutil.rmtree(work, ignore_errors=True)
    check(server.returncode == 0, f"SIGTERM stopped the server cleanly (exit status {server.returncode})")
    print("PASS", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
