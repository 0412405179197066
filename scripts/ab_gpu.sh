#!/usr/bin/env bash
# On a GPU machine: an A/B of gvdp binaries on `gvdp bench` (1500x1000), ROUNDS rounds, the
# binaries interleaved within each round; then, per binary against the first, the geometric means
# of floor_ms and avg_fps over the cells and each cell's floor and FPS, each the upper median of
# its rounds (with two rounds, the larger value: the same rule for every binary).
# Prints the summary and writes it to $OUT/ab.txt (rewritten after every round, so a run cut off
# by a time limit leaves the rounds it finished); the CSVs, JSONs and logs
# (ab_<name>_<round>.*, name: the binary's folder) to $OUT/ab_results.tgz (the device tool brings
# back 8 files a call).
# Extra arguments go to every bench (e.g. --scenes forest).
# Usage: scripts/ab_gpu.sh ROUNDS SCHEDULERS MOVEMENTS BIN [BIN...] [-- BENCH_ARGS...]
set -uo pipefail
# A GPU hang ends its run in a minute with a line naming where it waited (base/watchdog.h),
# instead of taking the rest of the call.
export GVDP_WATCHDOG_S="${GVDP_WATCHDOG_S:-60}"
cd "$(dirname "$0")/.."
results="${OUT:-out/ab}"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
mkdir -p "$results"
rounds=$1 schedulers=$2 movements=$3
shift 3
bins=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do bins+=("$1") && shift; done
[ $# -gt 0 ] && shift
# The summary of the rounds done so far (a run cut off by a time limit keeps the last one).
summary() {
  python3 - "$out" "$1" "${bins[@]}" <<'PY'
import csv, math, sys
out, rounds, bins = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
names = [b.split('/')[-2] for b in bins]
def load(name):
    cells = {}
    for r in range(1, rounds + 1):
        try:
            for row in csv.DictReader(open(f'{out}/ab_{name}_{r}.csv')):
                k = (row['scene'], row['movement'], row['scheduler'])
                cells.setdefault(k, []).append(row)
        except FileNotFoundError:
            pass
    return cells
data = {n: load(n) for n in names}
base = data[names[0]]
gm = lambda xs: math.exp(sum(map(math.log, xs)) / len(xs)) if xs else float('nan')
med = lambda rows, key: sorted(float(x[key]) for x in rows)[len(rows) // 2]
print(f'rounds done: {rounds}')
for n in names[1:]:
    keys = [k for k in base if k in data[n]]
    fl = gm([med(data[n][k], 'floor_ms') / med(base[k], 'floor_ms') for k in keys])
    fps = gm([med(data[n][k], 'avg_fps') / med(base[k], 'avg_fps') for k in keys])
    low = gm([med(data[n][k], 'low1_fps') / med(base[k], 'low1_fps') for k in keys])
    unf = sum(int(x['unfinished_pixels']) for k in keys for x in data[n][k])
    print(f'{n} vs {names[0]}: floors x{fl:.3f}, FPS x{fps:.3f}, 1% lows x{low:.3f} over {len(keys)} cells, unfinished {unf}')
# The lookahead issue's figures: cells whose 1% low is >= 75% of their average, the largest
# over-production (each the upper median of the rounds).
lows = lambda n: sum(med(c, 'low1_fps') >= 0.75 * med(c, 'avg_fps') for c in data[n].values())
over = lambda n: max(med(c, 'overproduction') for c in data[n].values())
# Frame 0 (from an empty cache; gvdp before session 58 wrote no first_ms): the slowest cell's.
def first(n):
    cells = [(med(c, 'first_ms'), ' '.join(k)) for k, c in data[n].items() if 'first_ms' in c[0]]
    return f', first frame at most {max(cells)[0]:.1f} ms ({max(cells)[1]})' if cells else ''
for n in names:
    print(f'{n}: 1% low >= 75% of average in {lows(n)} of {len(data[n])} cells, over-production max {100 * over(n):.1f}%{first(n)}')
print('cell'.ljust(40) + ''.join(f'{n:>30}' for n in names) + '   (floor ms / avg FPS / 1% low % of avg, upper medians of rounds)')
for k in base:
    row = ' '.join(k).ljust(40)
    for n in names:
        c = data[n].get(k)
        row += (f'{med(c, "floor_ms"):>12.2f} /{med(c, "avg_fps"):>7.1f} /{100 * med(c, "low1_fps") / med(c, "avg_fps"):>5.0f}%'
                if c else ' ' * 30)
    print(row)
PY
}
for r in $(seq 1 "$rounds"); do
  for bin in "${bins[@]}"; do
    name=$(basename "$(dirname "$bin")")
    "$bin" bench --backend cuda --schedulers "$schedulers" --movements "$movements" "$@" \
      --out "$out/ab_${name}_$r.json" --csv "$out/ab_${name}_$r.csv" >"$out/ab_${name}_$r.log" 2>&1 ||
      echo "$name round $r: bench failed ($(tail -n 1 "$out/ab_${name}_$r.log"))"
  done
  summary "$r" >"$results/ab.txt"
  tar czf "$results/ab_results.tgz" -C "$out" .
done
cat "$results/ab.txt"
