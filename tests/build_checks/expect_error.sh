#!/usr/bin/env bash
# Compiles a file that must not compile and checks the compiler says why: the checks that the
# type system makes (a light kind without its gradient declaration).
#
#   expect_error.sh COMPILER SOURCE_DIR FILE EXPECTED_TEXT [FLAGS...]
set -uo pipefail
compiler="$1" src="$2" file="$3" expected="$4"
shift 4
out="$("$compiler" -std=c++20 -fsyntax-only -I"$src" "$@" "$file" 2>&1)" && {
  echo "FAIL: $file compiled"
  exit 1
}
grep -qF -- "$expected" <<<"$out" || {
  echo "FAIL: $file did not compile, but not because of: $expected"
  echo "$out" | head -20
  exit 1
}
echo "refused at compile time: $expected"
