#!/usr/bin/env python3
"""scripts/frame_times.py: its figures of a run from stats.json frames made up here; on two
binaries that `gvdp render --backend cpu` runs, a line per run and per binary, and the images the
same in every run; bad arguments and a missing binary are a one-line error with exit status 2, a
run that fails a line naming it and exit status 1.
Usage: frame_times_test.py --gvdp PATH"""
import importlib.util
import re
import sys

from script_test import ScriptTest

t = ScriptTest('frame_times.py')
check, run, gvdp, script = t.check, t.run, t.gvdp, t.script

sys.path.insert(0, script.rsplit('/', 1)[0])
spec = importlib.util.spec_from_file_location('frame_times', script)
ft = importlib.util.module_from_spec(spec)
spec.loader.exec_module(ft)


def frame(i, ms, produced=10, unsampled=0, **extra):
    return {'index': i, 'ms': ms, 'bricks_produced': produced, 'bricks_unsampled': unsampled,
            'unfinished_pixels': 0, **extra}


v = ft.run_line([frame(0, 40.0, spike=True, longest_wait_list=900), frame(1, 2.0, 100, 5),
                 frame(2, 6.0, 100, 15), frame(3, 1.0)])
check(v['first'] == 40.0 and v['spike'] and v['longest'] == 900, f'frame 0: {v}')
check(v['mean'] == 3.0 and v['max'] == 6.0 and v['max_at'] == 2, f'later frames: {v}')
check(abs(v['over'] - 100.0 * 20 / 210) < 1e-9, f'over-production: {v}')
v = ft.run_line([frame(0, 5.0)])
check(v['mean'] == 5.0 and not v['spike'] and v['longest'] == 0, f'one frame, no pt stats: {v}')
rows = ft.table([frame(i, 1.5 * i, requested=7 * i) for i in range(5)], ['ms', 'requested'], 1, 3)
check([r.split() for r in rows] == [['frame', 'ms', 'requested'], ['1', '1.50', '7'],
                                    ['2', '3.00', '14'], ['3', '4.50', '21']], f'table: {rows}')

r = run('--backend', 'cpu', '--runs', '2', '--scene', 'perlin', '--movement', 'forward',
        '--frames', '3', '--size', '48x32', '--list', f'a={gvdp}', f'b={gvdp}')
check(r.returncode == 0, f'two binaries: exit {r.returncode}: {r.stdout} {r.stderr}')
lines = r.stdout.splitlines()
check(len(lines) == 7, f'4 runs, 2 binaries, the images: {lines}')
runs = [x for x in lines if re.search(r' run \d+: ', x)]
check([x.split(':')[0] for x in runs] == ['perlin forward a run 1', 'perlin forward b run 1',
                                          'perlin forward a run 2', 'perlin forward b run 2'],
      f'interleaved runs: {runs}')
for x in runs:
    m = re.search(r'frame 0 ([\d.]+) ms.*mean ([\d.]+) ms, slowest ([\d.]+) ms \(frame (\d)\), '
                  r'over-production ([\d.]+)%, unfinished 0, images [0-9a-f]{12} \| '
                  r'([\d.]+) [\d.]+ [\d.]+$', x)
    check(m is not None and float(m.group(1)) == float(m.group(6)) and
          float(m.group(2)) <= float(m.group(3)) and m.group(4) in '12', f'run line: {x}')
check(any(x.startswith('perlin forward a: 2 runs, frame 0 ') for x in lines), f'summary: {lines}')
check(lines[-1].startswith('images: the same in every run'), f'images: {lines[-1]}')

r = run('--backend', 'cpu', '--runs', '1', '--scene', 'perlin', '--movement', 'forward',
        '--frames', '3', '--size', '48x32', '--table', 'ms,bricks_requested', '--span', '1-2',
        f'a={gvdp}')
lines = r.stdout.splitlines()
check(r.returncode == 0 and len(lines) == 6 and lines[1].split() == ['frame', 'ms',
                                                                     'bricks_requested'] and
      [x.split()[0] for x in lines[2:4]] == ['1', '2'], f'a table of frames 1-2: {lines}')

for args, what in ((['--runs', '0', gvdp], '--runs 0'), (['--frames', '0', gvdp], '--frames 0'),
                   (['/no/such/gvdp'], '/no/such/gvdp'),
                   ([f'x={gvdp}', f'x={gvdp}'], 'one label'),
                   (['--size', '12', gvdp], "--size '12'"),
                   (['--span', '3-1', gvdp], "--span '3-1'"),
                   (['--frames', '4', '--span', '2-4', gvdp], "--span '2-4'"),
                   (['--table', 'ms,,x', gvdp], "--table 'ms,,x'")):
    r = run(*args)
    check(r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1 and what in r.stderr and
          r.stderr.startswith('frame_times: '), f'{args}: exit {r.returncode}, stderr {r.stderr!r}')
r = run('--backend', 'cpu', '--runs', '1', '--scene', 'perlin', '--frames', '1', '--size',
        '48x32', '--table', 'ms,no_such_field', f'x={gvdp}')
check(r.returncode == 2 and "'no_such_field'" in r.stderr and 'bricks_requested' in r.stderr and
      len(r.stderr.strip().splitlines()) == 1, f'an unknown field: {r.returncode} {r.stderr!r}')
r = run('--backend', 'cpu', '--runs', '1', '--scene', 'nosuch', '--frames', '1', f'x={gvdp}')
check(r.returncode == 1 and 'nosuch walkthrough x run 1: failed' in r.stdout and
      "'nosuch'" in r.stdout, f'a failing run: exit {r.returncode}, {r.stdout!r}')

t.finish('frame_times_test')
