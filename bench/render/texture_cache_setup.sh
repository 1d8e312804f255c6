#!/usr/bin/env bash
# A warm out-of-core render's set-up against its frame (bench/results/render.md, "A warm texture
# cache: set-up against the frame"): svbrdf-render --texture-cache with the cache's image and record
# files already written, and the same render with the images in memory and the MIP cache warm, each
# against its own 64-spp frame time, the anchor. Set-up is the program's wall time less the frame time
# it reports ("... rays in S s"): reading the scene, its images (decoded, or found in the cache), the
# MIP data, the BVH, and writing the EXR. The first two runs fill the caches and are not counted; then
# ROUNDS rounds alternate the two sides so that both see the same machine. With a second build, its
# program is measured the same way in the same run (in its own caches), for a before and after.
#   bench/render/texture_cache_setup.sh BUILD SCENE.gltf [ROUNDS=2] [OTHER_BUILD] -- [render options...]
set -euo pipefail
build=$1 scene=$2 rounds=${3:-2} other=${4:-}
# The render options follow the first "--" (OTHER_BUILD may be left out before it).
if [ "$other" = -- ]; then
  other=
  shift $(($# < 3 ? $# : 3))
else
  shift $(($# < 4 ? $# : 4))
fi
[ "${1:-}" = -- ] && shift
out=$(mktemp -d /tmp/svbrdf-texture-cache-setup.XXXXXX)
trap 'rm -rf "$out"' EXIT
echo "nproc $(nproc); $(lscpu | sed -n 's/^Model name: *//p'); load $(cut -d' ' -f1-3 /proc/loadavg)"
one() {  # label, build, cache folder, extra arguments...
  local label=$1 b=$2 cache=$3
  shift 3
  local start end
  start=$(date +%s.%N)
  "$b/svbrdf-render" "$scene" "$@" --mip-cache "$cache" -o "$out/out.exr" 2>"$out/err"
  end=$(date +%s.%N)
  local frame report
  frame=$(tr '\r' '\n' <"$out/err" | sed -n 's/.* rays in \([0-9.]*\) s .*/\1/p' | tail -1)
  report=$(sed -n 's/.*texture cache: [0-9]* files in [^ ]* \((images: [^)]*)\).*/\1/p; s/.*MIP maps: \([0-9]* read\) from the MIP cache [^ ]*, \([0-9]* built\)/MIP maps \1, \2;/p' \
    "$out/err" | tr '\n' ' ')
  awk -v l="$label" -v s="$start" -v e="$end" -v f="$frame" -v r="$report" \
    'BEGIN { w = e - s; printf "| %s | %.2f | %.2f | %.2f | %.1f %% | %s|\n", l, w, f, w - f, 100 * (w - f) / f, r }'
}
builds=("$build")
[ -n "$other" ] && builds+=("$other")
for b in "${builds[@]}"; do
  c="$out/cache-$(basename "$(dirname "$b")")-$(basename "$b")"
  # The in-memory render stores the MIP cache's entry; the out-of-core one then reads it, writes the
  # record files and the images' files.
  "$b/svbrdf-render" "$scene" "$@" --mip-cache "$c" -o "$out/fill.exr" 2>/dev/null
  "$b/svbrdf-render" "$scene" "$@" --mip-cache "$c" --texture-cache -o "$out/fill.exr" 2>/dev/null
done
echo "| run | wall s | frame s | set-up s | set-up / frame | report |"
echo "|---|---|---|---|---|---|"
for ((r = 0; r < rounds; ++r)); do
  for b in "${builds[@]}"; do
    c="$out/cache-$(basename "$(dirname "$b")")-$(basename "$b")"
    one "$b, in memory, MIP cache warm" "$b" "$c" "$@"
    one "$b, --texture-cache, warm" "$b" "$c" "$@" --texture-cache
  done
done
echo "load $(cut -d' ' -f1-3 /proc/loadavg)"
