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

# The signal is sent once the first checkpoint shows the render under way (not at a fixed time:
# under load or the sanitizers the scene may still be loading then), so the test needs no idle
# machine; 64 samples last seconds beyond the first checkpoint even in Release.
"$bin/nxrender" --threads 2 --spp 64 --checkpoint 1 -o "$d/int.exr" "$scene" 2>"$d/log" &
pid=$!
for _ in $(seq 600); do [ -f "$d/int.exr" ] && break; sleep 0.1; done
[ -f "$d/int.exr" ] || { echo "no checkpoint within 60 s"; cat "$d/log"; kill "$pid"; exit 1; }
cp "$d/int.exr" "$d/checkpoint.exr" # (written by rename: whole whenever it is read)
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

"$bin/nxrender" --threads 2 --spp 64 -o "$d/whole.exr" "$scene" 2>/dev/null
# The partial image is valid but has fewer samples than the whole one.
if "$bin/nxdiff" "$d/whole.exr" "$d/int.exr" >"$d/diff" 2>&1; then echo "the interrupted image is complete?"; exit 1; fi
grep -q "sample counts differ" "$d/diff" || { cat "$d/diff"; exit 1; }
"$bin/nxrender" --threads 2 --spp 64 -o "$d/int.exr" --resume "$d/int.exr" "$scene" 2>/dev/null
"$bin/nxdiff" "$d/whole.exr" "$d/int.exr" --max-relative 1e-5

# The checkpoint taken while the render ran is a readable image.
"$bin/nxdiff" "$d/checkpoint.exr" "$d/checkpoint.exr" >/dev/null || { echo "checkpoint not readable"; exit 1; }
echo "interrupt, resume and checkpoint behave"
