#!/usr/bin/env bash
# Packs binaries built here for a call of the device tool (which carries 64 MiB with the tree):
# each NAME=PATH becomes carry/NAME/<file name> (NAME '.': carry/<file name>), without the
# __nv_relfatbin section - the relocatable device code kept for a later device link, which nothing
# reads at run time (a gvdp binary compresses to 6.1 MB instead of 15.6 MB; same images, GPU tests
# and sanitizers, H100, BENCHMARKS.md session 33) - and the shared libraries they need beyond the C
# and C++ runtimes (carry/lib), into one xz archive.
# Usage: scripts/carry.sh ARCHIVE NAME=PATH...
#   e.g. scripts/carry.sh carry/bins.txz .=build/src/gvdp .=build/tests/gvdp_tests \
#          nocdp=build-nocdp/src/gvdp main=/tmp/main/gvdp
# On the device machine (carry: ["carry"]):
#   tar xJf carry/bins.txz -C carry && export LD_LIBRARY_PATH=$PWD/carry/lib
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 ARCHIVE NAME=PATH..." >&2; exit 2; }
archive=$1
shift
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/lib"
for spec in "$@"; do
  name=${spec%%=*} path=${spec#*=}
  [ "$name" != "$spec" ] && [ -f "$path" ] || { echo "$0: not NAME=FILE: '$spec'" >&2; exit 2; }
  mkdir -p "$stage/$name"
  objcopy --remove-section __nv_relfatbin "$path" "$stage/$name/$(basename "$path")"
  # (a binary that needs none of them is fine: grep then matches nothing)
  ldd "$path" | awk '$3 ~ /^\// {print $3}' |
    { grep -Ev '/(libc|libm|libstdc\+\+|libgcc_s|ld-linux[^/]*)\.so' || true; } |
    while read -r lib; do cp -Lu "$lib" "$stage/lib/"; done
done
mkdir -p "$(dirname "$archive")"
tar cf - -C "$stage" . | xz -9 -T2 >"$archive"
echo "$archive: $(du -h "$archive" | cut -f1) ($*; libraries: $(ls "$stage/lib" | tr '\n' ' '))"
