#!/usr/bin/env python3
"""Plots a `gvdp bench` results.json: frame time along each scene's walkthrough per scheduler,
and the speed-up over sp of every cell. Usage: plot_bench.py results.json OUTDIR"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

results = json.load(open(sys.argv[1]))
out = sys.argv[2]
os.makedirs(out, exist_ok=True)
cells = results["cells"]
scenes = list(dict.fromkeys(c["scene"] for c in cells))
movements = list(dict.fromkeys(c["movement"] for c in cells))
schedulers = list(dict.fromkeys(c["scheduler"] for c in cells))
title = f'{results["device"].split(",")[0]}, {results["width"]}x{results["height"]}'

fig, axes = plt.subplots(1, len(scenes), figsize=(4 * len(scenes), 3.2), squeeze=False)
for ax, scene in zip(axes[0], scenes):
    for c in cells:
        if c["scene"] == scene and c["movement"] == "walkthrough":
            ax.plot(c["frame_ms"], label=f'{c["scheduler"]} ({c["avg_fps"]:.1f} FPS)')
    ax.set_title(f"{scene}, walkthrough", fontsize=9)
    ax.set_xlabel("frame")
    ax.set_ylabel("ms")
    ax.legend(fontsize=7)
fig.suptitle(f"Frame time along the path ({title})", fontsize=10)
fig.tight_layout()
fig.savefig(os.path.join(out, "frame_time.png"), dpi=90)

others = [k for k in schedulers if k != "sp"]
if others:
    fig, ax = plt.subplots(figsize=(max(6, 0.5 * len(scenes) * len(movements)), 3.5))
    labels, width = [], 0.8 / len(others)
    for i, k in enumerate(others):
        xs, ys = [], []
        for s_i, scene in enumerate(scenes):
            for m_i, m in enumerate(movements):
                for c in cells:
                    if c["scene"] == scene and c["movement"] == m and c["scheduler"] == k:
                        xs.append(s_i * (len(movements) + 1) + m_i + i * width)
                        ys.append(c["speedup_vs_sp"])
        ax.bar(xs, ys, width=width, label=f"{k} / sp")
    ticks = [s_i * (len(movements) + 1) + m_i for s_i in range(len(scenes)) for m_i in range(len(movements))]
    ax.set_xticks(ticks)
    ax.set_xticklabels([f"{s}\n{m}" if m_i == 0 else m for s in scenes for m_i, m in enumerate(movements)],
                       rotation=90, fontsize=6)
    ax.axhline(1.0, color="black", linewidth=0.8)
    ax.set_ylabel("speed-up vs sp (average FPS)")
    ax.set_title(f"Speed-up against sp ({title})", fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "speedup.png"), dpi=90)
