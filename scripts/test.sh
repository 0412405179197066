#!/usr/bin/env bash
# Newcomer's path, step 2 (and CI): install what is missing, build, run every test. GPU tests
# skip at run time when no CUDA device is present.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
ctest --test-dir build --output-on-failure -j "$(nproc)"
