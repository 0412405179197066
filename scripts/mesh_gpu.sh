#!/usr/bin/env bash
# On a GPU machine, with binaries in carry/ and meshes in carry/meshes (scripts/get_meshes.sh):
# issue 15's whole check. The mesh tests (GPU schedulers equal, PSNR against the CPU and the ray
# cast), memcheck on every scheduler over a mesh world, the kd-tree of a >= 1 M-triangle mesh,
# the mesh walkthrough against perlin's (bench, 1500x1000), and the README's pictures (frames
# with their ray-cast references). Writes to $OUT (or out/mesh): summary.txt, and mesh_gpu.tar
# holding tests.txt, memcheck.txt, kdtree.txt, bench_*.md/json and the pictures (*.png).
set -uo pipefail
cd "$(dirname "$0")/.."
out="${OUT:-out/mesh}"
mkdir -p "$out"
export LD_LIBRARY_PATH="$PWD/carry/lib" GVDP_BIN="$PWD/carry/gvdp"
gvdp=./carry/gvdp m=carry/meshes
nvidia-smi -L | tee "$out/summary.txt"
timeout 300 ./carry/gvdp_tests --gtest_filter='Mesh*:Paths.*' >"$out/tests.txt" 2>&1
echo "tests rc=$? $(grep -a 'PASSED\|FAILED' "$out/tests.txt" | tr '\n' ' ')" | tee -a "$out/summary.txt"
grep -a "dB" "$out/tests.txt" | tee -a "$out/summary.txt"
for s in sp pt dp graph; do
  for lattice in 0 2; do
    mv=orbit
    [ "$lattice" = 2 ] && mv=walkthrough
    timeout 120 compute-sanitizer --tool memcheck --error-exitcode 9 "$gvdp" render --backend cuda \
      --scheduler "$s" --mesh "$m/bunny00.off" --lattice "$lattice" --movement "$mv" --frames 2 \
      --width 200 --height 120 --out "/tmp/mc_${s}_$lattice" >>"$out/memcheck.txt" 2>&1
    echo "memcheck $s lattice $lattice: rc=$?" | tee -a "$out/summary.txt"
  done
done
grep -a "ERROR SUMMARY" "$out/memcheck.txt" | sort | uniq -c | tee -a "$out/summary.txt"
"$gvdp" mesh subdivide --times 2 "$m/bunny00.off" /tmp/bunny_x16.ply | tee -a "$out/summary.txt"
timeout 200 "$gvdp" kdtree --mesh /tmp/bunny_x16.ply --builders gpu --repeat 5 >"$out/kdtree.txt" 2>&1
timeout 100 "$gvdp" kdtree --mesh "$m/bunny00.off" --builders gpu --repeat 5 >>"$out/kdtree.txt" 2>&1
grep -a "gpu" "$out/kdtree.txt" | tee -a "$out/summary.txt"
bench() {
  local name=$1
  shift
  timeout 240 "$gvdp" bench --backend cuda --schedulers sp,pt --out "$out/bench_$name.json" \
    --markdown "$out/bench_$name.md" "$@" >/dev/null 2>"$out/bench_$name.err"
  echo "bench $name rc=$?" | tee -a "$out/summary.txt"
  cat "$out/bench_$name.md" >>"$out/summary.txt"
}
bench lattice --scenes perlin,mesh --mesh "$m/bunny00.off" --lattice 2 --movements walkthrough \
  --frames 16 --warmup 4
bench orbit --scenes mesh --mesh "$m/bunny00.off" --movements orbit
bench x16 --scenes mesh --mesh /tmp/bunny_x16.ply --movements orbit --frames 16 --warmup 4
picture() {
  local name=$1
  shift
  timeout 120 "$gvdp" render --backend cuda --scheduler pt --frames 1 --width 1200 --height 800 \
    --reference --out "/tmp/pic_$name" "$@" | grep -a "PSNR\|frame" | tee -a "$out/summary.txt"
  cp "/tmp/pic_$name/frame_0000.png" "$out/${name}.png"
  cp "/tmp/pic_$name/reference_0000.png" "$out/${name}_reference.png"
}
picture bunny --mesh "$m/bunny00.off" --movement orbit
picture dragon --mesh "$m/ChineseDragon-10kv.off" --movement orbit
picture field --mesh "$m/bunny00.off" --lattice 2 --movement walkthrough
tar cf /tmp/mesh_gpu.tar -C "$out" --exclude=summary.txt . && find "$out" -mindepth 1 \
  ! -name summary.txt -delete && mv /tmp/mesh_gpu.tar "$out/"
