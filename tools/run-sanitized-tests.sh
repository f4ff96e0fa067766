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
# Each gtest binary runs once with all its cases, not once per case as ctest does: under ASan a
# process start costs seconds (8 s on a loaded machine), which over ~400 cases made ctest take hours.
# The binaries and working folders are ctest's own list; the binaries run one after the other
# while each uses every core it wants (the renderer's tests use TBB).
mapfile -t RUNS < <(ctest --test-dir "$BUILD" --show-only=json-v1 | $PYTHON -c '
import json, sys
seen = {}
for test in json.load(sys.stdin)["tests"]:
    command = test.get("command") or []
    wd = next((p["value"] for p in test.get("properties", []) if p["name"] == "WORKING_DIRECTORY"), ".")
    gtest = any(a.startswith("--gtest_filter") for a in command)
    key = command[0] + " --gtest_brief=1" if gtest else " ".join(command)
    if command and key not in seen:
        seen[key] = wd
for key, wd in seen.items():
    print(wd + "\t" + key)
')
for run in "${RUNS[@]}"; do
  wd=${run%%$'\t'*}
  command=${run#*$'\t'}
  echo "-- $command"
  ( cd "$wd" && $command ) || { echo "FAILED: $command"; status=1; }
done
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
