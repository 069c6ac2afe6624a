#!/bin/sh
# The README's test command and .ci/run must be the same command.
set -eu
cmd=$(sed -n '/^Install, build and run every test:/,/^    /p' "$1/README.md" | tail -n 1 | sed 's/^    //')
[ -n "$cmd" ] || { echo "README: no test command found"; exit 1; }
grep -qxF "$cmd" "$1/.ci/run" || { echo ".ci/run does not run the README's test command"; exit 1; }
