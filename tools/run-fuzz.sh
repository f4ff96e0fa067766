#!/usr/bin/env bash
# Runs each libFuzzer target for a bounded time: tools/run-fuzz.sh BUILD SECONDS TARGET...
# Each target starts from its seed corpus (fuzz/<target>/corpus, read only) plus what earlier
# runs found (BUILD/fuzz-corpus/<target>). A crash, sanitizer report, leak, timeout or
# out-of-memory is a finding: its input is saved under BUILD/fuzz-findings/ and the script fails.
set -uo pipefail
BUILD=$1
SECONDS_EACH=$2
shift 2
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
cd "$ROOT"
status=0
for target in "$@"; do
  corpus="$BUILD/fuzz-corpus/$target"
  findings="$BUILD/fuzz-findings"
  mkdir -p "$corpus" "$findings"
  log="$BUILD/fuzz-$target.log"
  echo "== fuzz $target for ${SECONDS_EACH} s"
  # One job, one thread: the machine is shared. JSON inputs may be longer than the default 4 KB.
  "$BUILD/fuzz/fuzz_$target" "$corpus" "fuzz/$target/corpus" -max_total_time="$SECONDS_EACH" \
    -timeout=30 -rss_limit_mb=2560 -max_len=65536 -print_final_stats=1 \
    -artifact_prefix="$findings/$target-" > "$log" 2>&1
  rc=$?
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | head -1 | grep -o '[0-9]*$')
  if [ "$rc" -ne 0 ]; then
    echo "!! fuzz $target: finding (exit $rc) after ${runs:-?} runs; see $log and $findings/"
    grep -m 5 -E 'ERROR|runtime error|SUMMARY' "$log"
    status=1
  else
    echo "fuzz $target: ${runs:-?} runs, no finding"
  fi
done
exit $status
