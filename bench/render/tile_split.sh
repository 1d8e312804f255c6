#!/usr/bin/env bash
# What splitting a frame into tiles costs (bench/results/render.md, "Tiles against one render"): one
# render of the whole frame against N tile renders (--tile I/N, one after another, as N machines
# would run them) plus their merge, alternating ROUNDS times in one run so that both see the same
# machine. Prints each run's wall seconds and the ratio of the sums; the merged EXR is checked
# against the whole render's, pixel for pixel (idiff, thresholds 0).
#   bench/render/tile_split.sh BUILD SCENE.gltf [N=4] [ROUNDS=2] [render options...]
set -euo pipefail
build=$1 scene=$2 n=${3:-4} rounds=${4:-2}
shift $(($# < 4 ? $# : 4))
render=$build/svbrdf-render
out=$(mktemp -d /tmp/svbrdf-tile-bench.XXXXXX)
trap 'rm -rf "$out"' EXIT
now() { date +%s.%N; }
calc() { awk "BEGIN { print $* }"; }
"$render" "$scene" -q "$@" -o "$out/warm.exr"  # fills the MIP cache: both sides start warm
whole_sum=0 split_sum=0
for ((r = 0; r < rounds; ++r)); do
  t0=$(now)
  "$render" "$scene" -q "$@" -o "$out/whole.exr"
  t1=$(now)
  for ((i = 0; i < n; ++i)); do "$render" "$scene" -q "$@" --tile "$i/$n" -o "$out/t$i.exr"; done
  t2=$(now)
  "$render" --merge -q -o "$out/merged.exr" "$out"/t*.exr
  t3=$(now)
  idiff -q -fail 0 -warn 0 "$out/whole.exr" "$out/merged.exr" >/dev/null
  whole=$(calc "$t1 - $t0") tiles=$(calc "$t2 - $t1") merge=$(calc "$t3 - $t2")
  printf 'round %d: whole %.2f s; %d tiles %.2f s + merge %.2f s\n' "$r" "$whole" "$n" "$tiles" "$merge"
  whole_sum=$(calc "$whole_sum + $whole") split_sum=$(calc "$split_sum + $tiles + $merge")
done
printf 'tiles + merge against whole: %.3f\n' "$(calc "$split_sum / $whole_sum")"
