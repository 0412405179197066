#!/usr/bin/env python3
"""scripts/frame_idle.py: its parse of gvdp timeline's summary line and its medians and ranges
on values made up here; on two binaries that `gvdp timeline --backend cpu` runs, a line per
binary with every run counted, and the render-only frame with --again; bad arguments and a
missing binary are a one-line error with exit status 2, a run that fails a line naming it and
exit status 1.
Usage: frame_idle_test.py --gvdp PATH"""
import importlib.util
import re

from script_test import ScriptTest

t = ScriptTest('frame_idle.py')
check, run, gvdp, script = t.check, t.run, t.gvdp, t.script

spec = importlib.util.spec_from_file_location('frame_idle', script)
fi = importlib.util.module_from_spec(spec)
spec.loader.exec_module(fi)

line = ('frame 12: 2.38 ms; timeline: 2.379 ms over 132 lanes, 90000 records; busy render 40.0% '
        'production 30.0%; idle 11.9%; tail 0.240 ms')
check(fi.parse_summary(line) == (2.38, 2.379, 11.9), f'parse: {fi.parse_summary(line)}')
check(fi.parse_summary('no summary here') is None, 'parse: a line without the summary')
again = line.replace('frame 12:', 'frame 12 again:')
check(fi.parse_summary(again) == (2.38, 2.379, 11.9), f'parse, again: {fi.parse_summary(again)}')
check(fi.spread([12.9, 11.1, 11.9, 12.0], 1, '%') == '11.9% (11.1-12.9)',
      f'spread: {fi.spread([12.9, 11.1, 11.9, 12.0], 1, "%")}')  # median of 4: the mean of 2

r = run('--backend', 'cpu', '--runs', '2', '--scenes', 'perlin', '--frame', '1',
        f'a={gvdp}', f'b={gvdp}')
check(r.returncode == 0, f'two binaries: exit {r.returncode}: {r.stdout} {r.stderr}')
lines = r.stdout.splitlines()
check([x.split(':')[0] for x in lines] == ['perlin a', 'perlin b'], f'two binaries: {lines}')
for x in lines:
    m = re.search(r'2 runs, frame 1 ([\d.]+) ms \(.*\), span ([\d.]+) ms \(.*\), idle '
                  r'([\d.]+)% \(([\d.]+)-([\d.]+)\)$', x)
    check(m is not None and float(m.group(2)) > 0 and
          0 <= float(m.group(4)) <= float(m.group(3)) <= float(m.group(5)) <= 100, f'line: {x}')

# --again: the render-only frame (gvdp timeline --again), named so on every line.
r = run('--backend', 'cpu', '--runs', '1', '--scenes', 'perlin', '--frame', '1', '--again',
        f'a={gvdp}')
check(r.returncode == 0 and re.fullmatch(r'perlin a: 1 runs, frame 1 again [\d.]+ ms .*idle .*',
                                         r.stdout.strip()) is not None,
      f'--again: exit {r.returncode}: {r.stdout} {r.stderr}')

for args, what in ((['--runs', '0', gvdp], '--runs 0'), (['/no/such/gvdp'], '/no/such/gvdp'),
                   ([f'x={gvdp}', f'x={gvdp}'], 'one label'),
                   (['--size', '12', gvdp], "--size '12'")):
    r = run(*args)
    check(r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1 and what in r.stderr,
          f'{args}: exit {r.returncode}, stderr {r.stderr!r}')
r = run('--backend', 'cpu', '--runs', '1', '--scenes', 'nosuch', f'x={gvdp}')
check(r.returncode == 1 and 'nosuch x run 1: failed' in r.stdout and "'nosuch'" in r.stdout,
      f'a failing run: exit {r.returncode}, {r.stdout!r}')

t.finish('frame_idle_test')
