#!/usr/bin/env bash
# What starting svbrdf-render costs before it does anything (bench/results/render.md, "A warm texture
# cache: set-up against the frame"): `svbrdf-render --help` against the anchor, an empty C program
# linked against the same shared libraries (ldd's list, all of them: OpenImageIO pulls in every format's
# library), and against an empty program linked against none. Each is run ROUNDS times, alternating;
# prints every run's wall seconds and the medians.
#   bench/render/process_start.sh BUILD [ROUNDS=9]
set -euo pipefail
build=${1:?usage: bench/render/process_start.sh BUILD [ROUNDS=9]}
rounds=${2:-9}
render="$build/svbrdf-render"
work=$(mktemp -d /tmp/svbrdf-process-start.XXXXXX)
trap 'rm -rf "$work"' EXIT
echo "nproc $(nproc); $(lscpu | sed -n 's/^Model name: *//p'); load $(cut -d' ' -f1-3 /proc/loadavg)"
mapfile -t libs < <(ldd "$render" | awk '$2 == "=>" && $3 ~ /^\// { print $3 }')
echo "$render: ${#libs[@]} shared libraries"
echo 'int main(void) { return 0; }' >"$work/empty.c"
cc "$work/empty.c" -o "$work/bare"
args=()
for l in "${libs[@]}"; do args+=("-Wl,--no-as-needed" "$l"); done
cc "$work/empty.c" -o "$work/linked" "${args[@]}" -Wl,-rpath,"$(dirname "$(readlink -f "$render")")"
export LD_LIBRARY_PATH="$(printf '%s:' "${libs[@]%/*}")${LD_LIBRARY_PATH:-}"
timed() { /usr/bin/time -f %e -o "$work/t" "$@" >/dev/null 2>&1; cat "$work/t"; }
declare -A all=()
for ((r = 0; r < rounds; ++r)); do
  all[render]+="$(timed "$render" --help) "
  all[linked]+="$(timed "$work/linked") "
  all[bare]+="$(timed "$work/bare") "
done
median() { tr ' ' '\n' | grep . | sort -g | awk '{ v[NR] = $1 } END { print NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
for k in render linked bare; do echo "$k: ${all[$k]} median $(echo "${all[$k]}" | median) s"; done
echo "load $(cut -d' ' -f1-3 /proc/loadavg)"
