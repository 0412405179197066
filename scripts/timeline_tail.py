#!/usr/bin/env python3
"""Where a frame's idle lies, from a `gvdp timeline --trace` file (Chrome trace events, one
thread per SM): the idle share of the frame's span (SM-time with no record open, over span x
SMs) split into the frame's start (to the first render record), the worker's last TAIL us, the
time between, and what follows the worker (the resolve); then the worker's last TAIL us in bins:
the share of SM-time busy (any record open), with each kind of record, and the records (warp
spans) of each kind open in the bin. With --bands N, the time between by bands of N SMs (by id:
pt's producer SMs are the lowest), each band's share busy and busy with each kind. With
--last-renders N, the frame's last rays: the stretch from when the render records open last fell
below N to the worker's end, its length, its share busy and its idle as a share of the frame.

Usage: scripts/timeline_tail.py TRACE.json [--tail US] [--bin US] [--sms N] [--bands N]
                                [--last-renders N]
A trace it cannot read, or one without records, is a one-line error with exit status 2.
"""
import argparse
import json
import sys


def union_length(spans, lo, hi):
    """Length of the union of [start, end) spans clipped to [lo, hi)."""
    total, cursor = 0.0, lo
    for s, e in sorted(spans):
        s, e = max(s, cursor), min(e, hi)
        if e > s:
            total += e - s
            cursor = e
    return total


def fail(message):
    print(f"timeline_tail: {message}", file=sys.stderr)
    sys.exit(2)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("trace")
    ap.add_argument("--tail", type=float, default=240.0, help="the worker's last us (240)")
    ap.add_argument("--bin", type=float, default=20.0, help="bin width in us (20)")
    ap.add_argument("--sms", type=int, default=0, help="SMs (default: the trace's thread names)")
    ap.add_argument("--bands", type=int, default=0, help="the time between by bands of N SMs")
    ap.add_argument("--last-renders", type=int, default=0,
                    help="the last stretch with fewer than N render records open")
    a = ap.parse_args()
    if a.bands < 0:
        fail(f"bad --bands {a.bands} (expected N >= 1, or 0: none)")
    if a.last_renders < 0:
        fail(f"bad --last-renders {a.last_renders} (expected N >= 1, or 0: none)")
    try:
        with open(a.trace) as f:
            events = json.load(f)["traceEvents"]
        sms = a.sms or sum(
            1 for e in events if e.get("ph") == "M" and e.get("name") == "thread_name")
        recs = [(e["tid"], e["ts"], e["ts"] + e["dur"], e["cat"]) for e in events
                if e.get("ph") == "X"]
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as e:
        fail(f"cannot read trace '{a.trace}': {e!r}")
    if not recs or sms == 0 or not any(r[3] == "render" for r in recs):
        fail(f"no render records or SMs in trace '{a.trace}'")
    t0, t1 = min(r[1] for r in recs), max(r[2] for r in recs)
    worker = [r for r in recs if r[3] in ("render", "production", "prefetch")]
    first = min(r[1] for r in worker if r[3] == "render")
    last = max(r[2] for r in worker)
    tail0 = max(first, last - a.tail)
    by_sm = {}
    for sm, s, e, _ in recs:
        by_sm.setdefault(sm, []).append((s, e))
    span = t1 - t0

    def idle(lo, hi):
        busy = sum(union_length(v, lo, hi) for v in by_sm.values())
        return 100.0 * ((hi - lo) * sms - busy) / (span * sms)

    print(f"{a.trace}: span {span:.0f} us, {sms} SMs, {len(recs)} records, idle "
          f"{idle(t0, t1):.1f}%: start to the first render record ({first - t0:.0f} us) "
          f"{idle(t0, first):.1f}%, between {idle(first, tail0):.1f}%, the worker's last "
          f"{last - tail0:.0f} us {idle(tail0, last):.1f}%, after the worker {idle(last, t1):.1f}%")
    kinds = ("render", "production", "prefetch")
    print(f"{'bin (us from start)':>20} {'busy':>6} " + " ".join(f"{k:>10}" for k in kinds) + " " +
          " ".join(f"{k[:6] + ' recs':>11}" for k in kinds))
    kind_sm = {}
    for sm, s, e, k in worker:
        kind_sm.setdefault((k, sm), []).append((s, e))
    b = tail0
    while b < last:
        hi = min(b + a.bin, last)
        width = (hi - b) * sms / 100.0
        busy = sum(union_length(v, b, hi) for v in by_sm.values()) / width
        line = f"{b - t0:9.0f}-{hi - t0:<10.0f} {busy:5.1f}% "
        for k in kinds:
            share = sum(union_length(v, b, hi) for (kk, _), v in kind_sm.items() if kk == k) / width
            line += f"{share:9.1f}% "
        for k in kinds:
            line += f"{sum(1 for r in worker if r[3] == k and r[1] < hi and r[2] > b):11d} "
        print(line.rstrip())
        b = hi
    if a.bands > 0:
        between_bands(a.bands, sms, first, tail0, by_sm, kind_sm, kinds)
    if a.last_renders > 0:
        lo = last_renders_start(a.last_renders, worker, first)
        share = idle(lo, last)  # of the frame's SM-time; of the stretch's, scaled by its length
        busy = 100.0 - share * span / (last - lo) if last > lo else 0.0
        print(f"fewer than {a.last_renders} render records open: the last {last - lo:.0f} us, "
              f"{busy:.1f}% busy, {share:.1f}% of the frame idle")


def last_renders_start(n, worker, first):
    """When the render records open last fell below n (ends before starts at one time), or the
    first render record's start if n were never open."""
    events = sorted([(s, 1) for _, s, _, k in worker if k == "render"] +
                    [(e, -1) for _, _, e, k in worker if k == "render"])
    count, start = 0, first
    for t, d in events:
        if d < 0 and count >= n > count + d:
            start = t
        count += d
    return start


def between_bands(n, sms, lo, hi, by_sm, kind_sm, kinds):
    """The time between (lo..hi) by bands of n SMs: each band's share busy, and with each kind."""
    print(f"between ({hi - lo:.0f} us) by bands of {n} SMs: busy, " + ", ".join(kinds))
    for first_sm in range(0, sms, n):
        band = range(first_sm, min(first_sm + n, sms))
        width = (hi - lo) * len(band) / 100.0 if hi > lo else float("inf")
        busy = sum(union_length(by_sm.get(sm, []), lo, hi) for sm in band) / width
        shares = [sum(union_length(kind_sm.get((k, sm), []), lo, hi) for sm in band) / width
                  for k in kinds]
        print(f"SMs {band[0]:3d}-{band[-1]:<3d} {busy:5.1f}% " +
              " ".join(f"{v:9.1f}%" for v in shares))


if __name__ == "__main__":
    try:
        main()
    except BrokenPipeError:  # a reader that took what it wanted (| head)
        sys.stderr.close()
