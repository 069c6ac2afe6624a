#!/usr/bin/env bash
# Repeatable options take one value per occurrence, never the positional arguments after them:
# the documented "nxrender --relightable --relight-for led=... --relight-for led=D65 scene.scn"
# (it failed with "scene is required") and nxrelight's repeated --light before its input.
# Usage: repeatable_options.sh BIN_DIR SOURCE_DIR
set -u
bin=$1 src=$2
d=$(mktemp -d)
trap 'rm -rf "$d"' EXIT
printf '400,0\n440,1\n460,1\n500,0\n' >"$d/LED450.csv"
"$bin/nxrender" --relightable --relight-for "led=$d/LED450.csv" --relight-for led=D65 \
  --spp 1 --crop 0,0,8,8 -o "$d/r.exr" "$src/scenes/lab_bench.scn" >"$d/out.txt" 2>&1 ||
  { echo "nxrender failed:"; cat "$d/out.txt"; exit 1; }
"$bin/nxrelight" --light led=D65 --light uv=A "$d/r.exr" -o "$d/relit.exr" >"$d/out.txt" 2>&1 ||
  { echo "nxrelight failed:"; cat "$d/out.txt"; exit 1; }
[ -s "$d/relit.exr" ] || { echo "no relit image"; exit 1; }
echo "repeatable options leave the positional arguments alone"
