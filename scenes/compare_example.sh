#!/usr/bin/env bash
# The worked example of docs/compare.md: render the lab bench, photograph the render with a
# simulated camera (a synthetic capture, ENVI), and compare the two.
#
#   scenes/compare_example.sh [BUILD_DIR] [OUT_DIR]     (defaults: build, /tmp/nxcompare-example)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-build}" out="${2:-/tmp/nxcompare-example}"
mkdir -p "$out"

# 1. The render: 31 bands over 400-700 nm, object ids for per-object regions.
"$build/apps/nxrender" --threads "$(nproc)" --spp 64 --bands 400:700:10 --aov ids \
  -o "$out/render.exr" "$here/lab_bench.scn"

# 2. The capture: a 12-bit camera at f/2.8, 1 ms, 5.5 um pixels, QE 0.6, full well 20,000 e-,
#    read noise 5 e-, no dark current or black level (as after a dark-frame subtraction).
"$build/apps/nxcamera" "$out/render.exr" -o "$out/capture.exr" --envi "$out/capture.img" \
  --f-number 2.8 --exposure 0.001 --pitch 5.5 --qe 0.6 --full-well 20000 --read-noise 5 \
  --dark-current 0 --offset 0 --gain 0.2 --bits 12 --seed 1

# 3. The comparison: per-band scale (the camera counts photons, so its per-band sensitivity
#    rises with wavelength; a lab's radiometric calibration does the same), per-object regions,
#    pixels at the full well (20,000 e- x 0.2 DN/e- = 4000 DN, less the read noise) left out.
"$build/apps/nxcompare" "$out/render.exr" "$out/capture.hdr" --scale band --labels --exclude-above 3980 \
  --csv "$out/bands.csv" --region-csv "$out/regions.csv" --plot "$out/figure.png"
