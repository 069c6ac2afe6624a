#!/bin/bash
# Renders a scene on a Slurm cluster: an array job of PARTS tasks, each a horizontal strip
# (nxrender --tile-of-array), then a merge job that runs only if every task succeeded.
#
#   submit.sh SCENE OUT.exr PARTS [SPP]
#
# Prints the two job ids. With NX_WAIT=1 it waits for both jobs and exits non-zero, naming
# the failed jobs, unless OUT.exr was produced. Extra sbatch options: NX_SBATCH_OPTIONS.
set -euo pipefail
if [ $# -lt 3 ]; then echo "usage: submit.sh SCENE OUT.exr PARTS [SPP]" >&2; exit 2; fi
here="$(cd "$(dirname "$0")" && pwd)"
export NX_SCENE="$(realpath "$1")" NX_OUT="$(realpath -m "$2")" NX_PARTS="$3" NX_SPP="${4:-}"
case "$NX_PARTS" in '' | *[!0-9]* | 0) echo "submit.sh: PARTS must be a positive whole number" >&2; exit 2 ;; esac
# shellcheck disable=SC2086
array=$(sbatch --parsable --array="0-$((NX_PARTS - 1))" --chdir="$(dirname "$NX_OUT")" ${NX_SBATCH_OPTIONS:-} \
  --export=ALL "$here/nxrender-array.sbatch")
array="${array%%;*}"
# shellcheck disable=SC2086
merge=$(sbatch --parsable --dependency="afterok:$array" --kill-on-invalid-dep=yes --chdir="$(dirname "$NX_OUT")" \
  ${NX_SBATCH_OPTIONS:-} --export=ALL "$here/nxmerge-parts.sbatch")
merge="${merge%%;*}"
echo "render array job $array ($NX_PARTS tasks), merge job $merge"
[ "${NX_WAIT:-0}" = 1 ] || exit 0
while [ -n "$(squeue -h -j "$array,$merge" 2>/dev/null)" ]; do sleep 0.5; done
failed=$(scontrol -o show job "$array" 2>/dev/null | grep -v 'JobState=COMPLETED' | grep -o 'JobId=[0-9]* .*JobState=[A-Z_]*' | sed 's/ .*JobState=/ /' | tr '\n' ';' || true)
if [ ! -f "$NX_OUT" ] || [ -n "$failed" ]; then
  echo "submit.sh: the render failed: ${failed:-no failed task found, but} $NX_OUT was not produced" >&2
  scontrol -o show job "$merge" 2>/dev/null | grep -o 'JobState=[A-Z_]* Reason=[A-Za-z_]*' >&2 || true
  exit 1
fi
echo "submit.sh: wrote $NX_OUT"
