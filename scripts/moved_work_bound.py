#!/usr/bin/env python3
"""How far could moving work into earlier frames lift each cell's 1% low? From a `gvdp bench
--json` file: for each cell, its measured 1% low as a share of its average FPS, and the most that
share could be if any part of any frame's time could be done in any earlier measured frame, at
no cost (a perfect prefetch of frames further ahead): the average frame time over the largest
prefix mean of frame times, the least slowest frame such a schedule can reach (the work of
frames 1..k cannot end before k frames of at least that mean). A cell whose bound is under the
target share cannot reach it by any schedule of the same work within its measured frames: its
heaviest frames come first.

Usage: scripts/moved_work_bound.py BENCH.json [--target SHARE]   (default 0.75: issue 14's)
A file it cannot read, or one without cells, is a one-line error with exit status 2.
"""
import argparse
import json
import sys


def bound(frame_ms):
    """(largest prefix mean of frame_ms, the prefix's length)."""
    best, length, total = 0.0, 0, 0.0
    for k, t in enumerate(frame_ms, start=1):
        total += t
        if total / k > best:
            best, length = total / k, k
    return best, length


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("bench")
    parser.add_argument("--target", type=float, default=0.75)
    a = parser.parse_args()
    try:
        with open(a.bench) as f:
            cells = json.load(f)["cells"]
        if not cells:
            raise ValueError("no cells")
        for c in cells:
            if not c["frame_ms"] or not all(isinstance(t, (int, float)) for t in c["frame_ms"]):
                raise ValueError(f"cell {c.get('scene')} {c.get('movement')}: no frame_ms")
    except (OSError, ValueError, KeyError, TypeError) as e:
        print(f"moved_work_bound: cannot read '{a.bench}': {e}", file=sys.stderr)
        sys.exit(2)
    reach = 0
    print(f"{'cell':40s} {'1% low/avg':>10s} {'bound':>6s}  prefix")
    for c in cells:
        t = c["frame_ms"]
        mean = sum(t) / len(t)
        prefix, k = bound(t)
        share, limit = mean / max(t), mean / prefix
        reach += limit >= a.target
        name = f"{c['scene']} {c['movement']} {c['scheduler']}"
        print(f"{name:40s} {share:10.2f} {limit:6.2f}  {k}")
    print(f"cells whose bound reaches {a.target:.2f}: {reach} of {len(cells)}")


if __name__ == "__main__":
    main()
