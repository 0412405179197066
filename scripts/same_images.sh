#!/usr/bin/env bash
# Does an optimisation change an image? Renders every scene's walkthrough with two gvdp binaries
# (same backend and scheduler) and compares the PNG files byte for byte (the encoder is
# deterministic: equal pixels, equal files). Prints one line per scene; exits 1 if any differ.
# Usage: scripts/same_images.sh OLD_BIN NEW_BIN [backend] [scheduler] [frames] [WxH]
#   (default: cuda sp 10 750x500; half the bench's size keeps PNG encoding short)
#   NEW_ARGS="--prefetch 4": more flags for the new binary (an option that must not change images)
set -uo pipefail
# A GPU hang ends its run in a minute with a line naming where it waited (base/watchdog.h),
# instead of taking the rest of the call.
export GVDP_WATCHDOG_S="${GVDP_WATCHDOG_S:-60}"
old=$1 new=$2 backend=${3:-cuda} scheduler=${4:-sp} frames=${5:-10} size=${6:-750x500}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
status=0
for scene in perlin fbm forest random-spheres aligned-spheres; do
  for which in old new; do
    bin=$old extra=()
    [ "$which" = new ] && bin=$new && read -ra extra <<<"${NEW_ARGS:-}"
    if ! "$bin" render "${extra[@]}" --backend "$backend" --scheduler "$scheduler" --scene "$scene" \
      --frames "$frames" --width "${size%x*}" --height "${size#*x}" \
      --out "$tmp/${which}_$scene" >/dev/null 2>"$tmp/err"; then
      echo "$scene: $which binary failed: $(tail -n 1 "$tmp/err")"
      status=1
      continue 2
    fi
  done
  differ=0
  for f in "$tmp/old_$scene"/frame_*.png; do
    cmp -s "$f" "$tmp/new_$scene/$(basename "$f")" || differ=$((differ + 1))
  done
  echo "$scene: $differ of $frames frames differ ($backend $scheduler, $size${NEW_ARGS:+, new: $NEW_ARGS})"
  [ "$differ" -eq 0 ] || status=1
done
exit $status
