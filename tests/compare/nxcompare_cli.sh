#!/usr/bin/env bash
# nxcompare from the command line: a render against its own ENVI export (identical bands,
# angle 0, exit 0), thresholds (exit 1), resampling through Gaussian bands, CSV columns, and
# the simulated camera, and the errors (exit 2) of mismatched sizes, bands beyond the render and masks of the wrong size.
#
#   nxcompare_cli.sh NXRENDER NXCOMPARE NXCAMERA SCENE
set -euo pipefail
nxrender="$1" nxcompare="$2" nxcamera="$3" scene="$4"
d="$(mktemp -d)"
trap 'rm -rf "$d"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$nxrender" --threads 2 --spp 4 --bands 400:700:10 --aov ids --envi -o "$d/r.exr" "$scene" >/dev/null 2>&1
"$nxrender" --threads 2 --spp 4 --seed 9 --bands 400:700:10 -o "$d/s.exr" "$scene" >/dev/null 2>&1

# Identical data through two formats: exit 0, angle 0, CSV with one row per band.
"$nxcompare" "$d/r.exr" "$d/r.hdr" --max-sam 0.0001 --max-relative-rmse 0 --csv "$d/b.csv" --labels \
  --region-csv "$d/g.csv" >"$d/out" || fail "identical cubes: exit $?"
grep -q "spectral angle (degrees) over .* mean 0.0000" "$d/out" || fail "angle not 0: $(cat "$d/out")"
head -1 "$d/b.csv" | grep -q '^band,wavelength_nm,rmse,relative_rmse,bias,' || fail "csv header"
[ "$(wc -l <"$d/b.csv")" = 32 ] || fail "csv rows: $(wc -l <"$d/b.csv")"
# Regions by --labels are named after their objects (a name="...", else a <material id>, else
# the shape, its line and material), not "object N".
grep -q '^"plane at line 19 (matte)",' "$d/g.csv" || fail "region csv: $(head -3 "$d/g.csv")"
! grep -q '^"object ' "$d/g.csv" || fail "regions named by number"

# A window of the render against the same window of the capture.
"$nxcompare" "$d/r.exr" "$d/r.hdr" --crop 100,20,200,100 --offset 0,0 --max-sam 0.0001 >"$d/out" ||
  fail "crop: exit $?"
grep -q "20000 pixels compared" "$d/out" || fail "crop pixels: $(cat "$d/out")"

# Two renders with different seeds differ by noise only: the z-scores say so; a threshold of 0
# on the angle fails with exit 1.
set +e
"$nxcompare" "$d/r.exr" "$d/s.exr" --max-sam 0 >"$d/out"
rc=$?
set -e
[ "$rc" = 1 ] || fail "threshold: exit $rc"
grep -q "FAIL: mean spectral angle" "$d/out" || fail "threshold message"

# Resampled through Gaussian bands of the capture (the ENVI header's fwhm replaced).
"$nxcompare" "$d/r.exr" "$d/r.hdr" --capture-wavelengths 420:680:20 --capture-fwhm 15 >"$d/out" 2>&1 &&
  fail "20 nm bands on a 10 nm cube accepted" || true
grep -q "expected 31 wavelengths (one per band), found 14" "$d/out" || fail "wavelength count: $(cat "$d/out")"

expect_error() { # message, then arguments
  local msg="$1"
  shift
  set +e
  "$nxcompare" "$@" >"$d/out" 2>&1
  local rc=$?
  set -e
  [ "$rc" = 2 ] || fail "expected exit 2 for $*, got $rc"
  grep -qF -- "$msg" "$d/out" || fail "expected '$msg', got: $(cat "$d/out")"
}
expect_error "lies beyond the render's bands (400-700 nm)" "$d/r.exr" "$d/r.hdr" \
  --capture-wavelengths 405:705:10
expect_error "expected the compared window (20 x 10 pixels at -1,0 in the capture) inside its 560 x 160" \
  "$d/r.exr" "$d/r.hdr" --crop 0,0,20,10 --offset -1,0
expect_error "--crop: expected a window inside the render's" "$d/r.exr" "$d/r.hdr" --crop 0,0,100000,10
expect_error "cannot open the file (it does not exist)" "$d/r.exr" "$d/absent.hdr"
expect_error "rgb16.png: expected a mask of the render's 560 x 160 pixels, found 2 x 1" "$d/r.exr" \
  "$d/r.hdr" --mask "$(dirname "$0")/../data/textures/rgb16.png"
printf 'P' >"$d/m.png"
expect_error "m.png: expected a PNG or JPEG image" "$d/r.exr" "$d/r.hdr" --mask "$d/m.png"
# The simulated camera: its ENVI capture compared with a per-band scale agrees in colour; the
# figure is written; a bad parameter is refused with nothing written.
"$nxcamera" "$d/r.exr" -o "$d/cap.exr" --envi "$d/cap.img" --exposure 0.0002 --full-well 1e9 \
  --bits 32 --offset 0 --dark-current 0 >/dev/null
"$nxcompare" "$d/r.exr" "$d/cap.hdr" --scale band --labels --plot "$d/fig.png" >"$d/out" ||
  fail "camera capture: exit $?"
test -s "$d/fig.png" || fail "no figure"
# The preview PNG is a mask of the right size (its black pixels left out); the angle map.
"$nxcompare" "$d/r.exr" "$d/cap.hdr" --mask "$d/r.png" --sam-map "$d/sam.tif" >"$d/out" || fail "mask: exit $?"
grep -q "^mask .*r.png" "$d/out" || fail "mask region: $(cat "$d/out")"
test -s "$d/sam.tif" || fail "no angle map"
grep -q "dE2000" "$d/out" || fail "no colour differences"
# Saturated capture pixels left out and counted.
"$nxcompare" "$d/r.exr" "$d/cap.hdr" --scale band --exclude-above 50 >"$d/out" || fail "exclude: exit $?"
grep -q "left out: [1-9][0-9]* pixels with a capture value at or above 50, 0 with non-finite" "$d/out" ||
  fail "exclude message: $(cat "$d/out")"
if "$nxcamera" "$d/r.exr" -o "$d/bad.exr" --qe 1.5 2>"$d/err"; then fail "qe 1.5 accepted"; fi
grep -q "expected quantum efficiencies in \[0, 1\], found 1.5" "$d/err" || fail "qe message: $(cat "$d/err")"
test ! -e "$d/bad.exr" || fail "bad.exr written"
echo "nxcompare CLI: all checks passed"
