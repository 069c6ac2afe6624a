#!/bin/bash
# Scattering models own their work: no code outside integrators/materials/ branches on a
# MaterialKind (`== MaterialKind::X`, `!= MaterialKind::X`, `case MaterialKind::X`); it asks
# the models (materialLobes, straightTransmittance, roughnessDifferentiable, ...;
# docs/architecture.md, "Scattering"). Fails naming each branch found.
set -u
root=${1:-$(dirname "$0")/../..}
cd "$root" || exit 2
pattern='([=!]=[[:space:]]*MaterialKind::|MaterialKind::[A-Za-z]+[[:space:]]*[=!]=|case[[:space:]]+MaterialKind::)'
found=$(grep -rnE "$pattern" --include='*.h' --include='*.cpp' core spectra accel io integrators \
  apps | grep -v '^integrators/materials/')
if [ -n "$found" ]; then
  echo "a branch on a MaterialKind outside the scattering models: ask the model instead (a"
  echo "member of ScatteringModel<K>, integrators/materials/scattering_model.h):"
  echo "$found"
  exit 1
fi
# The check sees the models: their dispatch must be where it looks.
inside=$(grep -rlE 'ScatteringModel<MaterialKind::' --include='*.cpp' integrators/materials | wc -l)
if [ "$inside" -lt 5 ]; then
  echo "expected the scattering models in integrators/materials/kinds/, found $inside files"
  exit 1
fi
echo "no branch on a MaterialKind outside the $inside files of the scattering models"
