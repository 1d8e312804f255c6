#!/usr/bin/env bash
# The BRDF MIP's cold build against `maketx`, and its texture decoding against `oiiotool`, on 4096²
# texture sets (bench/results/mip.md, "Build time"). Each round runs, one after another on the same
# machine and each with the machine's thread count:
#   maketx   ordinary MIP maps of every texture the build reads, one file after another (each maketx
#            uses every thread, as the build does; the sum is the set's time, the base colour's alone
#            the former anchor);
#   svbrdf   `svbrdf-bake mip` of the set, from the files to the written MIP file; its summary line
#            gives the stages (decoded / built / the BRDF pyramid / written);
#   oiiotool the same files read and decoded to float in one process (`-i:now=1:type=float`), nothing
#            written: the anchor of the decode stage.
# Prints every run (wall and CPU seconds, the load when it started), then the medians and ratios.
#   bench/mip/cold_build.sh BUILD [ROUNDS=3] [WORK=/tmp/svbrdf-cold-build]
# The sets are made in WORK when missing: the 4096² metal tray (`svbrdf-bake material`) and seed 4 of
# the random family (bench/mip/random_texture_set). Pass the MIP files of another build with
# COMPARE=DIR (DIR/SET.exr) to check this build's files against them, pixels and all; SETS="tray" (or
# "random") runs one set only.
set -euo pipefail
build=${1:?usage: bench/mip/cold_build.sh BUILD [ROUNDS=3] [WORK]}
rounds=${2:-3}
work=${3:-/tmp/svbrdf-cold-build}
threads=$(nproc)
mkdir -p "$work"
[ -e "$work/tray/metal-tray_normal.png" ] ||
  "$build/svbrdf-bake" material metal-tray --size 4096 --out "$work/tray" >/dev/null
[ -e "$work/random/random-4_normal.png" ] || "$build/bench/mip/random_texture_set" 4 4096 "$work/random" >/dev/null
declare -A prefix=([tray]="$work/tray/metal-tray" [random]="$work/random/random-4")
maps=(base_color metallic_roughness normal)

calc() { awk "BEGIN { print $* }"; }
median() { tr ' ' '\n' | grep . | sort -g | awk '{ v[NR] = $1 } END { print NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
load() { cut -d' ' -f1 /proc/loadavg; }
# Runs a command; sets $wall and $cpu (user + system seconds) from GNU time.
timed() {
  /usr/bin/time -f '%e %U %S' -o "$work/time" "$@"
  read -r wall user sys <"$work/time"
  cpu=$(calc "$user + $sys")
}

echo "nproc $threads; $(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //'); $(git -C "$(dirname "$0")" rev-parse --short HEAD 2>/dev/null || echo '?')"
echo "| set | round | load | maketx base colour s | maketx set s (cpu) | svbrdf-bake mip s (cpu) | decoded / built / BRDF / written s | oiiotool read s (cpu) |"
echo "|---|---|---|---|---|---|---|---|"
declare -A all
sets=${SETS:-tray random}
for set in $sets; do
  p=${prefix[$set]}
  for ((r = 1; r <= rounds; ++r)); do
    at=$(load)
    set_wall=0 set_cpu=0 base=0
    for m in "${maps[@]}"; do
      timed maketx --threads "$threads" "${p}_$m.png" -o "$work/$m.tx"
      [ "$m" = base_color ] && base=$wall
      set_wall=$(calc "$set_wall + $wall") set_cpu=$(calc "$set_cpu + $cpu")
    done
    timed "$build/svbrdf-bake" mip --base-color "${p}_base_color.png" --metallic-roughness "${p}_metallic_roughness.png" \
      --normal "${p}_normal.png" --out "$work/$set.exr" >"$work/line"
    sv_wall=$wall sv_cpu=$cpu
    stages=$(sed -n 's/.*decoded in \([0-9.]*\) s, built in \([0-9.]*\) s, the BRDF pyramid \([0-9.]*\) s, written in \([0-9.]*\) s.*/\1 \2 \3 \4/p' "$work/line")
    read -r decoded built brdf written <<<"$stages"
    timed oiiotool --threads "$threads" -i:now=1:type=float "${p}_base_color.png" -i:now=1:type=float \
      "${p}_metallic_roughness.png" -i:now=1:type=float "${p}_normal.png" 2>/dev/null
    printf '| %s | %d | %s | %.2f | %.2f (%.1f) | %.2f (%.1f) | %s / %s / %s / %s | %.2f (%.1f) |\n' "$set" "$r" "$at" "$base" \
      "$set_wall" "$set_cpu" "$sv_wall" "$sv_cpu" "$decoded" "$built" "$brdf" "$written" "$wall" "$cpu"
    all[$set.base]+=" $base" all[$set.maketx]+=" $set_wall" all[$set.svbrdf]+=" $sv_wall"
    all[$set.decoded]+=" $decoded" all[$set.oiiotool]+=" $wall"
  done
  if [ -n "${COMPARE:-}" ]; then
    idiff -a -fail 0 -warn 0 "$COMPARE/$set.exr" "$work/$set.exr" >/dev/null &&
      echo "$set: every level's pixels identical to $COMPARE/$set.exr" || echo "$set: DIFFERS from $COMPARE/$set.exr"
  fi
done
echo
echo "| set | maketx base colour | maketx set | svbrdf-bake mip | / set | / base colour | decoded | oiiotool read | decoded / oiiotool |"
echo "|---|---|---|---|---|---|---|---|---|"
for set in $sets; do
  b=$(median <<<"${all[$set.base]}") m=$(median <<<"${all[$set.maketx]}") s=$(median <<<"${all[$set.svbrdf]}")
  d=$(median <<<"${all[$set.decoded]}") o=$(median <<<"${all[$set.oiiotool]}")
  printf '| %s | %.2f | %.2f | %.2f | **%.2f×** | %.2f× | %.2f | %.2f | **%.2f×** |\n' "$set" "$b" "$m" "$s" \
    "$(calc "$s / $m")" "$(calc "$s / $b")" "$d" "$o" "$(calc "$d / $o")"
done
