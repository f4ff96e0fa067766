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
# the interpreter's own never-freed objects are not leaks of ours. libstdc++ is preloaded too:
# the interpreter does not link it, and ASan's C++-throw interceptor fails ("CHECK failed:
# real___cxa_throw") when libstdc++ arrives later with the module.
PRELOAD="$(g++ -print-file-name=libasan.so) $(g++ -print-file-name=libstdc++.so)"
LD_PRELOAD="$PRELOAD" ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 PYTHONPATH="$BUILD/python" \
  $PYTHON -m pytest tests/python -q -p no:cacheprovider || status=1
echo "== not run under the sanitizers: the blender and compare suites (they drive Blender, Cycles and"
echo "   POV-Ray for many minutes; the module's own use inside Blender is covered above by"
echo "   tests/python/test_blender_import.py, which runs Blender with the same preloads)"
echo "test-sanitize: $(( $(date +%s) - start )) s of tests, $([ $status -eq 0 ] && echo passed || echo FAILED)"
exit $status
