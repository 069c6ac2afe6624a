#!/usr/bin/env bash
# Light-group layers and a relightable transport are counted before they are allocated, with
# the EXR that will hold them: under an address-space limit the render is refused at once with
# the figures (it grew to 23 GiB, or was lost at the write), and under a limit of what the
# check says it needs (plus what the process already holds, and 5% and 256 MiB for thread
# stacks and allocator arenas) it completes: the count is an upper bound.
#
#   memory_layers_and_transport.sh NXRENDER
set -uo pipefail
nxrender="$1"
d="$(mktemp -d)"
trap 'rm -rf "$d"' EXIT
cd "$d"
fail() { echo "FAIL: $*"; exit 1; }

# N small emitting spheres, each its own light group, and a fluorescent wall behind them.
scene() {
  local n=$1 w=$2 h=$3
  echo "<scene><settings><xres>$w</xres><yres>$h</yres><mode>spectral_mcpt</mode><sampl>1</sampl></settings>"
  echo "<camera><position>0,0,-10</position><look_at>0,0,0</look_at></camera>"
  for ((i = 0; i < n; i++)); do
    echo "<sphere group=\"g$i\"><center>$((i % 40 - 20)).1,$((i / 40 - 2)).1,0</center><radius>0.05</radius><material>matte</material><reflectance>0</reflectance><emission>$((1 + i % 7))</emission></sphere>"
  done
  echo "<plane><normal>0,0,-1</normal><distance>-1</distance><material>matte</material><reflectance>0.5</reflectance><fluorescence><absorption>blue</absorption><stokes>100</stokes></fluorescence></plane></scene>"
}
scene 400 64 48 > groups.scn
scene 60 32 24 > transport.scn

check() { # SCENE WHAT OPTION...
  local scn=$1 what=$2; shift 2
  local out start end needs inuse limit
  start=$(date +%s%N)
  out="$( (ulimit -v 700000 && exec "$nxrender" "$@" -o x.exr "$scn") 2>&1)" && fail "$what: accepted under 0.67 GiB"
  end=$(date +%s%N)
  grep -q "expected $what and the EXR holding them whose buffers fit in memory" <<<"$out" || fail "message: $out"
  [ ! -e x.exr ] || fail "$what: a file was written"
  [ $(((end - start) / 1000000)) -lt 5000 ] || fail "$what: refused only after $(((end - start) / 1000000)) ms"
  needs=$(grep -o 'needs [0-9.]* GiB' <<<"$out" | grep -o '[0-9.]*')
  inuse=$(grep -o '[0-9.]* GiB of it in use' <<<"$out" | grep -o '^[0-9.]*')
  limit=$(awk -v n="$needs" -v u="$inuse" 'BEGIN { printf "%d", ((n + u) * 1.05 + 0.25) * 1048576 }')
  (ulimit -v "$limit" && exec "$nxrender" "$@" -o x.exr "$scn") >/dev/null 2>"$d/err" \
    || fail "$what: failed under the limit its check passed ($limit KiB): $(cat "$d/err")"
  [ -s x.exr ] || fail "$what: nothing written"
  rm -f x.exr x.png
  echo "$what: refused under 0.67 GiB, completed under $limit KiB (needs $needs GiB + $inuse in use)"
}
check groups.scn "component layers" --threads 2 --aov lightgroups
check transport.scn "a transport" --threads 2 --relightable
