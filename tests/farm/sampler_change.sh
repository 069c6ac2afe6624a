#!/usr/bin/env bash
# The default sampler changed (sobol -> stratified lanes): parts and partial renders made with
# another sampler are refused by nxmerge, --resume and --adaptive-from, naming the sampler and
# how to continue; given the same --sampler they merge and resume.
#
#   sampler_change.sh BIN_DIR
set -euo pipefail
bin="$1"
. "$(dirname "$0")/emitter_scene.sh"
r() { "$bin/nxrender" --threads 2 "$@" 2>"$d/err"; }
r --spp-range 0:4 --sampler sobol -o "$d/a.exr" "$d/s.scn"
r --spp-range 4:8 -o "$d/b.exr" "$d/s.scn"
# (the header stores an attribute as its name, type, size and value; bytes that are not
# printable read as spaces)
LC_ALL=C tr -c '[:print:]' ' ' <"$d/b.exr" | grep -q 'nxrender\.sampler string *stratified' ||
  { echo "no sampler attribute"; exit 1; }
if "$bin/nxmerge" -o "$d/m.exr" "$d/a.exr" "$d/b.exr" 2>"$d/err"; then
  echo "parts of two samplers were merged"; exit 1
fi
grep -q "its nxrender.sampler is 'stratified', not 'sobol'" "$d/err" || { cat "$d/err"; exit 1; }
[ ! -e "$d/m.exr" ] || { echo "a merged file was written"; exit 1; }
r --spp-range 4:8 --sampler sobol -o "$d/c.exr" "$d/s.scn"
"$bin/nxmerge" -o "$d/m.exr" "$d/a.exr" "$d/c.exr" 2>"$d/err" || { cat "$d/err"; exit 1; }
# Resume and adaptive rounds: a partial of the earlier default is refused with the advice.
r --spp 8 --sampler sobol -o "$d/p.exr" "$d/s.scn"
if r --spp 8 --resume "$d/p.exr" -o "$d/q.exr" "$d/s.scn"; then
  echo "resumed a sobol partial with stratified lanes"; exit 1
fi
grep -q "was rendered with --sampler sobol, this render uses stratified.*give --sampler sobol" \
  "$d/err" || { cat "$d/err"; exit 1; }
r --spp 8 --sampler sobol --resume "$d/p.exr" -o "$d/q.exr" "$d/s.scn" || { cat "$d/err"; exit 1; }
r --spp 8 --sampler sobol -o "$d/pilot.exr" "$d/s.scn" || { cat "$d/err"; exit 1; }
if r --spp 64 --target-error 0.5 --adaptive-from "$d/pilot.exr" -o "$d/round.exr" "$d/s.scn"; then
  echo "an adaptive round of stratified lanes continued a sobol pilot"; exit 1
fi
grep -q "was rendered with --sampler sobol" "$d/err" || { cat "$d/err"; exit 1; }
echo "samplers are never mixed; each continues its own parts"
