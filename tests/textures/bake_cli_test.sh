#!/bin/sh
# svbrdf-bake material end to end: bad input is one line on stderr, exit 2, nothing written; a good
# bake writes the texture set and prints the .gltf path.  Usage: bake_cli_test.sh PATH/TO/svbrdf-bake
bake=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

# expect_bad COMMAND...: the command exits 2 with one line on stderr and writes nothing.
expect_bad() {
  "$@" >"$tmp/out" 2>"$tmp/err"
  rc=$?
  [ "$rc" -eq 2 ] || fail "exit $rc (want 2) for: $*; stderr: $(cat "$tmp/err")"
  [ "$(wc -l <"$tmp/err")" -eq 1 ] || fail "stderr is not one line for: $*: $(cat "$tmp/err")"
  [ ! -e "$tmp/a" ] || fail "output written for: $*"
  echo "ok: $* -> $(cat "$tmp/err")"
}

expect_bad "$bake" material marble --out "$tmp/a"
expect_bad "$bake" material granite --variant blue --out "$tmp/a"
expect_bad "$bake" material granite --size 100 --out "$tmp/a"
expect_bad "$bake" material granite --size 0 --out "$tmp/a"
expect_bad "$bake" material granite --size 1048576 --out "$tmp/a"
expect_bad "$bake" material granite --mm-per-texel -1 --out "$tmp/a"
expect_bad "$bake" material granite --ocio-config "$tmp/none.ocio" --out "$tmp/a"
expect_bad env OCIO="$tmp/none.ocio" "$bake" material granite --out "$tmp/a"
echo x >"$tmp/file"
"$bake" material granite --size 8 --out "$tmp/file" >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] || fail "no exit 2 for an output path that is a file"
grep -q "$tmp/file" "$tmp/err" || fail "the message does not name the path: $(cat "$tmp/err")"

"$bake" material metal-tray --variant brass --size 16 --seed 3 --out "$tmp/ok" >"$tmp/out" 2>"$tmp/err" || fail "good bake failed: $(cat "$tmp/err")"
[ "$(cat "$tmp/out")" = "$tmp/ok/metal-tray.gltf" ] || fail "stdout: $(cat "$tmp/out")"
for f in metal-tray.gltf metal-tray_base_color.png metal-tray_metallic_roughness.png metal-tray_normal.png; do
  [ -s "$tmp/ok/$f" ] || fail "missing $f"
done
[ ! -s "$tmp/err" ] || fail "a fast bake printed progress: $(cat "$tmp/err")"
echo "ok: good bake"
