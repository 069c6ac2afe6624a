#!/usr/bin/env bash
# Runs the project's Slurm recipe (apps/farm) on a real single-node Slurm started here
# (munge, slurmctld, slurmd; no systemd), and checks that the merged image equals a
# single-machine render bit for bit. Also checks that a failing task makes the merge fail.
#
#   slurm_test.sh BIN_DIR SOURCE_DIR
#
# Needs root (to install and run the daemons); otherwise it says so and exits 77 (skipped).
set -euo pipefail
bin="$(realpath "$1")" src="$(realpath "$2")"
if [ "$(id -u)" != 0 ]; then
  echo "slurm test skipped: it needs root to install and run munge, slurmctld and slurmd"
  exit 77
fi

# shellcheck source=tests/farm/slurm_cluster.sh
. "$src/tests/farm/slurm_cluster.sh"

# The recipe: a 4-task array rendering strips, then the dependent merge.
scene="$src/scenes/materials.scn"
export NXRENDER="$bin/nxrender" NXMERGE="$bin/nxmerge" NX_THREADS=1
NX_WAIT=1 "$src/apps/farm/submit.sh" "$scene" "$d/work/farm.exr" 4 4
"$bin/nxrender" --threads 2 --spp 4 -o "$d/work/single.exr" "$scene" 2>/dev/null
"$bin/nxdiff" "$d/work/single.exr" "$d/work/farm.exr"

# A failing task (a scene that does not exist for task... all tasks) must stop the merge.
if NX_WAIT=1 "$src/apps/farm/submit.sh" "$d/work/missing.scn" "$d/work/broken.exr" 2 4; then
  echo "a failed array task did not make the render fail"
  exit 1
fi
[ ! -e "$d/work/broken.exr" ] || { echo "a partial image was written"; exit 1; }
# A dataset as a 2-task array (apps/farm/nxdataset-array.sbatch): every item present and equal
# to a direct render of its scene with its recorded seed.
cat >"$d/work/gen.py" <<'PY'
def scene(index):
    return {"settings": {"xres": 16, "yres": 12, "mode": "spectral_mcpt", "sampl": 4,
                         "bands": "400:700:100"},
            "camera": {"position": [0, 2, -6], "look_at": [0, 0.5, 0]},
            "objects": [{"shape": "sphere", "center": [0.2 * index, 1, 0], "radius": 0.6,
                         "material": "matte", "reflectance": 0.6,
                         "fluorescence": {"absorption": "blue", "stokes": 80}},
                        {"shape": "plane", "normal": [0, 1, 0], "distance": 0,
                         "material": "matte", "reflectance": 0.5}],
            "lights": [{"type": "point", "position": [0, 3, -2], "color": [1, 1, 1]}]}
PY
export NX_GENERATOR="$d/work/gen.py" NX_DATASET="$d/work/data" NX_COUNT=5 NX_SPP=4 \
  NXDATASET="$bin/nxdataset" NX_THREADS=1
(cd "$d/work" && sbatch --wait --array=0-1 "$src/apps/farm/nxdataset-array.sbatch" >/dev/null) ||
  { echo "the dataset array failed"; cat "$d"/work/nxdataset-*.log; exit 1; }
"$bin/../nxpython" - "$d/work/data" "$d/work/gen.py" <<'PY'
import sys
import numpy as np
import nxrender, nxrender.dataset
data = nxrender.dataset.Dataset(sys.argv[1])
assert len(data) == 5, len(data)
ns = {}
exec(open(sys.argv[2]).read(), ns)
for i in range(len(data)):
    item = data[i]
    direct = nxrender.render(nxrender.Scene.from_dict(ns["scene"](i)), seed=item["seed"], spp=4,
                             aovs=["components"])
    stored = nxrender.dataset.stored_values(direct.radiance, data.meta(i)["arrays"]["radiance"])
    assert np.array_equal(item["radiance"], stored), i
PY
echo "slurm test passed: merged image equals the single-machine render; a failed task stops the merge; a dataset array's items equal direct renders"
