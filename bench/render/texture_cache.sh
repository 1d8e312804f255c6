#!/usr/bin/env bash
# What reading the textures out of core costs (bench/results/render.md, "Out-of-core textures"): the
# same render with the images in memory (the anchor) and through the texture cache capped at 25 %,
# 50 % and 100 % of the scene's texture memory at the cache's formats, the MIP data's records among
# it under a MIP filter (what the render reports; a cap is at least TextureTiles::kMinMegabytes),
# alternating ROUNDS times in one run so that every side
# sees the same machine. Per side: the render's own seconds (its "rays in S s" line: the frame, not
# the set-up), the whole run's wall seconds, and the peak resident set (GNU time's %M); then each
# side's render seconds over the in-memory one's. Every cached EXR is checked against the in-memory
# one, pixel for pixel (idiff, thresholds 0).
#   bench/render/texture_cache.sh BUILD SCENE.gltf [ROUNDS=2] [render options...]
set -euo pipefail
build=$1 scene=$2 rounds=${3:-2}
shift $(($# < 3 ? $# : 3))
render=$build/svbrdf-render
out=$(mktemp -d /tmp/svbrdf-texture-cache-bench.XXXXXX)
trap 'rm -rf "$out"' EXIT
calc() { awk "BEGIN { print $* }"; }
now() { date +%s.%N; }
# Writes the cache's files and, under brdf, the in-memory side's MIP cache entries (a warm start for
# every side), and reads the scene's texture memory.
"$render" "$scene" "$@" --mip-cache "$out/cache" -o "$out/warm-memory.exr" 2>/dev/null
"$render" "$scene" "$@" --mip-cache "$out/cache" --texture-cache -o "$out/warm.exr" 2>"$out/warm.txt"
mb=$(sed -n 's/.*texture cache: [0-9]* files in .*, \([0-9.]*\) MB of texels.*/\1/p' "$out/warm.txt")
[ -n "$mb" ] || { echo "no texture cache report in $out/warm.txt" >&2; exit 1; }
printf 'texture memory at the cache formats: %s MB\n' "$mb"
sides=(memory 25 50 100)
declare -A render_sum wall_sum peak
for s in "${sides[@]}"; do render_sum[$s]=0 wall_sum[$s]=0 peak[$s]=0; done
for ((r = 0; r < rounds; ++r)); do
  for s in "${sides[@]}"; do
    cache=()
    if [ "$s" != memory ]; then
      cap=$(calc "($mb * $s / 100 < 10) ? 10 : $mb * $s / 100")
      cache=(--texture-cache "$cap")
    fi
    t0=$(now)
    /usr/bin/time -f 'peak %M' "$render" "$scene" "$@" --mip-cache "$out/cache" "${cache[@]}" -o "$out/$s.exr" \
      2>"$out/$s.txt"
    t1=$(now)
    secs=$(tr '\r' '\n' <"$out/$s.txt" | sed -n 's/.* rays in \([0-9.]*\) s .*/\1/p' | tail -1)
    kb=$(sed -n 's/^peak \([0-9]*\)$/\1/p' "$out/$s.txt")
    [ "$s" = memory ] || idiff -q -fail 0 -warn 0 "$out/memory.exr" "$out/$s.exr" >/dev/null
    printf 'round %d %-6s render %.2f s, wall %.2f s, peak %.0f MB\n' "$r" "$s" "$secs" "$(calc "$t1 - $t0")" \
      "$(calc "$kb / 1024")"
    render_sum[$s]=$(calc "${render_sum[$s]} + $secs")
    wall_sum[$s]=$(calc "${wall_sum[$s]} + $t1 - $t0")
    peak[$s]=$(calc "($kb > ${peak[$s]}) ? $kb : ${peak[$s]}")
  done
done
for s in "${sides[@]}"; do
  printf '%-6s render %.2f s (%.3f of in memory), wall %.2f s, peak %.0f MB\n' "$s" \
    "$(calc "${render_sum[$s]} / $rounds")" "$(calc "${render_sum[$s]} / ${render_sum[memory]}")" \
    "$(calc "${wall_sum[$s]} / $rounds")" "$(calc "${peak[$s]} / 1024")"
done
