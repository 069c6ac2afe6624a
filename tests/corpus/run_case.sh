#!/usr/bin/env bash
# Runs nxrender on one malformed scene and checks: exit status 1, the expected message (a
# fixed string, with {file} replaced by the scene's path, {dir} by the corpus directory and
# {material_kinds} by the registry's list of material kinds as messages write it, {shape_tags}
# by the shape kinds' elements likewise), nothing
# written, and an answer within 10 seconds.
#
#   run_case.sh NXRENDER CORPUS_DIR FILE.scn NXDOCS
set -euo pipefail
nxrender="$1" dir="$2" name="$3" nxdocs="$4"
expected="$(awk -F '\t' -v n="$name" '$1 == n { print $2 }' "$dir/expected.txt")"
[ -n "$expected" ] || { echo "no expected message for $name"; exit 1; }
scene="$dir/$name"
expected="${expected//\{file\}/$scene}"
expected="${expected//\{dir\}/$dir}"
if [[ "$expected" == *"{material_kinds}"* ]]; then
  kinds="$("$nxdocs" --material-kind-list)"
  [ -n "$kinds" ] || { echo "nxdocs --material-kind-list printed nothing"; exit 1; }
  expected="${expected//\{material_kinds\}/$kinds}"
fi
if [[ "$expected" == *"{shape_tags}"* ]]; then
  tags="$("$nxdocs" --shape-tag-list)"
  [ -n "$tags" ] || { echo "nxdocs --shape-tag-list printed nothing"; exit 1; }
  expected="${expected//\{shape_tags\}/$tags}"
fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
set +e
(cd "$work" && timeout 10 "$nxrender" --spp 1 "$scene") >"$work.out" 2>&1
rc=$?
set -e
output="$(cat "$work.out")"
rm -f "$work.out"
[ "$rc" = 1 ] || { echo "expected exit status 1, got $rc"; echo "$output"; exit 1; }
grep -qF -- "nxrender: error: $expected" <<<"$output" || { echo "expected: nxrender: error: $expected"; echo "got:      $output"; exit 1; }
[ -z "$(ls -A "$work")" ] || { echo "files were written:"; ls -A "$work"; exit 1; }
