#!/usr/bin/env python3
"""Joins scripts/ncu_lines.sh's two outputs: the share of a kernel's warp instructions and stall
samples per source line, and the lanes its instructions ran on.
Usage: scripts/ncu_lines.py sass_SCENE.csv.gz lines_SCENE.txt.gz [TOP]"""
import collections
import csv
import gzip
import sys

if len(sys.argv) < 3:
    sys.exit(__doc__)
rows = list(csv.reader(gzip.open(sys.argv[1], "rt")))
head = next(r for r in rows if r and r[0] == "Address")
data = [dict(zip(head, r)) for r in rows if len(r) == len(head) and r[0].startswith("0x")]
if not data:
    sys.exit(f"{sys.argv[1]}: no instructions")
base = int(data[0]["Address"], 16)
where = {}
for line in gzip.open(sys.argv[2], "rt"):
    parts = line.split(None, 1)
    if line.startswith("#") or not parts:
        continue
    where[int(parts[0], 16)] = parts[1].strip().split("/src/")[-1] if len(parts) > 1 else "?"


def count(d, key):
    return int(d[key].replace(",", ""))


warp, thread, stalls = collections.Counter(), collections.Counter(), collections.Counter()
for d in data:
    loc = where.get(int(d["Address"], 16) - base, "?")
    warp[loc] += count(d, "Instructions Executed")
    thread[loc] += count(d, "Thread Instructions Executed")
    stalls[loc] += count(d, "Warp Stall Sampling (All Samples)")
total, samples = sum(warp.values()), max(sum(stalls.values()), 1)
print(f"{total} warp instructions, {sum(thread.values()) / max(total, 1):.1f} lanes each")
for loc, n in warp.most_common(int(sys.argv[3]) if len(sys.argv) > 3 else 30):
    print(f"{100 * n / total:5.1f}% instructions {100 * stalls[loc] / samples:5.1f}% stall samples "
          f"{thread[loc] / max(n, 1):5.1f} lanes  {loc}")
