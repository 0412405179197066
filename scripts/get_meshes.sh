#!/usr/bin/env bash
# Fetches the meshes of Debian's CGAL demo data into data/meshes/ (gitignored), without
# installing the package or its dependencies: `apt-get download libcgal-demo` (the .deb alone),
# `dpkg -x` into a temporary folder, then the meshes out of its data.tar.gz. Then, with a built
# gvdp (GVDP=path, default build-cpu/src/gvdp then build/src/gvdp), a mesh of over a million
# triangles: the bunny (75 408 triangles) subdivided twice, 1 206 528 triangles, as binary PLY.
#
#   scripts/get_meshes.sh            # data/meshes/*.off and data/meshes/bunny_x16.ply
#   GVDP=/path/to/gvdp scripts/get_meshes.sh
#
# The tests never use these files: they make their meshes themselves (tests/mesh_test_util.h).
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
out="$repo/data/meshes"
# Well-known models among the package's 139 OFF files (data/meshes/ of CGAL 5.5).
meshes="bunny00 armadillo ChineseDragon-10kv elephant refined_elephant fandisk_large eight \
  camel bull cow dino lion mushroom anchor_dense sphere966 cube"

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"
(cd "$tmp" && apt-get download libcgal-demo >/dev/null)
dpkg -x "$tmp"/libcgal-demo_*.deb "$tmp/x"
data=$(find "$tmp/x" -name data.tar.gz | head -n 1)
[ -n "$data" ] || { echo "get_meshes: no data.tar.gz in libcgal-demo" >&2; exit 1; }
members=""
for m in $meshes; do members="$members data/meshes/$m.off"; done
# shellcheck disable=SC2086
tar xzf "$data" -C "$tmp" $members
for m in $meshes; do cp "$tmp/data/meshes/$m.off" "$out/"; done
echo "get_meshes: $(echo $meshes | wc -w) meshes in $out"

gvdp=${GVDP:-}
for candidate in "$repo/build-cpu/src/gvdp" "$repo/build/src/gvdp"; do
  [ -z "$gvdp" ] && [ -x "$candidate" ] && gvdp=$candidate
done
if [ -n "$gvdp" ]; then
  "$gvdp" mesh subdivide --times 2 "$out/bunny00.off" "$out/bunny_x16.ply"
else
  echo "get_meshes: no gvdp binary (build it, or set GVDP=): skipped the 1.2 M-triangle bunny"
fi
