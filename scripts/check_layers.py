#!/usr/bin/env python3
"""Fails when an include runs up the layers of docs/DESIGN.md ("Layers").

A file in src/gvdp/<layer>/ may include gvdp/<other>/ only when <other> is the same layer or one
below it; src/apps may include anything. Prints every offending include as file:line."""
import pathlib
import re
import sys

# Bottom to top.
LAYERS = ["base", "profile", "world", "render", "cache", "sched", "bench", "io"]
INCLUDE = re.compile(r'^\s*#\s*include\s+"gvdp/([a-z_]+)/')

root = pathlib.Path(__file__).resolve().parent.parent / "src" / "gvdp"
bad = 0
for path in sorted(root.rglob("*")):
    if path.suffix not in {".h", ".cpp", ".cu", ".cuh"}:
        continue
    layer = path.relative_to(root).parts[0]
    if layer not in LAYERS:
        print(f"{path}: folder '{layer}' is in no layer (scripts/check_layers.py)")
        bad += 1
        continue
    for number, line in enumerate(path.read_text().splitlines(), 1):
        m = INCLUDE.match(line)
        if m and (m.group(1) not in LAYERS or LAYERS.index(m.group(1)) > LAYERS.index(layer)):
            print(f"{path}:{number}: {layer} includes {m.group(1)} ({line.strip()})")
            bad += 1
print(f"check_layers: {bad} upward include(s); order: {' < '.join(LAYERS)} < apps")
sys.exit(1 if bad else 0)
