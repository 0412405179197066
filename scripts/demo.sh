#!/usr/bin/env bash
# Newcomer's path, step 1: install what is missing, build, and render a walkthrough of the default
# scene to out/frame_*.png with the time of every frame (on the GPU when there is one, else a
# small CPU render). Extra arguments go to `gvdp render`.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
./build/src/gvdp render --out out "$@"
