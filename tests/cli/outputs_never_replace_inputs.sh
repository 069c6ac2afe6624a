#!/usr/bin/env bash
# No program's output may replace one of its inputs (nxrelight in.exr -o in.exr replaced a
# relightable file with its relit image; nxcamera -o in.exr in.exr the same): the same path,
# ./ spellings, symlinks and hard links are refused with exit 1 and the input left unchanged;
# a render resumed into the file it continues is the one exception.
#
#   outputs_never_replace_inputs.sh BIN_DIR SOURCE_DIR
set -uo pipefail
bin="$1" src="$2"
d="$(mktemp -d)"
trap 'rm -rf "$d"' EXIT
cd "$d"
fail() { echo "FAIL: $*"; exit 1; }

scene="$src/scenes/white_floor.scn"
"$bin/nxrender" --threads 2 --spp 1 --relightable -o in.exr "$scene" 2>/dev/null || fail "render"
ln -s in.exr link.exr
ln in.exr hard.exr
sum="$(md5sum < in.exr)"

# refused CMD...: the program's error status (nxcompare's is 2: 1 means a threshold failed),
# a message naming the input, the input untouched, no stray files.
refused() {
  local out status want=1
  out="$("$@" 2>&1)"
  status=$?
  [[ "$1" == */nxcompare ]] && want=2
  [ "$status" = "$want" ] || fail "status $status: $*: $out"
  grep -q "expected an output" <<<"$out" || fail "no clear message: $*: $out"
  [ "$(md5sum < in.exr)" = "$sum" ] || fail "in.exr changed by: $*"
  ! ls -A | grep -q nxtmp || fail "temporary file left by: $*"
}
for target in in.exr ./in.exr link.exr hard.exr "$d/in.exr"; do
  refused "$bin/nxrelight" in.exr --light default=D65 -o "$target"
  refused "$bin/nxcamera" -o "$target" in.exr
  refused "$bin/nxmerge" -o "$target" in.exr
done
# nxcompare: its figure over its mask, its table over its response file.
cp in.png mask.png || fail "no preview"
refused "$bin/nxcompare" in.exr in.exr --mask mask.png --plot mask.png
printf 'nm,v\n400,1\n700,1\n' > lamp.csv
refused "$bin/nxcompare" in.exr in.exr --srf lamp.csv --csv lamp.csv
# nxrender: a file the scene reads (here its environment map) is no output.
cat > env.scn <<SCN
<scene><settings><xres>8</xres><yres>6</yres><mode>spectral_mcpt</mode><sampl>1</sampl>
<bands>410:990:20</bands></settings>
<camera><position>0,0,0</position><look_at>0,0,1</look_at></camera>
<light type="environment"><file>in.exr</file></light></scene>
SCN
refused "$bin/nxrender" --threads 2 -o link.exr env.scn
# nxrender: an adaptive round over its pilot is refused, a resume into itself is not.
"$bin/nxrender" --threads 2 --spp 2 -o pilot.exr "$scene" 2>/dev/null || fail "pilot"
psum="$(md5sum < pilot.exr)"
out="$("$bin/nxrender" --threads 2 --spp 4 --target-error 0.5 --adaptive-from pilot.exr \
  -o pilot.exr "$scene" 2>&1)"
[ $? = 1 ] && grep -q "expected an output" <<<"$out" || fail "adaptive round over its pilot: $out"
[ "$(md5sum < pilot.exr)" = "$psum" ] || fail "pilot.exr changed"
"$bin/nxrender" --threads 2 --spp 2 --resume pilot.exr -o pilot.exr "$scene" 2>/dev/null \
  || fail "resume into itself refused"
echo "no output replaced an input"
