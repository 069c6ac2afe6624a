#!/bin/bash
# The layers as drawn (docs/architecture.md): each folder includes only the folders below it.
#   core/        core/ (core/params/: the scene format's parameter vocabulary)
#   spectra/     core/ spectra/
#   accel/       core/ spectra/ accel/
#   io/          core/ spectra/ io/
#   integrators/ core/ spectra/ accel/ io/ integrators/
# (apps/ and tests/ may include anything.) Fails naming every include that reaches upward or
# sideways, except the ones listed in ALLOWED with the reason they remain.
set -u
root=${1:-$(dirname "$0")/../..}
cd "$root" || exit 2

# file:include pairs still allowed, and why (remove them as they are fixed).
ALLOWED=(
  # None today. (The scene reader once included the kind registries; it now reads by the
  # declarations handed to it, io/scene_kind_schemas.h.)
)

allowedBelow() {
  case "$1" in
  core) echo "core" ;;
  spectra) echo "core spectra" ;;
  accel) echo "core spectra accel" ;;
  io) echo "core spectra io" ;;
  integrators) echo "core spectra accel io integrators" ;;
  esac
}

status=0
for layer in core spectra accel io integrators; do
  allowed=$(allowedBelow "$layer")
  while IFS= read -r line; do
    file=${line%%:*}
    include=$(sed -E 's/.*#include "([^"]+)".*/\1/' <<<"$line")
    top=${include%%/*}
    case " $allowed " in *" $top "*) continue ;; esac
    case "$top" in core | spectra | accel | io | integrators | apps) ;; *) continue ;; esac
    pair="$file:$include"
    if printf '%s\n' "${ALLOWED[@]}" | grep -qxF "$pair"; then continue; fi
    echo "layers: $file includes \"$include\": $layer/ may include only $allowed"
    status=1
  done < <(grep -rHn --include='*.h' --include='*.cpp' -E '^\s*#\s*include "[^"]+"' "$layer" |
    sed -E 's/^([^:]+):[0-9]+:/\1:/')
done
# An allowed include that is gone must leave the list (so it cannot come back unnoticed).
for pair in "${ALLOWED[@]}"; do
  file=${pair%%:*}
  include=${pair#*:}
  if ! grep -qF "#include \"$include\"" "$file" 2>/dev/null; then
    echo "layers: $file no longer includes \"$include\": remove it from ALLOWED in $0"
    status=1
  fi
done
[ $status -eq 0 ] && echo "layers: every include points down"
exit $status
