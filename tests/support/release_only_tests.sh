#!/usr/bin/env bash
# The names in tests/release_only_tests.txt (tests CI runs outside its sanitizer pass):
#   release_only_tests.sh LIST regex    prints them as a CTest -E regular expression
#   release_only_tests.sh LIST check BUILD_DIR
#                                       fails unless each names exactly one test of the build
#                                       (a renamed test would silently run in both passes, or
#                                       a removed one leave a stale line)
set -uo pipefail
list="$1" mode="$2"
names=$(sed -e 's/#.*//' -e 's/[[:space:]]*$//' "$list" | grep -v '^$')
if [ "$mode" = regex ]; then
  echo "^($(echo "$names" | sed 's/\./\\./g' | paste -sd '|'))\$"
  exit 0
fi
all=$(ctest --test-dir "$3" -N | sed -n 's/^ *Test *#[0-9]*: //p')
fail=0
for n in $names; do
  count=$(grep -cxF -- "$n" <<<"$all")
  if [ "$count" != 1 ]; then
    echo "FAIL: $n names $count tests"
    fail=1
  fi
done
[ "$fail" = 0 ] && echo "$(echo "$names" | wc -l) release-only tests, each a test of the build"
exit "$fail"
