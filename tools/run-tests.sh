#!/usr/bin/env bash
# Runs every test suite: C++ (ctest), Python (pytest), Blender (pytest inside blender -b),
# comparison harness (pytest). Ends with one line "N passed, N failed" over all suites and
# exits non-zero when any suite fails.
set -uo pipefail
BUILD=${1:-build}
shift || true
SUITES=${*:-cpp python blender compare}   # a subset may be named: run-tests.sh build python
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
cd "$ROOT"
PYTHON=/usr/bin/python3
LOGDIR="$BUILD/test-logs"
rm -rf "$LOGDIR"
mkdir -p "$LOGDIR"
export BXDF_PYTHONPATH="$ROOT/$BUILD/python"
status=0

# run_suite NAME COMMAND...: runs the suite if selected, shows its output, remembers its log.
run_suite() {
  local name=$1; shift
  case " $SUITES " in *" $name "*) ;; *) return 0 ;; esac
  echo "== $name"
  "$@" 2>&1 | tee "$LOGDIR/$name.log"
  local rc=${PIPESTATUS[0]}
  if [ "$rc" -ne 0 ]; then
    echo "!! $name failed (exit $rc)"
    status=1
  fi
}

run_suite cpp ctest --test-dir "$BUILD" --output-on-failure -j "$(nproc)"
if [ -d tests/python ]; then
  case " $SUITES " in *" python "*)
  [ -d "$BUILD/python/bxdf" ] || { echo "!! the Python module was not built ($BUILD/python/bxdf missing)"; status=1; } ;; esac
  run_suite python env PYTHONPATH="$BUILD/python" $PYTHON -m pytest tests/python -q -p no:cacheprovider
fi
if [ -f tests/blender/run.py ]; then
  run_suite blender env PYTHONPATH="$BUILD/python" blender -b --factory-startup --python-exit-code 1 \
    --python tests/blender/run.py -- -q -p no:cacheprovider
fi
if [ -d tests/compare ]; then
  run_suite compare env PYTHONPATH="$ROOT:$BUILD/python" $PYTHON -m pytest tests/compare -q -p no:cacheprovider
fi

# One closing line over every suite (ctest's and pytest's own summaries, added up).
$PYTHON - "$LOGDIR" <<'PY'
import pathlib, re, sys
passed = failed = skipped = 0
for log in sorted(pathlib.Path(sys.argv[1]).glob("*.log")):
    text = log.read_text(errors="replace")
    m = re.search(r"(\d+)% tests passed, (\d+) tests? failed out of (\d+)", text)
    if m:
        failed += int(m.group(2)); passed += int(m.group(3)) - int(m.group(2))
        continue
    lines = [l for l in text.splitlines() if re.search(r"\d+ (passed|failed|error)", l)]
    if lines:
        last = lines[-1]
        for n, what in re.findall(r"(\d+) (passed|failed|errors?|skipped)", last):
            if what == "passed": passed += int(n)
            elif what == "skipped": skipped += int(n)
            else: failed += int(n)
print(f"total: {passed} passed, {failed} failed" + (f", {skipped} skipped" if skipped else ""))
PY
exit $status
