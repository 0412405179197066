#!/usr/bin/env bash
# Configures (CMake preset "default": CUDA when nvcc is found) and builds.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v nvcc >/dev/null && [ -x /usr/local/cuda/bin/nvcc ]; then
  export PATH="$PATH:/usr/local/cuda/bin"
fi
cmake --preset default >/dev/null
cmake --build build -j "$(nproc)"
