#!/usr/bin/env bash
# Parts rendered from the same scene file but different referenced data (a CSV spectrum edited
# between them) do not merge, and a render does not resume from a partial made with other data.
#
#   changed_data.sh BIN_DIR
set -euo pipefail
bin="$1"
REFLECTANCE='<reflectance csv="paint.csv"/>'
. "$(dirname "$0")/emitter_scene.sh"
printf '400,0.5\n700,0.5\n' >"$d/paint.csv"
"$bin/nxrender" --threads 2 --spp-range 0:4 -o "$d/a.exr" "$d/s.scn" 2>/dev/null
printf '400,0.5\n700,0.9\n' >"$d/paint.csv"
"$bin/nxrender" --threads 2 --spp-range 4:8 -o "$d/b.exr" "$d/s.scn" 2>/dev/null
if "$bin/nxmerge" -o "$d/m.exr" "$d/a.exr" "$d/b.exr" 2>"$d/err"; then
  echo "parts made with different CSV data were merged"; exit 1
fi
grep -q "does not belong with .*nxrender.renderKey.*other data files" "$d/err" || { cat "$d/err"; exit 1; }
[ ! -e "$d/m.exr" ] || { echo "a merged file was written"; exit 1; }
# Resume: a partial of the old data is refused by a render of the new data.
printf '400,0.5\n700,0.5\n' >"$d/paint.csv"
"$bin/nxrender" --threads 2 --spp 8 -o "$d/p.exr" "$d/s.scn" 2>/dev/null
printf '400,0.5\n700,0.9\n' >"$d/paint.csv"
if "$bin/nxrender" --threads 2 --spp 8 --resume "$d/p.exr" -o "$d/q.exr" "$d/s.scn" 2>"$d/err"; then
  echo "resumed from a partial made with other CSV data"; exit 1
fi
grep -q "other data files" "$d/err" || { cat "$d/err"; exit 1; }
echo "changed data refused by nxmerge and --resume"
