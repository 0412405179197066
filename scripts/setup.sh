#!/usr/bin/env bash
# Installs the Debian packages gvdp needs, only those missing (idempotent). CUDA (nvcc) is
# optional and not installed here: with it the CUDA backend is built, without it the CPU one.
set -euo pipefail
# The viewer (gvdp serve): cpp-httplib, libjpeg-turbo; its browser test: chromium-headless-shell;
# render --video: ffmpeg.
packages=(cmake ninja-build g++ pkg-config libgtest-dev libcli11-dev nlohmann-json3-dev libstb-dev zlib1g-dev
  clang-format libcpp-httplib-dev libturbojpeg0-dev chromium-headless-shell ffmpeg)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
  echo "setup: all packages present"
fi
