#!/usr/bin/env bash
# A benchmark (prints figures; not a test): the cost of docs/farm.md's dataset recipe measured
# on a real single-node Slurm started here (tests/farm/slurm_cluster.sh). Submits
# apps/farm/nxdataset-array.sbatch for COUNT items of scenes/datasets/separation.py (128 x 128,
# 64 spp, components and ground truth) as an array of TASKS tasks of CPUS cores each, waits,
# and prints items per hour, core-seconds per item, bytes per item and what 100,000 items
# cost at that rate. docs/farm.md quotes its figures.
#
#   slurm_dataset_cost.sh BIN_DIR SOURCE_DIR [COUNT=96] [TASKS=2] [CPUS=1] [JOBS=1]
#
# Needs root (to install and run the daemons).
set -euo pipefail
bin="$(realpath "$1")" src="$(realpath "$2")"
count="${3:-96}" tasks="${4:-2}" cpus="${5:-1}" jobs="${6:-1}"
if [ "$(id -u)" != 0 ]; then
  echo "slurm_dataset_cost.sh: needs root to install and run munge, slurmctld and slurmd" >&2
  exit 2
fi
# shellcheck source=tests/farm/slurm_cluster.sh
. "$src/tests/farm/slurm_cluster.sh"

export NX_GENERATOR="$src/scenes/datasets/separation.py" NX_DATASET="$d/work/separation" \
  NX_COUNT="$count" NX_SPP=64 NX_AOV=components,normals,albedo,fluorescence \
  NXDATASET="$bin/nxdataset" NX_JOBS="$jobs"
start=$(date +%s.%N)
(cd "$d/work" && sbatch --wait --array=0-$((tasks - 1)) --cpus-per-task="$cpus" \
  "$src/apps/farm/nxdataset-array.sbatch" >/dev/null) ||
  { echo "the dataset array failed"; cat "$d"/work/nxdataset-*.log; exit 1; }
# (the last item's write, not sbatch's return: --wait polls the job's state at growing intervals)
end=$(find "$NX_DATASET" -name 'item_*.nxi' -printf '%T@\n' | sort -n | tail -n 1)
items=$(find "$NX_DATASET" -name 'item_*.nxi' | wc -l)
bytes=$(find "$NX_DATASET" -name 'item_*.nxi' -printf '%s\n' | awk '{s += $1} END {print s}')
cores=$((tasks * cpus))
awk -v n="$items" -v want="$count" -v t0="$start" -v t1="$end" -v cores="$cores" -v b="$bytes" \
  -v tasks="$tasks" -v cpus="$cpus" -v jobs="$jobs" 'BEGIN {
  s = t1 - t0
  if (n != want) { printf "only %d of %d items were written\n", n, want; exit 1 }
  printf "%d items of scenes/datasets/separation.py (128 x 128, 64 spp, components, normals, albedo, fluorescence)\n", n
  printf "as a %d-task Slurm array of %d cores per task (NX_JOBS=%d), submission to the last item written: %.1f s\n", tasks, cpus, jobs, s
  printf "%.0f items per hour on %d cores; %.2f core-seconds per item; %.2f MB per item\n", n / s * 3600, cores, s * cores / n, b / n / 1e6
  printf "100,000 items at this rate: %.1f core-hours, %.0f GB\n", 1e5 * s * cores / n / 3600, 1e5 * b / n / 1e9
}'
