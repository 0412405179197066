#!/usr/bin/env python3
"""Tiles PNG frames side by side (halved), labelled, into one PNG: montage.py OUT IN... (numpy + matplotlib)."""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

out, inputs = sys.argv[1], sys.argv[2:]
fig, axes = plt.subplots(1, len(inputs), figsize=(4 * len(inputs), 2.9), dpi=100)
for ax, path in zip(axes if len(inputs) > 1 else [axes], inputs):
    ax.imshow(plt.imread(path)[::2, ::2])
    ax.set_title(path.split("/")[-1].rsplit(".", 1)[0], fontsize=9)
    ax.axis("off")
fig.tight_layout()
fig.savefig(out)
