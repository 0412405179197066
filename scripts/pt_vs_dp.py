#!/usr/bin/env python3
"""pt's and graph's speed-ups of a `gvdp bench` results.json, cell by cell (average FPS ratios),
with the mean over the cells. Usage: pt_vs_dp.py results.json"""
import json
import statistics
import sys

cells = json.load(open(sys.argv[1]))["cells"]
fps = {(c["scene"], c["movement"], c["scheduler"]): c["avg_fps"] for c in cells}
keys = sorted({(c["scene"], c["movement"]) for c in cells})
pairs = [("pt", "dp"), ("pt", "sp"), ("graph", "sp")]
print("%-16s %-11s" % ("scene", "movement") + "".join("%10s" % f"{a}/{b}" for a, b in pairs))
ratios = {p: [] for p in pairs}
for scene, movement in keys:
    row = "%-16s %-11s" % (scene, movement)
    for a, b in pairs:
        if (scene, movement, a) in fps and (scene, movement, b) in fps:
            r = fps[(scene, movement, a)] / fps[(scene, movement, b)]
            ratios[(a, b)].append(r)
            row += "%10.2f" % r
        else:
            row += "%10s" % "-"
    print(row)
for (a, b), v in ratios.items():
    if v:
        print("%s/%s over %d cells: mean %.2fx, min %.2fx, max %.2fx" % (a, b, len(v), statistics.mean(v), min(v), max(v)))
