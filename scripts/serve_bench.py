#!/usr/bin/env python3
"""A scripted viewer client: measures what `gvdp serve` delivers.

For each scene it starts `gvdp serve` on a free loopback port, warms up, then fetches frames as fast
as they come for --seconds while sending input every 250 ms, as the page does: with --path the
camera follows that camera path (the input moves nothing, so the path goes on; the frames are
the benchmark's), else the input holds the forward key.
It reports frames delivered per second against the frames the server's loop rendered in the same
window, the GPU-timed frame time (the renderer's FPS), input-to-frame latency (client side: input
sent to the first frame showing it arriving; server side: from /api/stats), and the same with a
slow client (one that takes 50 ms per frame), whose frames are dropped rather than queued.

usage: serve_bench.py --gvdp BIN [--backend cuda] [--scenes perlin,...] [--scheduler pt]
                      [--width 1500 --height 1000] [--seconds 10] [--budget-ms X] [--out FILE]"""
import argparse
import http.client
import json
import statistics
import subprocess
import sys
import threading
import time


def get(conn, path, method="GET"):
    conn.request(method, path, body=b"" if method == "POST" else None)
    r = conn.getresponse()
    return r.status, dict(r.getheaders()), r.read()


def measure(port, seconds, slow_ms, client, move):
    frames_conn = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
    input_conn = http.client.HTTPConnection("127.0.0.1", port, timeout=30)

    def stats_now():  # a connection of its own: an idle keep-alive one is closed after 2 s
        return json.loads(get(http.client.HTTPConnection("127.0.0.1", port, timeout=30),
                              f"/api/stats?client={client}")[2])
    sent, sent_lock = {}, threading.Lock()  # input seq -> time sent
    latencies, stop = [], threading.Event()

    def inputs():
        seq = 0
        while not stop.is_set():
            seq += 1
            with sent_lock:
                sent[seq] = time.perf_counter()
            status, _, body = get(input_conn, f"/api/input?client={client}&seq={seq}&move={move}", "POST")
            if status != 200:
                print("input refused:", status, body, file=sys.stderr)
            stop.wait(0.25)

    after, got, frame_ms, nbytes = 0, 0, [], 0
    before = stats_now()
    # Warm up: frames for 3 s (the first pool fill), then the measured window.
    warm_end = time.perf_counter() + 3.0
    while time.perf_counter() < warm_end:
        status, h, body = get(frames_conn, f"/api/frame?after={after}&client={client}")
        if status == 200:
            after = int(h["X-Frame"])
    thread = threading.Thread(target=inputs)
    thread.start()
    before = stats_now()
    start = time.perf_counter()
    end = start + seconds
    while time.perf_counter() < end:
        status, h, body = get(frames_conn, f"/api/frame?after={after}&client={client}")
        if status != 200:
            continue
        now = time.perf_counter()
        after = int(h["X-Frame"])
        shown_input = int(h["X-Input"])
        with sent_lock:
            for s in [s for s in sent if s <= shown_input]:
                latencies.append(1e3 * (now - sent.pop(s)))
        got += 1
        nbytes += len(body)
        frame_ms.append(float(h["X-Frame-Ms"]))
        if slow_ms:
            time.sleep(slow_ms / 1e3)
    stats = stats_now()
    elapsed = time.perf_counter() - start
    stop.set()
    thread.join()
    dropped = stats["dropped"] - before["dropped"]
    # The renderer's own times over the frames the loop rendered in the window (GPU-timed on
    # cuda; the wall time of its call).
    frames = stats["frame"] - before["frame"]
    renderer_ms = (stats["frameMsTotal"] - before["frameMsTotal"]) / max(1, frames)
    call_ms = (stats["renderCallMsTotal"] - before["renderCallMsTotal"]) / max(1, frames)
    return {
        "slow_client_ms": slow_ms,
        "seconds": elapsed,
        "frames_delivered": got,
        "frames_rendered": frames,
        "delivered_fps": got / elapsed,
        "loop_fps": frames / elapsed,
        "delivered_over_rendered": got / max(1, frames),
        "renderer_frame_ms_mean": renderer_ms,
        "renderer_fps": 1e3 / renderer_ms if renderer_ms else None,
        "delivered_over_renderer_fps": got / elapsed * renderer_ms / 1e3 if renderer_ms else None,
        "jpeg_kb_mean": nbytes / max(1, got) / 1024,
        "latency_client_ms_median": statistics.median(latencies) if latencies else None,
        "latency_server_ms_median": stats["latencyMs"],
        "dropped_by_loop": dropped,
        "render_call_ms_mean": call_ms,
        "renderer_wall_fps": 1e3 / call_ms if call_ms else None,
        "unfinished_pixels_last": stats["unfinishedPixels"],
    }


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--gvdp", required=True)
    p.add_argument("--backend", default="cuda")
    p.add_argument("--scenes", default="perlin,random-spheres,aligned-spheres")
    p.add_argument("--scheduler", default="pt")
    p.add_argument("--width", type=int, default=1500)
    p.add_argument("--height", type=int, default=1000)
    p.add_argument("--seconds", type=float, default=10.0)
    p.add_argument("--budget-ms", default="")
    p.add_argument("--path", default="walkthrough", help="a camera path, or free")
    p.add_argument("--out", default="")
    p.add_argument("--timeline-dir", default="", help="also save each scene's timeline PNG here")
    a = p.parse_args()
    results = []
    for scene in a.scenes.split(","):
        cmd = [a.gvdp, "serve", "--port", "0", "--backend", a.backend, "--scene", scene,
               "--scheduler", a.scheduler, "--width", str(a.width), "--height", str(a.height)]
        if a.budget_ms:
            cmd += ["--budget-ms", a.budget_ms]
        cmd += ["--path", a.path]
        server = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        banner = server.stdout.readline()
        print(banner.strip(), flush=True)
        port = int(banner.split("http://127.0.0.1:")[1].split("/")[0])
        for slow in (0, 50):
            r = measure(port, a.seconds if not slow else min(a.seconds, 5.0), slow, f"bench{slow}", "0,0,0" if a.path != "free" else "0,0,1")
            r.update(scene=scene, scheduler=a.scheduler, width=a.width, height=a.height,
                     budget_ms=a.budget_ms or None, path=a.path, server=banner.strip())
            results.append(r)
            print(json.dumps(r), flush=True)
            time.sleep(3.5)  # the driver's seat frees before the next client
        if a.timeline_dir:
            conn = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
            status, _, png = get(conn, "/api/timeline?client=timeline", "POST")
            print(f"timeline of {scene}: HTTP {status}, {len(png)} bytes", flush=True)
            if status == 200:
                with open(f"{a.timeline_dir}/serve_timeline_{scene}.png", "wb") as f:
                    f.write(png)
        server.terminate()
        server.wait(timeout=30)
    if a.out:
        with open(a.out, "w") as f:
            json.dump(results, f, indent=1)
    print("| scene | client | delivered FPS | loop FPS | renderer FPS (GPU-timed) | renderer FPS (wall, its call) | delivered / renderer GPU FPS | frames delivered / rendered | dropped by the loop | latency client / server ms | JPEG KB |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in results:
        print(f"| {r['scene']} | {'slow (50 ms)' if r['slow_client_ms'] else 'fast'} | "
              f"{r['delivered_fps']:.1f} | {r['loop_fps']:.1f} | {r['renderer_fps'] or 0:.1f} | "
              f"{r['renderer_wall_fps'] or 0:.1f} | "
              f"{r['delivered_over_renderer_fps'] or 0:.3f} | {r['delivered_over_rendered']:.3f} | "
              f"{r['dropped_by_loop']} | "
              f"{r['latency_client_ms_median'] or 0:.1f} / {r['latency_server_ms_median']:.1f} | "
              f"{r['jpeg_kb_mean']:.0f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
