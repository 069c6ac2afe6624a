#!/usr/bin/env bash
# An existing output that cannot be replaced (immutable, or read-only for a non-root user) is
# refused before rendering, with nothing written; it used to be found only after the render,
# whose result was then deleted.
#
#   output_files.sh NXRENDER SCENE WORK_DIR
set -euo pipefail
nxrender="$1" scene="$2" work="$3"
# An immutable file needs root and a file system with attributes (ext4 here); the build
# directory is tried first, then a temporary directory.
make_locked() {
  echo old >"$1/out.exr"
  if [ "$(id -u)" = 0 ]; then chattr +i "$1/out.exr" 2>/dev/null; else chmod 444 "$1/out.exr"; fi
}
d="$work/output_files.$$"
mkdir -p "$d"
cleanup() { chattr -i "$d/out.exr" 2>/dev/null || true; rm -rf "$d"; }
trap cleanup EXIT
if ! make_locked "$d"; then
  rm -rf "$d"
  d="$(mktemp -d)"
  make_locked "$d" || { echo "no file system here can hold an immutable file: cannot test"; exit 77; }
fi
set +e
"$nxrender" --spp 64 -o "$d/out.exr" "$scene" 2>"$d/err"
rc=$?
set -e
[ "$rc" = 1 ] || { echo "expected exit status 1, got $rc"; cat "$d/err"; exit 1; }
grep -q "out.exr: exists and cannot be replaced" "$d/err" || { cat "$d/err"; exit 1; }
grep -q "%" "$d/err" && { echo "it rendered before refusing"; cat "$d/err"; exit 1; }
[ "$(cat "$d/out.exr")" = old ] || { echo "the existing file changed"; exit 1; }
[ -z "$(ls -A "$d" | grep -v -e '^out.exr$' -e '^err$')" ] || { echo "files were left:"; ls -A "$d"; exit 1; }
echo "an output that cannot be replaced is refused before rendering"
