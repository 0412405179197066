#!/usr/bin/env python3
"""Joins scripts/ncu_lines.sh's two outputs: the share of a kernel's warp instructions, of its
stall samples and of its no-instruction stall samples (the instruction fetch) per source line, and
the lanes its instructions ran on. The SASS page lists the kernel and each function it calls out
of line (e.g. gradientNoise), each from its own address; the line table covers the kernel, so a
called function counts as one line, "function NAME".
Usage: scripts/ncu_lines.py sass_SCENE.csv.gz lines_SCENE.txt.gz [TOP]"""
import collections
import csv
import gzip
import sys

if len(sys.argv) < 3:
    print(__doc__, file=sys.stderr)
    sys.exit(2)


def read(path, parse):
    """parse(the gzip text file at path), or a one-line error and exit status 2."""
    try:
        return list(parse(gzip.open(path, "rt")))
    except (OSError, EOFError, UnicodeDecodeError) as e:
        print(f"ncu_lines.py: cannot read {path} as gzip text: {e}", file=sys.stderr)
        sys.exit(2)


# Blocks of the page: a "Kernel Name" row, a header row ("Address", ...), then one row an
# instruction.
page, table = read(sys.argv[1], csv.reader), read(sys.argv[2], iter)
blocks, head = [], None
for r in page:
    if r and r[0] == "Kernel Name":
        head = None
        blocks.append((r[1], []))
    elif r and r[0] == "Address":
        head = r
        if not blocks:
            blocks.append(("?", []))
    elif head and len(r) == len(head) and r[0].startswith("0x"):
        blocks[-1][1].append(dict(zip(head, r)))
blocks = [(n, rows) for n, rows in blocks if rows]
if not blocks:
    print(f"ncu_lines.py: {sys.argv[1]}: no instructions", file=sys.stderr)
    sys.exit(2)
kernel = max(blocks, key=lambda b: len(b[1]))[0]  # the kernel: the largest block
where = {}
for line in table:
    parts = line.split(None, 1)
    if line.startswith("#") or not parts:
        continue
    where[int(parts[0], 16)] = parts[1].strip().split("/src/")[-1] if len(parts) > 1 else "?"


def count(d, key):
    return int(d.get(key, "0").replace(",", "") or 0)


warp, thread = collections.Counter(), collections.Counter()
stalls, fetch = collections.Counter(), collections.Counter()
for n, rows in blocks:
    base = int(rows[0]["Address"], 16)
    short = n.split("(")[0].split("::")[-1]
    for d in rows:
        loc = where.get(int(d["Address"], 16) - base, "?") if n == kernel else f"function {short}"
        warp[loc] += count(d, "Instructions Executed")
        thread[loc] += count(d, "Thread Instructions Executed")
        stalls[loc] += count(d, "Warp Stall Sampling (All Samples)")
        fetch[loc] += count(d, "stall_no_inst")
total, samples = sum(warp.values()), max(sum(stalls.values()), 1)
nofetch = max(sum(fetch.values()), 1)
print(f"{total} warp instructions, {sum(thread.values()) / max(total, 1):.1f} lanes each; "
      f"no-instruction stalls {100 * sum(fetch.values()) / samples:.1f}% of the stall samples")


def shares(n, s, i):
    """A row's shares of the instructions, the stall samples and the no-instruction samples."""
    return f"{100 * n / total:6.1f}% {100 * s / samples:6.1f}% {100 * i / nofetch:8.1f}%"


print(" instrs  stalls  no-instr  lanes  source line")
for loc, n in warp.most_common(int(sys.argv[3]) if len(sys.argv) > 3 else 30):
    print(f"{shares(n, stalls[loc], fetch[loc])} {thread[loc] / max(n, 1):5.1f}  {loc}")
# The same per source file (a called function is its own).
files = collections.defaultdict(lambda: [0, 0, 0])
for loc, n in warp.items():
    f = files[loc.rsplit(":", 1)[0]]
    f[0] += n
    f[1] += stalls[loc]
    f[2] += fetch[loc]
print(" instrs  stalls  no-instr  source file")
for f, (n, s, i) in sorted(files.items(), key=lambda kv: -kv[1][2])[:15]:
    print(f"{shares(n, s, i)}  {f}")
