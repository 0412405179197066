#!/usr/bin/env python3
"""scripts/timeline_tail.py: on a trace made up here, the idle of each phase and the bins' busy
shares as computed by hand; on a trace `gvdp timeline --backend cpu` writes, the same idle as
gvdp's own summary line; a trace it cannot read is a one-line error with exit status 2.
Usage: timeline_tail_test.py --gvdp PATH"""
import json
import os
import re
import subprocess
import tempfile

from script_test import ScriptTest

t = ScriptTest('timeline_tail.py')
check, run, gvdp = t.check, t.run, t.gvdp


def record(sm, start, end, kind):
    return {'ph': 'X', 'pid': 0, 'tid': sm, 'ts': start, 'dur': end - start, 'cat': kind,
            'name': kind}


with tempfile.TemporaryDirectory() as d:
    # Two SMs over 0..150 us: SM 0 renders 0..100 then produces 100..150, SM 1 renders 10..60.
    # Busy 200 of 300 SM-us: idle 33.3%; between (0..100) 50 idle SM-us of the span's 300: 16.7%;
    # the last 50 us (100..150) the same; the two 25 us bins half busy, all of it production.
    made = os.path.join(d, 'made.json')
    with open(made, 'w') as f:
        json.dump({'traceEvents': [
            {'ph': 'M', 'name': 'thread_name', 'pid': 0, 'tid': 0, 'args': {'name': 'SM 0'}},
            {'ph': 'M', 'name': 'thread_name', 'pid': 0, 'tid': 1, 'args': {'name': 'SM 1'}},
            record(0, 0, 100, 'render'), record(0, 100, 150, 'production'),
            record(1, 10, 60, 'render')]}, f)
    r = run(made, '--tail', '50', '--bin', '25')
    check(r.returncode == 0, f'made-up trace: exit {r.returncode}: {r.stderr}')
    first = r.stdout.splitlines()[0] if r.stdout else ''
    for part in ('span 150 us', '2 SMs', '3 records', 'idle 33.3%', '(0 us) 0.0%',
                 'between 16.7%', "last 50 us 16.7%", 'after the worker 0.0%'):
        check(part in first, f'made-up trace: "{part}" not in "{first}"')
    bins = [line.split() for line in r.stdout.splitlines()[2:]]
    check(len(bins) == 2, f'made-up trace: {len(bins)} bins, expected 2')
    for b in bins:
        check(b[1:5] == ['50.0%', '0.0%', '50.0%', '0.0%'], f'made-up trace: bin {b}')

    # By bands of one SM, between (0..100 us): SM 0 renders throughout, SM 1 half of it.
    r = run(made, '--tail', '50', '--bin', '25', '--bands', '1')
    bands = [line.split() for line in r.stdout.splitlines() if line.startswith('SMs')]
    check([b[2:5] for b in bands] == [['100.0%', '100.0%', '0.0%'], ['50.0%', '50.0%', '0.0%']],
          f'made-up trace: bands {bands}')

    # The last renders: two render records are open together until 60 us, so fewer than 2 from
    # 60 us to the worker's end (150): 90 us, SM 0 busy throughout, SM 1 idle (50% busy), 90 idle
    # SM-us of the span's 300 (30.0%). Fewer than 3 were open from the first render record on.
    r = run(made, '--last-renders', '2')
    last = [line for line in r.stdout.splitlines() if line.startswith('fewer than')]
    check(last == ['fewer than 2 render records open: the last 90 us, 50.0% busy, 30.0% of the '
                   'frame idle'], f'made-up trace: last renders {last}')
    r = run(made, '--last-renders', '3')
    check('the last 150 us, 66.7% busy, 33.3% of the frame idle' in r.stdout,
          f'made-up trace: fewer than 3 renders: {r.stdout}')
    r = run(made, '--last-renders', '-1')
    check(r.returncode == 2 and '--last-renders -1' in r.stderr,
          f'--last-renders -1: exit {r.returncode}, stderr {r.stderr!r}')

    # gvdp's own trace: the script's idle is the summary's (both the union of each SM's records).
    png, trace = os.path.join(d, 't.png'), os.path.join(d, 't.json')
    g = subprocess.run([gvdp, 'timeline', '--backend', 'cpu', '--scheduler', 'pt', '--scene',
                        'perlin', '--frame', '2', '--out', png, '--trace', trace],
                       capture_output=True, text=True)
    check(g.returncode == 0, f'gvdp timeline: exit {g.returncode}: {g.stderr}')
    own = re.search(r'idle (\d+\.\d)%', g.stdout)
    r = run(trace)
    got = re.search(r'idle (\d+\.\d)%', r.stdout)
    check(own is not None and got is not None and own.group(1) == got.group(1),
          f'idle: gvdp says {own and own.group(1)}, the script {got and got.group(1)}')

    bad = os.path.join(d, 'bad.json')
    with open(bad, 'w') as f:
        f.write('{"traceEvents": [')
    for path in (bad, os.path.join(d, 'missing.json')):
        r = run(path)
        check(r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1 and path in r.stderr,
              f'{path}: exit {r.returncode}, stderr {r.stderr!r}')

t.finish('timeline_tail_test')
