#!/usr/bin/env bash
# SIGINT to a running nxrender writes a valid partial EXR with its true sample counts (and no
# temporary file); --resume finishes it into the uninterrupted image; --checkpoint writes a
# readable image while rendering.
#
#   interrupt_resume.sh BIN_DIR SCENE
set -euo pipefail
bin="$1" scene="$2"
d="$(mktemp -d)"
trap 'rm -rf "$d"' EXIT

"$bin/nxrender" --threads 2 --spp 128 -o "$d/int.exr" "$scene" 2>"$d/log" &
pid=$!
sleep 1.5
kill -INT "$pid"
set +e
wait "$pid"
rc=$?
set -e
[ "$rc" = 3 ] || { echo "expected exit status 3 after SIGINT, got $rc"; cat "$d/log"; exit 1; }
grep -q "stopped by signal 2" "$d/log" || { echo "no stop message"; cat "$d/log"; exit 1; }
if ls -A "$d" | grep -q nxtmp; then echo "a temporary file was left behind"; ls -A "$d"; exit 1; fi
# The partial's preview is written beside it (an older preview would not match the EXR).
[ -s "$d/int.png" ] || { echo "no preview of the interrupted render"; ls -A "$d"; exit 1; }

"$bin/nxrender" --threads 2 --spp 128 -o "$d/whole.exr" "$scene" 2>/dev/null
# The partial image is valid but has fewer samples than the whole one.
if "$bin/nxdiff" "$d/whole.exr" "$d/int.exr" >"$d/diff" 2>&1; then echo "the interrupted image is complete?"; exit 1; fi
grep -q "sample counts differ" "$d/diff" || { cat "$d/diff"; exit 1; }
"$bin/nxrender" --threads 2 --spp 128 -o "$d/int.exr" --resume "$d/int.exr" "$scene" 2>/dev/null
"$bin/nxdiff" "$d/whole.exr" "$d/int.exr" --max-relative 1e-5

# Periodic checkpoints: a readable image exists while the render runs.
"$bin/nxrender" --threads 2 --spp 128 --checkpoint 1 -o "$d/cp.exr" "$scene" 2>/dev/null &
pid=$!
for _ in $(seq 100); do [ -f "$d/cp.exr" ] && break; sleep 0.1; done
"$bin/nxdiff" "$d/cp.exr" "$d/cp.exr" >/dev/null || { echo "checkpoint not readable"; exit 1; }
wait "$pid"
echo "interrupt, resume and checkpoint behave"
