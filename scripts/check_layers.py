#!/usr/bin/env python3
"""Fails when an include runs up the layers of docs/DESIGN.md ("Layers").

A file in src/gvdp/<layer>/ may include gvdp/<other>/ only when <other> is the same layer or one
below it; the public headers (include/gvdp/*.h, included as "gvdp/<name>.h") are the api layer, but
gvdp/io.h (image files) is io;
src/apps, tests and examples may include anything. Prints every offending include as file:line."""
import pathlib
import re
import sys

# Bottom to top.
LAYERS = ["base", "mesh", "profile", "world", "render", "cache", "sched", "tiles", "api", "bench", "io", "serve"]
INCLUDE = re.compile(r'^\s*#\s*include\s+"gvdp/(?:([a-z_]+)/|[a-z_]+\.h")')

repo = pathlib.Path(__file__).resolve().parent.parent
root = repo / "src" / "gvdp"
files = [(p, p.relative_to(root).parts[0]) for p in sorted(root.rglob("*"))]
PUBLIC_LAYER = {"io.h": "io"}  # public headers above api
files += [(p, PUBLIC_LAYER.get(p.name, "api")) for p in sorted((repo / "include" / "gvdp").glob("*"))]
bad = 0
for path, layer in files:
    if path.suffix not in {".h", ".cpp", ".cu", ".cuh"}:
        continue
    if layer not in LAYERS:
        print(f"{path}: folder '{layer}' is in no layer (scripts/check_layers.py)")
        bad += 1
        continue
    for number, line in enumerate(path.read_text().splitlines(), 1):
        m = INCLUDE.match(line)
        if not m:
            continue
        other = m.group(1) or PUBLIC_LAYER.get(line.split('"')[1][5:], "api")
        if other not in LAYERS or LAYERS.index(other) > LAYERS.index(layer):
            print(f"{path}:{number}: {layer} includes {other} ({line.strip()})")
            bad += 1
print(f"check_layers: {bad} upward include(s); order: {' < '.join(LAYERS)} < apps")
sys.exit(1 if bad else 0)
