#!/usr/bin/env bash
# No CTest entry may pass whatever its exit status: PASS_REGULAR_EXPRESSION makes CTest ignore
# the status, and WILL_FAIL passes on any failure, a crash included. Every such check goes
# through tests/support/expect_status.sh (status and output). Reads the CTest files CMake
# generated under BUILD_TESTS_DIR.
#
#   check_ctest_entries.sh BUILD_TESTS_DIR
set -uo pipefail
dir="$1"
files=$(find "$dir" -name CTestTestfile.cmake)
[ -n "$files" ] || { echo "FAIL: no CTestTestfile.cmake under $dir"; exit 1; }
entries=$(cat $files | grep -c "^add_test\|^  add_test" || true)
found=$(grep -l "PASS_REGULAR_EXPRESSION\|WILL_FAIL" $files || true)
if [ -n "$found" ]; then
  echo "FAIL: CTest entries that pass whatever the exit status (use expect_status.sh):"
  grep -h -B1 "PASS_REGULAR_EXPRESSION\|WILL_FAIL" $found | grep -o 'set_tests_properties([^ ]*' | sort -u
  exit 1
fi
echo "every CTest entry checks its exit status ($entries entries read)"
