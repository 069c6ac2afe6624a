#!/bin/bash
# Analytic primitives own their work: no code outside accel/ names one to branch on it
# (`ShapeKind::Sphere`, `std::get_if<DiskShape>`, `is_same_v<Shape, CylinderShape>`, ...);
# it asks the primitive through the AnalyticPrimitive contract (accel/primitive.h;
# docs/architecture.md, "A primitive is one file"), the shape-derivative code included (a
# primitive's outline and its surface's motion are its own). Fails naming each branch found.
set -u
root=${1:-$(dirname "$0")/../..}
cd "$root" || exit 2
names=$(grep -oE '^  X\([A-Za-z]+\)' accel/shape_kind.h | sed -E 's/^  X\(([A-Za-z]+)\)/\1/' |
  paste -sd '|')
[ -n "$names" ] || { echo "found no NX_ANALYTIC_PRIMITIVES list in accel/shape_kind.h"; exit 1; }
pattern="ShapeKind::($names)\\b|(get_if|holds_alternative|is_same_v)[^;]*\\b($names)Shape\\b"
found=$(grep -rnE "$pattern" --include='*.h' --include='*.cpp' core spectra io integrators apps)
if [ -n "$found" ]; then
  echo "a branch on an analytic primitive outside accel/: ask the primitive instead (a member of"
  echo "AnalyticPrimitive, accel/primitive.h, through visitPrimitive or forEachAnalyticKind):"
  echo "$found"
  exit 1
fi
count=$(echo "$names" | tr '|' '\n' | wc -l)
echo "no branch on any of the $count analytic primitives ($names) outside accel/"
