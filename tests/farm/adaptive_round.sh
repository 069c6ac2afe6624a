#!/usr/bin/env bash
# Adaptive sampling on a farm: a uniform pilot, then one adaptive round planned from it and
# rendered as crop parts (cut across the 8x8 plan blocks), merged by nxmerge, equals the same
# round rendered whole, bit for bit (nxdiff with no tolerance, SampleCount included). Also:
# a plan from a part of the image, an adaptive --spp-range and adaptive parts mixed with
# uniform ones are refused with their reasons.
#
#   adaptive_round.sh BIN_DIR SCENE
set -euo pipefail
bin="$1"
scene="$2"
d="$(mktemp -d)"
trap 'rm -rf "$d"' EXIT
r() { "$bin/nxrender" --threads 2 "$@" 2>>"$d/log"; }
r --spp 16 -o "$d/pilot.exr" "$scene"
r --spp 512 --target-error 0.5 --adaptive-from "$d/pilot.exr" -o "$d/whole.exr" "$scene"
r --spp 512 --target-error 0.5 --adaptive-from "$d/pilot.exr" --crop 0,0,157,180 -o "$d/a.exr" "$scene"
r --spp 512 --target-error 0.5 --adaptive-from "$d/pilot.exr" --crop 157,0,320,77 -o "$d/b.exr" "$scene"
r --spp 512 --target-error 0.5 --adaptive-from "$d/pilot.exr" --crop 157,77,320,180 -o "$d/c.exr" "$scene"
"$bin/nxmerge" -o "$d/merged.exr" "$d/a.exr" "$d/b.exr" "$d/c.exr" 2>>"$d/log"
"$bin/nxdiff" "$d/merged.exr" "$d/whole.exr" >"$d/diff" || { cat "$d/diff"; exit 1; }
grep -q "rendered the planned round" "$d/log" || { cat "$d/log"; exit 1; }

expect_error() { # expected message, then the command
  local want="$1"
  shift
  if "$@" 2>"$d/err"; then echo "accepted: $*"; exit 1; fi
  grep -q -- "$want" "$d/err" || { echo "expected '$want', found:"; cat "$d/err"; exit 1; }
}
expect_error "expected the whole 320x180 image to plan from" \
  "$bin/nxrender" --spp 512 --target-error 0.5 --adaptive-from "$d/a.exr" -o "$d/x.exr" "$scene"
expect_error "an adaptive render splits by crops only" \
  "$bin/nxrender" --spp-range 0:64 --adaptive --target-error 0.5 -o "$d/x.exr" "$scene"
expect_error "expected a --target-error to aim at" \
  "$bin/nxrender" --spp 64 --adaptive -o "$d/x.exr" "$scene"
expect_error "expected at least 2 samples per pixel" \
  "$bin/nxrender" --spp 1 --adaptive --target-error 0.5 -o "$d/x.exr" "$scene"
expect_error "only with --adaptive" \
  "$bin/nxrender" --spp 16 --adaptive-min-spp 4 -o "$d/x.exr" "$scene"
r --spp 16 --crop 157,0,320,77 -o "$d/u.exr" "$scene"
expect_error "its adaptive sampling is 'off'" \
  "$bin/nxmerge" -o "$d/x.exr" "$d/a.exr" "$d/u.exr" "$d/c.exr"
# A pilot without variances (--no-variance) or a band range naming no band of the render:
# refused (the first planned no sample and recorded an error of 0, the second never stopped).
r --spp 16 --no-variance -o "$d/novar.exr" "$scene"
expect_error "expected variance estimates to plan from, found 0 at every pixel" \
  "$bin/nxrender" --spp 512 --target-error 0.5 --adaptive-from "$d/novar.exr" -o "$d/x.exr" "$scene"
expect_error "expected a range holding at least one band of the render" \
  "$bin/nxrender" --spp 512 --target-error 0.5 --error-of bands:900-1000 --adaptive-from "$d/pilot.exr" -o "$d/x.exr" "$scene"
expect_error "expected a range holding at least one band of the render" \
  "$bin/nxrender" --spp 64 --target-error 0.5 --error-of bands:900-1000 -o "$d/x.exr" "$scene"
[ ! -e "$d/x.exr" ] || { echo "a refused render wrote x.exr"; exit 1; }
echo "adaptive round: crops merge into the whole round bit for bit; misuse refused"
