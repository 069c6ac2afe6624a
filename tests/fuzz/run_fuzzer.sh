#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (AddressSanitizer + UndefinedBehaviorSanitizer) and
# runs one: the scene target (scene files, CSV tables, matrices, bands; seeds: the malformed-
# scene corpus and the example scenes, with the scene dictionary) or the input target for one
# kind of lab file (ply, obj, sensor, envi, exr, eem, calibration, concentration, relight;
# seeds: the project's files of that kind, tests/fuzz/seeds/<kind> for the last four).
# Findings are written as crash-*/leak-*/timeout-*/oom-* files in the work directory; add each
# to the tests after fixing it.
#
#   tests/fuzz/run_fuzzer.sh [--kind scene|ply|obj|sensor|envi|exr|eem|calibration|concentration|relight]
#                            [--seconds S | --runs N] [--jobs J]
set -euo pipefail
src="$(cd "$(dirname "$0")/../.." && pwd)"
kind=scene seconds=600 runs="" jobs=1
while [ $# -gt 0 ]; do
  case "$1" in
  --kind) kind="$2"; shift 2 ;;
  --seconds) seconds="$2"; shift 2 ;;
  --runs) runs="$2"; shift 2 ;;
  --jobs) jobs="$2"; shift 2 ;;
  *) echo "run_fuzzer.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
if ! command -v clang++-14 >/dev/null; then
  apt-get install -y --no-install-recommends clang-14 libclang-rt-14-dev >/dev/null
fi
build="$src/build-fuzz"
# The sRGB table's fit takes most of an hour under the sanitizers: NX_SIGMOID_TABLE_FROM names a
# table a Release build fitted (e.g. build/spectra/srgb_sigmoid_table.bin), as CI does.
cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang-14 \
  -DCMAKE_CXX_COMPILER=clang++-14 -DNX_FUZZ=ON -DNX_BUILD_TESTS=OFF \
  ${NX_SIGMOID_TABLE_FROM:+-DNX_SIGMOID_TABLE_FROM="$NX_SIGMOID_TABLE_FROM"} >/dev/null
target=$([ "$kind" = scene ] && echo scene_fuzzer || echo input_fuzzer)
cmake --build "$build" -j"$(nproc)" --target "$target" >/dev/null
work="$build/fuzz-work-$kind"
mkdir -p "$work/corpus"
case "$kind" in
scene) cp "$src"/tests/corpus/*.scn "$src"/scenes/*.scn "$work/corpus/" ;;
ply | obj) find "$src/tests" "$src/scenes" -name "*.$kind" -exec cp {} "$work/corpus/" \; ;;
sensor)
  grep -rl --include=*.csv '^nm,' "$src/tests" "$src/scenes" | xargs -I{} cp {} "$work/corpus/"
  printf 'nm,blue,green\n400,0,0\n440,0.8,0\n460,1,0.01\n500,0.1,0.6\n540,0,1\n580,0,0\n' >"$work/corpus/srf.csv" ;;
envi)
  printf 'ENVI\nsamples = 4\nlines = 3\nbands = 2\nheader offset = 0\nfile type = ENVI Standard\ndata type = 4\ninterleave = bsq\nbyte order = 0\nwavelength units = Nanometers\nwavelength = {500, 600}\nfwhm = {10, 10}\n' >"$work/corpus/cube.hdr"
  printf 'ENVI\nsamples = 2\nlines = 2\nbands = 3\ndata type = 12\ninterleave = bip\nbyte order = 1\nwavelength = {0.5, 0.6, 0.7}\nwavelength units = Micrometers\n' >"$work/corpus/bip.hdr" ;;
exr)
  # Debian's interpreter, where python3-numpy and python3-openimageio are installed
  "${PYTHON:-/usr/bin/python3}" - "$work/corpus" <<'PY'
import sys, numpy as np, OpenImageIO as oiio
d = sys.argv[1]
for name, chans, comp in [("s0.exr", ["S0.500nm", "S0.600nm", "R", "G", "B"], "none"),
                          ("t.exr", ["T.450nm", "T.550nm", "T.650nm"], "zip"),
                          ("piz.exr", ["S0.400nm", "S0.700nm"], "piz")]:
    spec = oiio.ImageSpec(3, 2, len(chans), "float")
    spec.channelnames = chans
    spec.attribute("compression", comp)
    out = oiio.ImageOutput.create(f"{d}/{name}")
    out.open(f"{d}/{name}", spec)
    out.write_image(np.full((2, 3, len(chans)), 0.5, np.float32))
    out.close()
PY
  ;;
eem | calibration | concentration | relight) cp "$src/tests/fuzz/seeds/$kind"/* "$work/corpus/" ;;
*) echo "run_fuzzer.sh: unknown kind '$kind'" >&2; exit 2 ;;
esac
cd "$work"
limit=$([ -n "$runs" ] && echo "-runs=$runs" || echo "-max_total_time=$seconds")
dict=$([ "$kind" = scene ] && echo "-dict=$src/tests/fuzz/scene.dict" || echo "")
# A relightable EXR holds a transport's channels: its seeds are 4-7 kB.
maxlen=$([ "$kind" = relight ] && echo 16384 || echo 8192)
NX_FUZZ_KIND="$kind" "$build/tests/fuzz/$target" $dict "$limit" -max_len="$maxlen" -timeout=10 \
  -rss_limit_mb=2048 -jobs="$jobs" -workers="$jobs" -print_final_stats=1 corpus
