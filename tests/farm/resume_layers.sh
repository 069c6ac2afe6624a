#!/usr/bin/env bash
# A partial render resumed with other ground-truth layers (--aov) is refused naming both sets of
# layers (it got the render key's generic "another scene, ..., other options" message); with
# the same layers, in any order, it resumes.
#
#   resume_layers.sh BIN_DIR
set -euo pipefail
bin="$1"
. "$(dirname "$0")/emitter_scene.sh"
r() { "$bin/nxrender" --threads 2 "$@" 2>"$d/err"; }
r --spp 4 --aov normals,albedo -o "$d/p.exr" "$d/s.scn"
if r --spp 4 --aov normals --resume "$d/p.exr" -o "$d/q.exr" "$d/s.scn"; then
  echo "resumed with other layers"; exit 1
fi
grep -q "p.exr: holds the ground-truth layers 'normals,albedo', this render 'normals': resume with the same --aov" \
  "$d/err" || { cat "$d/err"; exit 1; }
[ ! -e "$d/q.exr" ] || { echo "wrote q.exr"; exit 1; }
r --spp 4 --aov albedo,normals --resume "$d/p.exr" -o "$d/q.exr" "$d/s.scn" || { cat "$d/err"; exit 1; }
echo "resumes need the same ground-truth layers, and say so"
