#!/usr/bin/env python3
"""One frame's time and idle, run after run: `gvdp timeline` of the same frame by several gvdp
binaries, interleaved run by run (binary A, B, ..., then A again), and per scene and binary the
median and range of the frame's time, its timeline's span and its idle share (SM-time with no
record open, as gvdp's summary line gives it and scripts/timeline_tail.py splits it). A frame's
idle varies from run to run by points (perlin's walkthrough frame 12 on an H200: 10.1-12.2% over
6 runs of one binary, BENCHMARKS.md session 56), so one run says little. A run that hangs ends
in GVDP_WATCHDOG_S seconds (60 unless set: base/watchdog.h).

Usage: scripts/frame_idle.py [--runs N] [--scenes A,B] [--frame F] [--again] [--movement M]
                             [--scheduler S] [--backend B] [--size WxH] [LABEL=]BIN...
A binary without a label is named by its folder (carry/off/gvdp: off), as scripts/ab_gpu.sh
names them. Bad arguments, or a binary that is not there, are a one-line error with exit status 2;
a run that fails is a line naming it, and the exit status is then 1.
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile

SUMMARY = re.compile(
    r"frame (\d+)(?: again)?: ([\d.]+) ms; timeline: ([\d.]+) ms.*; idle ([\d.]+)%")


def fail(message):
    """A one-line error naming the script that runs (frame_times.py uses it too), exit status 2."""
    name = os.path.splitext(os.path.basename(sys.argv[0]))[0] or "frame_idle"
    print(f"{name}: {message}", file=sys.stderr)
    sys.exit(2)


def parse_summary(text):
    """(frame ms, span ms, idle %) from gvdp timeline's summary line, or None."""
    m = SUMMARY.search(text)
    return (float(m.group(2)), float(m.group(3)), float(m.group(4))) if m else None


def spread(values, digits, unit):
    """'median unit (lowest-highest)' of values, with `digits` decimals."""
    return (f"{statistics.median(values):.{digits}f}{unit} "
            f"({min(values):.{digits}f}-{max(values):.{digits}f})")


def binaries(specs):
    out = []
    for spec in specs:
        label, _, path = spec.rpartition("=")
        label = label or os.path.basename(os.path.dirname(os.path.abspath(path))) or path
        if not (os.path.isfile(path) and os.access(path, os.X_OK)):
            fail(f"not an executable gvdp binary: '{path}'")
        out.append((label, path))
    if len({label for label, _ in out}) != len(out):
        fail(f"two binaries with one label: {', '.join(label for label, _ in out)} "
             "(name them LABEL=BIN)")
    return out


def common_arguments(ap, runs):
    """The arguments of this script and frame_times.py: the binaries, runs of each, and what
    they render."""
    ap.add_argument("bins", nargs="+", metavar="[LABEL=]BIN")
    ap.add_argument("--runs", type=int, default=runs, help=f"runs of each binary ({runs})")
    ap.add_argument("--movement", default="walkthrough")
    ap.add_argument("--scheduler", default="pt")
    ap.add_argument("--backend", default="cuda")
    ap.add_argument("--size", default="", help="WxH (default: gvdp's for the backend)")


def common_values(a):
    """Those arguments checked: gvdp's size arguments and the (label, path) binaries."""
    if a.runs < 1:
        fail(f"bad --runs {a.runs} (expected N >= 1)")
    size = []
    if a.size:
        m = re.fullmatch(r"(\d+)x(\d+)", a.size)
        if not m:
            fail(f"bad --size '{a.size}' (expected WxH)")
        size = ["--width", m.group(1), "--height", m.group(2)]
    return size, binaries(a.bins)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    common_arguments(ap, 6)
    ap.add_argument("--scenes", default="perlin,random-spheres")
    ap.add_argument("--frame", type=int, default=12, help="the frame timed (12)")
    ap.add_argument("--again", action="store_true",
                    help="time the frame's pose rendered once more from the cache it filled (the "
                         "render-only frame: gvdp timeline --again)")
    a = ap.parse_args()
    if a.frame < 0:
        fail(f"bad --frame {a.frame} (expected F >= 0)")
    size, bins = common_values(a)
    scenes = [s for s in a.scenes.split(",") if s]
    if not scenes:
        fail(f"bad --scenes '{a.scenes}' (expected a comma-separated list)")
    os.environ.setdefault("GVDP_WATCHDOG_S", "60")
    frame = f"frame {a.frame}" + (" again" if a.again else "")
    status = 0
    with tempfile.TemporaryDirectory() as d:
        for scene in scenes:
            got = {label: [] for label, _ in bins}
            for run in range(a.runs):
                for label, path in bins:
                    cmd = [path, "timeline", "--backend", a.backend, "--scheduler", a.scheduler,
                           "--scene", scene, "--movement", a.movement, "--frame", str(a.frame),
                           "--out", os.path.join(d, "t.png"), *size,
                           *(["--again"] if a.again else [])]
                    r = subprocess.run(cmd, capture_output=True, text=True)
                    values = parse_summary(r.stdout) if r.returncode == 0 else None
                    if values is None:
                        last = (r.stderr.strip().splitlines() or ["no summary line"])[-1]
                        print(f"{scene} {label} run {run + 1}: failed (exit {r.returncode}): "
                              f"{last}")
                        status = 1
                        continue
                    got[label].append(values)
            for label, _ in bins:
                v = got[label]
                if not v:
                    continue
                ms, span, idle = ([x[k] for x in v] for k in range(3))
                print(f"{scene} {label}: {len(v)} runs, {frame} {spread(ms, 2, ' ms')}, "
                      f"span {spread(span, 2, ' ms')}, idle {spread(idle, 1, '%')}", flush=True)
    sys.exit(status)


if __name__ == "__main__":
    main()
