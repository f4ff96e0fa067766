#!/usr/bin/env bash
# Runs the model benchmarks (single thread) and prints each result in M items/s next to the
# pbrt-v3 reference figure where there is one (goal: 2× the reference); then the other
# benchmark programs that are built (measured data, renderer) and the Python API timing.
# Usage: tools/run-bench.sh [BUILD] [extra benchmark flags, e.g. --benchmark_filter=ggx]
set -euo pipefail
BUILD=${1:-build}
shift || true
cd "$(dirname "$0")/.."
BIN="$BUILD/bench/bxdf_bench_models"
if [ ! -x "$BIN" ]; then
  echo "run-bench: $BIN not built (configure with -DBXDF_BUILD_BENCH=ON)" >&2
  exit 1
fi
OUT="$BUILD/bench/models.json"
"$BIN" --benchmark_out="$OUT" --benchmark_out_format=json --benchmark_min_time=0.3 "$@"

/usr/bin/python3 - "$OUT" <<'PY'
import json, sys
# pbrt-v3 -O3 on one core, M items/s (the task's reference figures).
REFERENCE = {
    "f/oren_nayar/defaults": 33.0,
    "f/microfacet/ggx": 20.0,
    "sample_f/microfacet/ggx": 5.8,
    "pdf/microfacet/ggx": 22.0,
    "f/microfacet/beckmann+dielectric": 9.9,
    "fresnel/conductor": 30.0,
}
rows = json.load(open(sys.argv[1]))["benchmarks"]

print()
print(f"{'benchmark':58s} {'M items/s':>10s} {'pbrt-v3':>8s} {'goal 2x':>8s} {'vs goal':>8s}")
for r in rows:
    rate = r.get("items_per_second", 0.0) / 1e6
    ref = REFERENCE.get(r["name"])
    extra = f"{ref:8.1f} {2 * ref:8.1f} {rate / (2 * ref):7.2f}x" if ref else ""
    print(f"{r['name']:58s} {rate:10.1f} {extra}")
PY

for other in "$BUILD/bench/measured/bxdf_bench_measured" "$BUILD/bench/render/bxdf_bench_render" \
             "$BUILD/bench/render/bxdf_bench_textured"; do
  if [ -x "$other" ]; then
    echo
    echo "== $(basename "$other")"
    "$other"
  fi
done
echo
echo "== Cycles' own texture cost on bxdf_bench_textured's scene (bench/cycles_texture_cost.py)"
blender -b --factory-startup --python-exit-code 1 --python bench/cycles_texture_cost.py 2>&1 \
  | grep -A3 '^cycles_texture_cost:' || { echo "run-bench: cycles_texture_cost failed" >&2; exit 1; }
if [ -d "$BUILD/python" ]; then
  echo
  echo "== Python API (bench/python_bench.py)"
  PYTHONPATH="$BUILD/python" /usr/bin/python3 bench/python_bench.py
fi
echo
echo "== BXDF_LAB vs Cycles side by side (bench/side_by_side.py, 2 threads each)"
for scene in ${SIDE_BY_SIDE_SCENES:-cornell principled_showroom}; do
  BXDF_PYTHONPATH="$(pwd)/$BUILD/python" blender -b --factory-startup --python-exit-code 1 \
    --python bench/side_by_side.py -- --scene "$scene" --spp 64 256 --threads 2 \
    --reference-spp 1024 --repeats 3 --json "$BUILD/bench/side_by_side_$scene.json" 2>&1 \
    | grep -E '^(side_by_side|  *spp| +[0-9]+ )' || { echo "run-bench: side_by_side failed on $scene" >&2; exit 1; }
done
echo
echo "== Fixed cost of a render in Blender, cornell at 1 spp (bench/fixed_cost.py, 2 threads each)"
BXDF_PYTHONPATH="$(pwd)/$BUILD/python" blender -b --factory-startup --python-exit-code 1 \
  --python bench/fixed_cost.py -- --scene cornell --renders 10 --threads 2 2>&1 \
  | grep -E '^(fixed_cost|BXDF_LAB|CYCLES|2 spp)' || { echo "run-bench: fixed_cost failed" >&2; exit 1; }
if command -v blender >/dev/null && [ -d "$BUILD/python" ]; then
  echo
  echo "== HDRI scene: time to equal error against Cycles (bench/hdri_vs_cycles.py)"
  PYTHONPATH="$BUILD/python" blender -b --factory-startup --python-exit-code 1 \
    --python bench/hdri_vs_cycles.py 2>/dev/null | grep -v '^Fra:\|^Saved:\|^ Time:\|^Blender\|^Read\|^$'
fi
