#!/usr/bin/env bash
# On a machine with a GPU, with the binaries built elsewhere and carried in carry/ (carry/gvdp,
# carry/gvdp_tests from preset default; carry/nocdp/gvdp from preset nocdp):
#   1. every test (GPU ones included), then dp's 32-launch buffer test 100 times over;
#   2. compute-sanitizer's four tools on every scheduler, each with a large pool (forest
#      walkthrough, 20000 bricks), a tiny one (random-spheres backward, 64 bricks: refills and
#      degraded frames, --tiles off), the large one with --budget-ms 0 ("late": every claim past
#      the deadline, rays never waiting) and forest backward with 600 bricks ("tiled": frames
#      rendered as tiles, memcheck and racecheck only) and, for pt, random-spheres forward over
#      20 frames with --far-prefetch 8 ("far": its idle frames inside a sphere march a far
#      prefetch that holds the frame open; memcheck and racecheck only). memcheck runs on the default build; initcheck, racecheck and synccheck
#      on the nocdp build: with CDP in the binary they instrument no kernel ("CUDA Dynamic
#      Parallelism is not supported by the selected tool"), and initcheck then reports every
#      download as uninitialised since it never saw the kernels' writes;
#   3. unless frames is 0, a 1500x1000 walkthrough of each scene per scheduler (montages).
# Prints one line per tool, scheduler and pool; exits 1 on any failed test or any tool error.
# Writes to $OUT (or out/gpu_check): device.txt, tests.log, dp_stress.log, sanitizer.log,
# renders.log, montage_<scheduler>.png.
# Usage: scripts/gpu_check.sh [frames] [schedulers...]   (default: 0, all five schedulers)
#   TOOLS="memcheck racecheck" and POOLS="large tiny" (environment) run only those tools and
#   pools (default: all four of each); TESTS=0 skips the tests (when another call runs them);
#   RENDER_ARGS="--cost-map" adds flags to every sanitizer render (pass the schedulers that
#   take them).
set -uo pipefail
cd "$(dirname "$0")/.."
out="${OUT:-out/gpu_check}"
mkdir -p "$out"
frames="${1:-0}"
shift || true
schedulers=("${@:-sp}")
[ $# -eq 0 ] && schedulers=(direct sp dp pt graph)
export GVDP_BIN="$PWD/carry/gvdp"
{
  nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader
  compute-sanitizer --version | tail -n 1
} | tee "$out/device.txt"
status=0

tools=" ${TOOLS:-memcheck initcheck racecheck synccheck} "
read -ra pool_list <<<"${POOLS:-large tiny late tiled far}"
for t in $tools; do
  [[ " memcheck initcheck racecheck synccheck " == *" $t "* ]] || { echo "gpu_check: unknown tool '$t' in TOOLS" >&2 && exit 2; }
done
for p in "${pool_list[@]}"; do
  [[ " large tiny late tiled far " == *" $p "* ]] || { echo "gpu_check: unknown pool '$p' in POOLS" >&2 && exit 2; }
done
if [ "${TESTS:-1}" = 0 ]; then
  echo "== tests: skipped (TESTS=0)"
else
  echo "== tests"
  # Full output and a time limit (the tests take ~210 s on an H100): a run that hangs names its
  # test, and the sanitizers still run (one such run, never reproduced: BENCHMARKS.md, session 18).
  # The watchdog (base/watchdog.h) ends a run whose GPU hangs, naming where (dp's rare hang).
  GVDP_WATCHDOG_S=60 timeout 420 ./carry/gvdp_tests >"$out/tests.log" 2>&1
  rc=$?
  [ $rc -ne 0 ] && status=1
  [ $rc -eq 124 ] && echo "tests: no end after 420 s, in $(grep -E '^\[ RUN' "$out/tests.log" | tail -n 1)"
  [ $rc -eq 3 ] && echo "tests: $(grep -E 'did not finish' "$out/tests.log" | tail -n 1), in $(grep -E '^\[ RUN' "$out/tests.log" | tail -n 1)"
  grep -E "^\[  (FAILED|PASSED|SKIPPED) |^\[==========\]|measure" "$out/tests.log" | tail -n 25
  # dp's launch allowance under stress: before it, a 32-launch buffer hung the launch tree once in
  # about 35 repeats of these 5 tests (BENCHMARKS.md, session 35); 100 repeats take ~25 s.
  GVDP_WATCHDOG_S=20 timeout 120 ./carry/gvdp_tests --gtest_filter='*TinyLaunchBuffer*' \
    --gtest_repeat=100 >"$out/dp_stress.log" 2>&1
  rc=$?
  [ $rc -ne 0 ] && status=1
  echo "dp stress (32 pending launches, 100 repeats of 5 scenes): rc $rc, \
$(grep -cE 'PASSED  \] 5 tests' "$out/dp_stress.log") repeats passed \
$(grep -E 'did not finish' "$out/dp_stress.log" | tail -n 1)"
fi

# One sanitizer run: prints "<tool> <scheduler> <pool>: <the tool's summary>", FAIL if the tool
# found anything or the render failed.
sanitize() {
  local tool=$1 sched=$2 pool=$3 bin=$4 note=${5:-}
  [[ "$tools" == *" $tool "* ]] || return 0
  local scene=forest movement=walkthrough args=()
  [ "$pool" = tiny ] && scene=random-spheres movement=backward
  [ "$pool" = tiled ] && movement=backward
  [ "$pool" = far ] && scene=random-spheres movement=forward
  [ "$sched" != direct ] && args=(--pool-bricks "$(case $pool in tiny) echo 64 ;; tiled) echo 600 ;; *) echo 20000 ;; esac)")
  [ "$pool" = late ] && args+=(--budget-ms 0)
  # The scheduler's own degraded frames (then the cold retries of tiles/tiled_frame.cpp);
  # "tiled": frames that overflow 600 bricks, rendered as tiles.
  [ "$pool" = tiny ] && args+=(--tiles off)
  read -ra extra <<<"${RENDER_ARGS:-}"
  args+=("${extra[@]}")
  # pt with its lookahead and prefetch on: the protocol with every kind of claim in it (the second
  # frame prefetches for a third, whose prefetch is as dense as the second's yield asks).
  local frames=2
  [ "$sched" = pt ] && args+=(--lookahead 4 --prefetch 2) && frames=3
  [ "$pool" = far ] && frames=20 && args+=(--far-prefetch 8)
  local log=/tmp/sanitize.log
  GVDP_GRAPH_LOOP=$graph_loop timeout 240 compute-sanitizer --tool "$tool" --error-exitcode 9 --print-limit 20 "$bin" render \
    --backend cuda --scheduler "$sched" --scene "$scene" --movement "$movement" --width 160 \
    --height 100 --frames "$frames" "${args[@]}" --out "/tmp/sanitize_$sched" >"$log" 2>&1
  local rc=$?
  local summary
  summary=$(grep -E "(ERROR|RACECHECK) SUMMARY" "$log" | tail -n 1 | sed 's/^========= //')
  local verdict=ok
  # A tool that instruments nothing finds nothing: its warning fails the run.
  if grep -q "not supported by the selected tool" "$log"; then
    summary="the tool did not instrument this binary: $summary"
    [ $rc -eq 0 ] && rc=8
  fi
  if [ $rc -ne 0 ] || [ -z "$summary" ]; then
    verdict=FAIL
    status=1
  fi
  printf "%-9s %-6s %-5s %-4s %s%s\n" "$tool" "$sched" "$pool" "$verdict" "${summary:-no summary (rc $rc)}" "$note"
  { echo "=== $tool $sched $pool (rc $rc)"; cat "$log"; } >>"$out/sanitizer.log"
}

graph_loop=device
echo "== compute-sanitizer (160x100, 2 frames, pt 3; large pool: forest, tiny: random-spheres backward, late: large with --budget-ms 0, tiled: forest backward, 600 bricks, far: pt's far prefetch, random-spheres forward, 20 frames)"
: >"$out/sanitizer.log"
for sched in "${schedulers[@]}"; do
  pools=("${pool_list[@]}")
  [ "$sched" = direct ] && pools=(none)
  for pool in "${pools[@]}"; do
    [ "$pool" = far ] && [ "$sched" != pt ] && continue
    sanitize memcheck "$sched" "$pool" ./carry/gvdp
    if [ "$pool" = tiled ] || [ "$pool" = far ]; then
      [ "$sched" = dp ] && continue
      [ "$sched" = graph ] && graph_loop=host
      sanitize racecheck "$sched" "$pool" ./carry/nocdp/gvdp
      graph_loop=device
      continue
    fi
    if [ "$sched" = dp ]; then
      [[ "$tools" =~ (init|race|sync)check ]] || continue
      printf "%-9s %-6s %-5s %-4s %s\n" "init/race/sync" dp "$pool" skip \
        "not run: initcheck, racecheck and synccheck do not instrument CUDA Dynamic Parallelism; dp's protocol runs under ThreadSanitizer on its CPU twin (scripts/tsan.sh: DpCpu tests, in CI)"
      continue
    fi
    if [ "$sched" = graph ]; then
      # compute-sanitizer 2025.3 cannot check kernels of a conditional node's body (racecheck
      # crashes in its own library, synccheck misreports barriers: scripts/probe/graph_probe.cu;
      # under initcheck the frame fails with an illegal address, the binary of bf426be too,
      # H100): the same kernels with the host repeating the loop's body (graph_cuda.h).
      graph_loop=host
      sanitize initcheck graph "$pool" ./carry/nocdp/gvdp "  (GVDP_GRAPH_LOOP=host)"
      sanitize racecheck graph "$pool" ./carry/nocdp/gvdp "  (GVDP_GRAPH_LOOP=host)"
      sanitize synccheck graph "$pool" ./carry/nocdp/gvdp "  (GVDP_GRAPH_LOOP=host)"
      graph_loop=device
      continue
    fi
    sanitize initcheck "$sched" "$pool" ./carry/nocdp/gvdp
    sanitize racecheck "$sched" "$pool" ./carry/nocdp/gvdp
    sanitize synccheck "$sched" "$pool" ./carry/nocdp/gvdp
  done
done

if [ "$frames" -gt 0 ]; then
  echo "== renders (1500x1000, $frames frames)"
  for sched in "${schedulers[@]}"; do
    pngs=()
    for scene in perlin fbm forest random-spheres aligned-spheres; do
      dir="/tmp/render_${sched}_${scene}"
      echo "== $sched $scene" >>"$out/renders.log"
      ./carry/gvdp render --backend cuda --scheduler "$sched" --scene "$scene" --width 1500 \
        --height 1000 --frames "$frames" --out "$dir" >>"$out/renders.log" 2>&1 || status=1
      echo "$sched $scene: $(tail -n 1 "$out/renders.log")"
      cp "$dir/frame_0000.png" "/tmp/${scene}.png" && pngs+=("/tmp/${scene}.png")
    done
    python3 scripts/montage.py "$out/montage_${sched}.png" "${pngs[@]}" || true
  done
fi
echo "gpu_check: $([ $status -eq 0 ] && echo "all passed" || echo FAILED)"
exit $status
