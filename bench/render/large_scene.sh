#!/usr/bin/env bash
# A scene larger than memory through the texture cache (bench/results/render.md, "A scene of 20
# generated 4096² materials"): N distinct seeds of the random material family (textures/random_material.h)
# written at bench time as SIZE² texture sets (bench/mip/random_texture_set) into a temporary folder,
# one glTF scene that puts each on its own quad in a grid the camera sees, lit by a sun
# (bench/render/large_scene.py), then, for each filter of FILTERS (the first one cold and warm, the
# others warm: a record file with the BRDF pyramid serves every filter):
#   cold    `svbrdf-render --texture-cache CAP` into an empty MIP cache: it decodes each image, writes
#           it as a tiled file, builds each material's MIP data and writes its record file, one material
#           at a time (render/scene_mips_tiles.cpp), then renders from the files;
#   warm    the same command again: it opens the files;
#   memory  (MEMORY=1; the default where SIZE ≤ 1024) the images and MIP data held in memory, into a
#           MIP cache of its own: the reference the cached renders' EXRs must equal (idiff, thresholds 0).
# Per run: the wall seconds, the render's own seconds (its "rays in S s" line: the frame, not the
# set-up), the peak resident set (GNU time's %M) and the load average when it started; the resident
# set is also sampled every 2 s (the largest sample and when it came, against the stage the render
# printed last). Then the texture cache's report (the files and MB of texels it holds, at the cache's
# formats) against the cap, and the files' MB on disk. Nothing generated stays: the folder is removed
# unless KEEP=1.
#   bench/render/large_scene.sh BUILD [N=20] [SIZE=4096] [CAP=1024] [render options...]
# The sun is the scene's; a uniform environment (ENV, default 0.3) lights what it does not reach.
#   FILTERS="brdf level0" (default brdf)  MEMORY=0|1  WORK=DIR (default a new folder in /tmp)  KEEP=1
#   SIDES=warm (default "cold warm"): with the WORK and KEEP=1 of an earlier run, its warm side again
#   (the sets are made only where WORK lacks them).
set -euo pipefail
build=${1:?usage: bench/render/large_scene.sh BUILD [N=20] [SIZE=4096] [CAP=1024] [render options...]}
count=${2:-20} size=${3:-4096} cap=${4:-1024}
shift $(($# < 4 ? $# : 4))
render=$build/svbrdf-render generator=$build/bench/mip/random_texture_set
here=$(cd "$(dirname "$0")" && pwd)
for f in "$render" "$generator"; do [ -x "$f" ] || { echo "large_scene.sh: $f: not built" >&2; exit 2; }; done
memory=${MEMORY:-$((size <= 1024 ? 1 : 0))}
work=${WORK:-$(mktemp -d /tmp/svbrdf-large-scene.XXXXXX)}
mkdir -p "$work"
[ "${KEEP:-0}" = 1 ] || trap 'rm -rf "$work"' EXIT
calc() { awk "BEGIN { print $* }"; }
now() { date +%s.%N; }
load() { cut -d' ' -f1-3 /proc/loadavg; }

echo "nproc $(nproc); $(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //'); $(free -g | awk '/^Mem:/ { print $2 }') GB of memory;" \
  "$(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo '?'); $count materials of ${size}², cap $cap MB; in $work"
t0=$(now)
sets=()
for ((k = 1; k <= count; ++k)); do
  set=$work/sets/random-$k/random-$k.gltf
  sets+=("$set")
  [ -e "$set" ] && [ "$(iinfo "${set%.gltf}_normal.png" | sed -n 's/.* : *\([0-9]*\) x.*/\1/p')" = "$size" ] && continue
  "$generator" "$k" "$size" "$work/sets/random-$k" >"$work/draw.txt"
  cat "$work/draw.txt"
done
python3 "$here/large_scene.py" "$work/scene.gltf" "${sets[@]}"
printf 'generated in %.1f s: %s MB of PNG\n' "$(calc "$(now) - $t0")" "$(du -sm "$work/sets" | cut -f1)"

# Runs the render as side $1 with the MIP cache $2 and the rest of the arguments; prints its figures.
run() {
  local side=$1 cache=$2
  shift 2
  local log=$work/$side.txt trace=$work/$side.rss at
  at=$(load)
  local t1
  t1=$(now)
  /usr/bin/time -f 'peak %M' "$render" "$work/scene.gltf" --mip-cache "$cache" -o "$work/$side.exr" "$@" 2>"$log" &
  local pid=$!
  # The resident set every 2 s: GNU time's child is the render.
  : >"$trace"
  while kill -0 "$pid" 2>/dev/null; do
    local child
    child=$(pgrep -P "$pid" | head -1 || true)
    [ -n "$child" ] && awk -v t="$(calc "$(now) - $t1")" -v s="$(tr '\r' '\n' <"$log" | grep -v '^$' | tail -1 | cut -c1-60)" \
      '/^VmRSS/ { printf "%.0f %.0f %s\n", t, $2 / 1024, s }' "/proc/$child/status" >>"$trace" 2>/dev/null || true
    sleep 2
  done
  wait "$pid" || { echo "$side: the render failed:" >&2; tail -5 "$log" >&2; exit 1; }
  local wall secs kb report sample
  wall=$(calc "$(now) - $t1")
  secs=$(tr '\r' '\n' <"$log" | sed -n 's/.* rays in \([0-9.]*\) s .*/\1/p' | tail -1)
  kb=$(sed -n 's/^peak \([0-9]*\)$/\1/p' "$log")
  report=$(sed -n 's/.*texture cache: //p' "$log")
  sample=$(sort -k2,2n "$trace" | tail -1)
  printf '%-12s wall %7.1f s, render %6.2f s, peak %6.0f MB (load %s)\n' "$side" "$wall" "${secs:-0}" "$(calc "$kb / 1024")" "$at"
  [ -z "$sample" ] || printf '%-12s largest sample %s MB at %s s, during: %s\n' "" "$(cut -d' ' -f2 <<<"$sample")" \
    "$(cut -d' ' -f1 <<<"$sample")" "$(cut -d' ' -f3- <<<"$sample")"
  [ -z "$report" ] || printf '%-12s texture cache: %s\n' "" "$report"
  grep -h 'MIP maps:' "$log" | sed "s/^/$(printf '%-12s ' '')/" || true
}

# One cache for every filter: a record file with the BRDF pyramid serves them all, so the filters after
# the first start warm.
first=1
for filter in ${FILTERS:-brdf}; do
  opts=(--filter "$filter" --env "${ENV:-0.3}" "$@")
  sides=${SIDES:-cold warm}
  [ "$first" = 1 ] || sides=warm
  for side in $sides; do
    [ "$side" = cold ] && rm -rf "$work/cache"
    run "$filter-$side" "$work/cache" --texture-cache "$cap" "${opts[@]}"
  done
  if [ "$first" = 1 ]; then
    # The record files and the tiled images are both .tx files; a record file says so in its description.
    images=0 records=0
    for f in "$work/cache"/*.tx; do
      bytes=$(stat -c %s "$f")
      if iinfo -v "$f" | grep -q 'svbrdf mip records'; then records=$((records + bytes)); else images=$((images + bytes)); fi
    done
    printf 'on disk: %s MiB in all (tiled images %.1f MB, MIP records %.1f MB) against the cap %s MB\n' \
      "$(du -sm "$work/cache" | cut -f1)" "$(calc "$images / 1e6")" "$(calc "$records / 1e6")" "$cap"
  fi
  if [ "$memory" = 1 ]; then
    run "$filter-memory" "$work/memory" "${opts[@]}"
    for side in $sides; do
      idiff -q -fail 0 -warn 0 "$work/$filter-memory.exr" "$work/$filter-$side.exr" >/dev/null ||
        { echo "$filter-$side: DIFFERS from the in-memory render" >&2; exit 1; }
    done
    echo "$filter: the $sides EXRs equal the in-memory one, pixel for pixel"
  else
    echo "$filter: no in-memory render (MEMORY=0, the default above 1024², where a scene of many materials would not fit in memory)"
  fi
  first=0
done
