#!/usr/bin/env bash
# The read-only export tests with `bounce` where a clone in root's home puts
# it: inside a folder of mode 0700 that no other user may enter. Those tests
# drop to user `nobody`; they must still pass there (or skip, saying why,
# where dropping root is impossible), never read a failed exec as the
# program's exit code.
#
#   private_clone.sh BOUNCE INTEGRATION_TEST_BINARY
#
# Exit 0 when they pass, 77 (ctest: skipped) when one skipped, otherwise
# the test binary's failure.
set -euo pipefail
bounce=$1
tests=$2
home=$(mktemp -d "${TMPDIR:-/tmp}/bounce-private-home-XXXXXX")
trap 'rm -rf "$home"' EXIT
chmod 0700 "$home"
mkdir -p "$home/project/build/release/app"
cp "$bounce" "$home/project/build/release/app/bounce"
log="$home/gtest.log"
status=0
BOUNCE_TEST_CLI="$home/project/build/release/app/bounce" \
  "$tests" --gtest_filter='ExportFailure.*' >"$log" 2>&1 || status=$?
cat "$log"
if ((status != 0)); then
  exit "$status"
fi
if grep -q '^\[  SKIPPED \]' "$log"; then
  if [[ $(id -u) -eq 0 ]]; then
    echo "private_clone.sh: as root every ExportFailure test should run; see the skip reasons above" >&2
  fi
  exit 77
fi
