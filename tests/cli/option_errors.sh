#!/usr/bin/env bash
# Option errors of every program: status 1 (nxcompare: its usage status 2), the message
# "<program>: error: <option>: expected ..., found ..." on stderr, nothing written. NaN and
# infinity in any numeric option are refused (CLI::Range let NaN through and switched checks
# off), and bounds are printed as numbers, not "0.000000".
# Usage: option_errors.sh BIN_DIR SCENE
set -u
bin=$1 scene=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
failures=0
check() { # status expected-first-line program args...
  local status=$1 expected=$2
  shift 2
  "$bin/$1" "${@:2}" >out.txt 2>err.txt
  local got=$?
  local first
  first=$(head -n 1 err.txt)
  if [ "$got" != "$status" ] || [ "$first" != "$expected" ]; then
    echo "FAIL: $* -> status $got, '$first' (expected $status, '$expected')"
    failures=$((failures + 1))
  fi
  if ls ./*.exr ./*.png >/dev/null 2>&1; then
    echo "FAIL: $* wrote $(ls ./*.exr ./*.png)"
    failures=$((failures + 1))
    rm -f ./*.exr ./*.png
  fi
}
check 1 "nxrender: error: --target-error: expected a number from 1e-09 to 1e+09, found 'nan'" \
  nxrender --target-error nan -o x.exr "$scene"
check 1 "nxrender: error: --time-limit: expected a number from 0.001 to 1e+12, found 'nan'" \
  nxrender --time-limit nan -o x.exr "$scene"
check 1 "nxrender: error: --checkpoint: expected a number from 1 to 1e+09, found 'inf'" \
  nxrender --checkpoint inf -o x.exr "$scene"
check 1 "nxrender: error: --target-error: expected a number from 1e-09 to 1e+09, found '1e-300'" \
  nxrender --target-error 1e-300 -o x.exr "$scene"
check 1 "nxrender: error: --threads: expected a number from 1 to 4096, found '0'" \
  nxrender --threads 0 -o x.exr "$scene"
check 1 "nxrender: error: The following argument was not expected: --no-such-option" \
  nxrender --no-such-option -o x.exr "$scene"
check 1 "nxdiff: error: --max-relative: expected a number from 0 to 1e+09, found 'nan'" \
  nxdiff --max-relative nan a.exr b.exr
check 2 "nxcompare: error: --max-sam: expected a number from 0 to 180, found 'nan'" \
  nxcompare --max-sam nan a.exr b.exr
check 2 "nxcompare: error: --max-relative-rmse: expected a number from 0 to 1e+09, found 'NaN'" \
  nxcompare --max-relative-rmse NaN a.exr b.exr
check 1 "nxcamera: error: --gain: expected a finite number, found 'nan'" \
  nxcamera --gain nan -o c.exr a.exr
check 1 "nxmerge: error: --output is required" nxmerge a.exr
# nxcamera checks every output before writing any (the EXR was left when --envi was refused
# after it), and an EXR is never written under another format's name.
"$bin/nxrender" --spp 2 --crop 0,0,8,8 -o in.exr "$scene" >/dev/null 2>&1 || echo "FAIL: render"
mkdir -p inputs && mv in.exr inputs/ && rm -f in.png
check 1 "nxcamera: error: c.png: expected an output name ending in .exr (the file is an OpenEXR), found '.png'" \
  nxcamera -o c.png inputs/in.exr
check 1 "nxcamera: error: c.hdr: expected an ENVI data file name with an extension other than .hdr (e.g. .img), found 'c.hdr'" \
  nxcamera -o c.exr --envi c.hdr inputs/in.exr
check 1 "nxcamera: error: /nonexistent-dir/c.img: the output directory '/nonexistent-dir' does not exist" \
  nxcamera -o c.exr --envi /nonexistent-dir/c.img inputs/in.exr
# Relighting: the grid step, a file without a transport, groups, spectra and the --light form.
check 1 "nxrender: error: --relight-step: expected a step in nm from 0.1 to 100 that divides 5 (0.1, 0.25, 0.5, 1, 2.5, 5) or is a multiple of 5 (its bins nest with the 5 nm re-radiation grid), found 3" \
  nxrender --relightable --relight-step 3 -o x.exr "$scene"
# A step too fine to build (1e-6 took minutes and 12 GiB; 1e-300 overflowed the bin count).
for step in 1e-06 1e-300 0.05; do
  check 1 "nxrender: error: --relight-step: expected a step in nm from 0.1 to 100 that divides 5 (0.1, 0.25, 0.5, 1, 2.5, 5) or is a multiple of 5 (its bins nest with the 5 nm re-radiation grid), found $step" \
    nxrender --relightable --relight-step $step -o x.exr "$scene"
done
check 1 "nxrender: error: --relight-step: only with --relightable (the excitation grid it keeps)" \
  nxrender --relight-step 5 -o x.exr "$scene"
check 1 "nxrelight: error: inputs/in.exr: expected a relightable image (rendered with --relightable), found one without relight channels" \
  nxrelight inputs/in.exr --light default=D65 -o r.exr
"$bin/nxrender" --spp 2 --crop 0,0,8,8 --relightable -o rel.exr "$scene" >/dev/null 2>&1 || echo "FAIL: relightable render"
mv rel.exr inputs/
check 1 "nxrelight: error: --light sky=D65: expected a light group of the image (default), found 'sky'" \
  nxrelight inputs/rel.exr --light sky=D65 -o r.exr
check 1 "nxrelight: error: --light default=nosuch: expected a CSV file (nm,value) or a built-in emission name (A, D65, F1-F12, blackbody:K, ...), found 'nosuch' (no such file)" \
  nxrelight inputs/rel.exr --light default=nosuch -o r.exr
check 1 "nxrelight: error: --light: expected GROUP=spectrum.csv (or GROUP=NAME, a built-in emission such as D65), found 'foo'" \
  nxrelight inputs/rel.exr --light foo -o r.exr
printf '400,1\n500,-2\n' >inputs/bad.csv
check 1 "nxrelight: error: --light default=inputs/bad.csv: inputs/bad.csv: expected an emission spectrum of values >= 0, found -2 at 500 nm" \
  nxrelight inputs/rel.exr --light default=inputs/bad.csv -o r.exr
check 1 "nxrelight: error: r.png: expected an output name ending in .exr (the file is an OpenEXR), found '.png'" \
  nxrelight inputs/rel.exr --light default=D65 -o r.png
"$bin/nxrender" --help >/dev/null || { echo "FAIL: --help status $?"; failures=$((failures + 1)); }
echo "$failures failures"
[ "$failures" = 0 ]
