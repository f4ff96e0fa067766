#!/usr/bin/env bash
# ctest and pytest against a build made with -DBXDF_SANITIZE=ON (make test-sanitize). The first
# ASan or UBSan report aborts the process and fails its test.
set -uo pipefail
BUILD=${1:-build-sanitize}
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
cd "$ROOT"
PYTHON=/usr/bin/python3
status=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
start=$(date +%s)
echo "== cpp (ASan + UBSan)"
ctest --test-dir "$BUILD" --output-on-failure -j "$(nproc)" || status=1
echo "== python (ASan + UBSan)"
# The interpreter is not built with ASan: the runtime must be loaded first (LD_PRELOAD), and
# the interpreter's own never-freed objects are not leaks of ours.
ASAN_LIB=$(g++ -print-file-name=libasan.so)
LD_PRELOAD="$ASAN_LIB" ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 PYTHONPATH="$BUILD/python" \
  $PYTHON -m pytest tests/python -q -p no:cacheprovider || status=1
echo "test-sanitize: $(( $(date +%s) - start )) s of tests, $([ $status -eq 0 ] && echo passed || echo FAILED)"
exit $status
