#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer build of the CPU backend (preset "asan") and the
# tests of what users type: the command line (malformed and oversized input, unwritable outputs,
# resource limits) and the library's checks behind it, plus the cheap host-side units. Any report
# fails the run, the gvdp processes the Cli tests start included.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset asan >/dev/null
cmake --build build-asan -j "$(nproc)" --target gvdp_tests gvdp
export ASAN_OPTIONS="halt_on_error=1 abort_on_error=1 detect_leaks=1"
export UBSAN_OPTIONS="halt_on_error=1 print_stacktrace=1"
./build-asan/tests/gvdp_tests --gtest_brief=1 \
  --gtest_filter='Cli.*:MemoryEstimate.*:Bench.*:Paths.*:Image.*:Math.*:Lod.*:Cache.*:Serve*'
