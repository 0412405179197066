#!/usr/bin/env bash
# The package as a user meets it: install the build (scripts/build.sh) under build/prefix, build
# examples/custom_producer against it with find_package(gvdp), render a few frames of its gyroid.
# Usage: scripts/example.sh [cpu|cuda] [scheduler] [frames]   (PNGs in build/example-out)
set -euo pipefail
cd "$(dirname "$0")/.."
backend=${1:-cpu} scheduler=${2:-sp} frames=${3:-4}
cmake --install build --prefix build/prefix > /dev/null
cmake -S examples/custom_producer -B build/example -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$PWD/build/prefix" > /dev/null
cmake --build build/example
rm -rf build/example-out && mkdir -p build/example-out
build/example/custom_producer "$backend" "$scheduler" "$frames" build/example-out
written=$(find build/example-out -name 'gyroid_*.png' | wc -l)
if [ "$written" -ne "$frames" ]; then
  echo "example: $written of $frames frames written" >&2
  exit 1
fi
echo "example: $frames frames of the gyroid ($backend $scheduler) in build/example-out"
