#!/usr/bin/env python3
"""Each frame's time of a walk, run after run: `gvdp render` of the same walk by several gvdp
binaries, interleaved run by run (binary A, B, ..., then A again), read from stats.json. A line a
run: frame 0 (from an empty cache) with its spike flag and longest wait list (pt on the GPU), the
later frames' mean and slowest (which one), their over-production (bricks produced and never
sampled) and an md5 of the run's images; with --list, every frame's ms too; with --table, a table
of stats.json fields a frame (those of --span). Then a line a binary:
the medians and ranges over its runs, and whether every run of every binary rendered the same
images (the schedulers' and the optimisations' rule: an image that changes is a bug). The tool
sessions 57-60 rebuilt by hand for the sphere walks' exit frames and perlin's frame 0, and the
tables session 60 printed of the far prefetch's frames, e.g.
  --table ms,bricks_requested,prefetch_rays,prefetch_claims,relaunched_rays,spike --span 8-19

Usage: scripts/frame_times.py [--runs N] [--scene S] [--movement M] [--frames N] [--list]
                              [--table FIELD,...] [--span A-B]
                              [--scheduler S] [--backend B] [--size WxH] [LABEL=]BIN...
A binary without a label is named by its folder, as scripts/frame_idle.py names them. Bad
arguments, a binary that is not there or a --table field stats.json does not have, are a
one-line error with exit status 2; a run that
fails is a line naming it, and the exit status is then 1; so are images that differ.
"""
import argparse
import hashlib
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from frame_idle import common_arguments, common_values, fail, spread  # noqa: E402


def run_line(frames):
    """The figures of one run from stats.json's frames: frame 0's ms, spike and longest wait
    list; the later frames' mean and slowest ms, its index, and their over-production in %."""
    first = frames[0]
    later = frames[1:] or frames
    ms = [f["ms"] for f in later]
    slowest = max(range(len(ms)), key=lambda i: ms[i])
    produced = sum(f["bricks_produced"] for f in later)
    unsampled = sum(f["bricks_unsampled"] for f in later)
    return {"first": first["ms"], "spike": bool(first.get("spike", False)),
            "longest": first.get("longest_wait_list", 0), "mean": sum(ms) / len(ms),
            "max": ms[slowest], "max_at": later[slowest]["index"],
            "over": 100.0 * unsampled / produced if produced else 0.0,
            "unfinished": sum(f["unfinished_pixels"] for f in frames)}


def span_of(text, frames):
    """The frames a table shows: 'A-B' (both in the walk, A <= B), or all of them."""
    if not text:
        return 0, frames - 1
    parts = text.split("-")
    if len(parts) != 2 or not all(p.isdigit() for p in parts):
        fail(f"bad --span '{text}' (expected A-B, frame numbers)")
    a, b = int(parts[0]), int(parts[1])
    if a > b or b >= frames:
        fail(f"bad --span '{text}' (expected A <= B < --frames {frames})")
    return a, b


def table(frames, fields, first, last):
    """Lines of a table: a frame a row, its index and `fields` from stats.json."""
    names = ["frame", *fields]
    width = [max(8, len(n)) for n in names]

    def cell(v):
        return f"{v:.2f}" if isinstance(v, float) else str(int(v))

    rows = [names] + [[cell(f["index"]), *(cell(f[k]) for k in fields)]
                      for f in frames if first <= f["index"] <= last]
    return ["  " + " ".join(c.rjust(w) for c, w in zip(r, width)) for r in rows]


def images_md5(folder):
    h = hashlib.md5()
    for name in sorted(os.listdir(folder)):
        if name.endswith(".png"):
            with open(os.path.join(folder, name), "rb") as f:
                h.update(f.read())
    return h.hexdigest()[:12]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    common_arguments(ap, 3)
    ap.add_argument("--scene", default="aligned-spheres")
    ap.add_argument("--frames", type=int, default=34, help="frames of the walk (34)")
    ap.add_argument("--list", action="store_true", help="every frame's ms on each run's line")
    ap.add_argument("--table", default="", help="stats.json fields (comma-separated): a table "
                    "of them a frame after each run's line")
    ap.add_argument("--span", default="", help="A-B: the frames the table shows (default: all)")
    a = ap.parse_args()
    if a.frames < 1:
        fail(f"bad --frames {a.frames} (expected N >= 1)")
    fields = [k for k in a.table.split(",") if k] if a.table else []
    if a.table and (not fields or len(fields) != len(a.table.split(","))):
        fail(f"bad --table '{a.table}' (expected stats.json fields, comma-separated)")
    first, last = span_of(a.span, a.frames)
    size, bins = common_values(a)
    os.environ.setdefault("GVDP_WATCHDOG_S", "60")
    status = 0
    got = {label: [] for label, _ in bins}
    md5s = set()
    walk = f"{a.scene} {a.movement}"
    with tempfile.TemporaryDirectory() as d:
        for run in range(a.runs):
            for label, path in bins:
                out = os.path.join(d, f"{label}_{run}")
                cmd = [path, "render", "--backend", a.backend, "--scheduler", a.scheduler,
                       "--scene", a.scene, "--movement", a.movement, "--frames", str(a.frames),
                       "--out", out, *size]
                r = subprocess.run(cmd, capture_output=True, text=True)
                if r.returncode != 0:
                    last = (r.stderr.strip().splitlines() or ["no message"])[-1]
                    print(f"{walk} {label} run {run + 1}: failed (exit {r.returncode}): {last}",
                          flush=True)
                    status = 1
                    continue
                with open(os.path.join(out, "stats.json")) as f:
                    frames = json.load(f)["frames"]
                for k in fields:
                    if k not in frames[0]:
                        fail(f"bad --table field '{k}' (stats.json's frames have: "
                             f"{', '.join(sorted(frames[0]))})")
                v = run_line(frames)
                v["md5"] = images_md5(out)
                md5s.add(v["md5"])
                got[label].append(v)
                listed = " | " + " ".join(f"{f['ms']:.1f}" for f in frames) if a.list else ""
                print(f"{walk} {label} run {run + 1}: frame 0 {v['first']:.1f} ms"
                      f"{' (spike)' if v['spike'] else ''}, longest wait list {v['longest']}; "
                      f"then mean {v['mean']:.2f} ms, slowest {v['max']:.2f} ms (frame "
                      f"{v['max_at']}), over-production {v['over']:.1f}%, unfinished "
                      f"{v['unfinished']}, images {v['md5']}{listed}", flush=True)
                if fields:
                    print("\n".join(table(frames, fields, first, last)), flush=True)
    for label, _ in bins:
        v = got[label]
        if not v:
            continue
        pick = lambda k: [x[k] for x in v]  # noqa: E731
        print(f"{walk} {label}: {len(v)} runs, frame 0 {spread(pick('first'), 1, ' ms')}, "
              f"mean {spread(pick('mean'), 2, ' ms')}, slowest {spread(pick('max'), 2, ' ms')}, "
              f"over-production {spread(pick('over'), 1, '%')}", flush=True)
    if len(md5s) > 1:
        print(f"images differ: {len(md5s)} md5s over the runs ({', '.join(sorted(md5s))})")
        status = 1
    elif md5s:
        print(f"images: the same in every run ({md5s.pop()})")
    sys.exit(status)


if __name__ == "__main__":
    main()
