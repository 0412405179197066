#!/usr/bin/env bash
# ThreadSanitizer build of the CPU backend (preset "tsan") and the tests of the concurrent CPU
# protocols: dp's task queue with its ray locks and brick publication, sp's parallel passes, pt's
# rings and wait lists, and frames past a budget's deadline (claims no ray waits for).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset tsan >/dev/null
cmake --build build-tsan -j "$(nproc)" --target gvdp_tests gvdp
TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" ./build-tsan/tests/gvdp_tests \
  --gtest_filter='*DpCpu*:*PtCpu*:PtRing.*:PtWaitList.*:Cache.*:*SpTest.IsDeterministic*:*SpTest.Tiny*:BudgetCpu.*:ServeLoop.*:ServeHttp.*:ThreadPool.*:ImportanceCpu.NodeCounts*' --gtest_brief=1
