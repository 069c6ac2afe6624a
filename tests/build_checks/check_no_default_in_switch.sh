#!/bin/bash
# No `default:` label in a switch of the sources (core spectra accel io integrators apps): every
# switch lists its cases, so a new kind (ShapeKind, MaterialKind, LightKind, ...) is a compile
# error (-Wswitch under -Werror) wherever it is not handled, instead of falling silently into
# a default (docs/architecture.md, "Kinds"). Fails naming each label found.
set -u
root=${1:-$(dirname "$0")/../..}
cd "$root" || exit 2
found=$(grep -rnE '^[[:space:]]*default[[:space:]]*:' --include='*.h' --include='*.cpp' \
  core spectra accel io integrators apps)
if [ -n "$found" ]; then
  echo "a switch with a default: list the cases (a kind enum's new member must not compile"
  echo "silently into a default):"
  echo "$found"
  exit 1
fi
# The check sees the sources: an empty tree would pass anything.
count=$(grep -rlE '\bswitch[[:space:]]*\(' --include='*.h' --include='*.cpp' core spectra accel \
  io integrators apps | wc -l)
if [ "$count" -lt 5 ]; then
  echo "expected switches in the sources, found $count files with one"
  exit 1
fi
echo "no default: in the switches of $count files"
