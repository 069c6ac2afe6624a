#!/usr/bin/env bash
# Runs a command and checks both its exit status and its output (stdout and stderr together):
# CTest's PASS_REGULAR_EXPRESSION ignores the exit status, so an error printed by a program
# that then exits 0 would pass. PATTERN is an extended regular expression the whole output
# must match ('.' matches line breaks too, as in CTest's); with a leading '!' one it must not.
#
#   expect_status.sh STATUS PATTERN COMMAND [ARGS...]
set -uo pipefail
want="$1" pattern="$2"
shift 2
out="$("$@" 2>&1)"
got=$?
fail=0
if [ "$got" != "$want" ]; then
  echo "FAIL: exit status $got, expected $want: $*"
  fail=1
fi
if [ "${pattern:0:1}" = "!" ]; then
  if grep -qzE -e "${pattern:1}" <<<"$out"; then
    echo "FAIL: the output matches '${pattern:1}', which it must not"
    fail=1
  fi
elif ! grep -qzE -e "$pattern" <<<"$out"; then
  echo "FAIL: the output does not match '$pattern'"
  fail=1
fi
if [ "$fail" = 1 ]; then
  echo "--- output ---"
  echo "$out" | head -40
  exit 1
fi
echo "status $got and output as expected"
