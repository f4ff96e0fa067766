// Measured BRDFs, single thread: MERL lookups (nearest cell and trilinear) on an in-memory
// table, Cornell lookups, the `measured` model's f and sample_f, and the wall time of fits to
// the Cornell paints (goal: a 2-lobe Lafortune fit in under 2 s).
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <vector>

#include "bxdf/fit/fit.h"
#include "bxdf/measured/measured_data.h"
#include "bxdf/measured/merl.h"
#include "bxdf/registry.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"

using namespace bxdf;

namespace {

const std::string kData = BXDF_DATA_DIR "/measured/";
constexpr size_t kPairs = 1 << 16;

struct Pairs {
  std::vector<Vec3> wo, wi;
  std::vector<Point2> u;
  Pairs() {
    PCG32 rng(3);
    for (size_t i = 0; i < kPairs; ++i) {
      wo.push_back(sample_uniform_hemisphere({rng.uniform(), rng.uniform()}));
      wi.push_back(sample_uniform_hemisphere({rng.uniform(), rng.uniform()}));
      u.push_back({rng.uniform(), rng.uniform()});
    }
  }
};
const Pairs& pairs() {
  static const Pairs p;
  return p;
}

// A full-size MERL table with smooth synthetic values (no MERL file ships with the project).
const MerlData& merl_table() {
  static const MerlData d = [] {
    MerlData m;
    m.rgb.resize(3 * kMerlCells);
    m.measured.assign(kMerlCells, 1);
    for (size_t i = 0; i < kMerlCells; ++i)
      for (int c = 0; c < 3; ++c) m.rgb[3 * i + size_t(c)] = 0.1f + 1e-7f * static_cast<float>(i);
    return m;
  }();
  return d;
}

void BM_MerlLookupNearest(benchmark::State& state) {
  const MerlData& m = merl_table();
  const Pairs& p = pairs();
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(m.lookup_nearest(half_diff_from_directions(p.wi[i], p.wo[i])));
    i = (i + 1) & (kPairs - 1);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MerlLookupNearest);

void BM_MerlLookupTrilinear(benchmark::State& state) {
  const MerlData& m = merl_table();
  const Pairs& p = pairs();
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(m.lookup_trilinear(half_diff_from_directions(p.wi[i], p.wo[i])));
    i = (i + 1) & (kPairs - 1);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MerlLookupTrilinear);

void BM_CornellLookup(benchmark::State& state) {
  const auto data = load_measured_data(kData + "krylon_blue.brdf");
  const Pairs& p = pairs();
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(data->lookup(p.wo[i], p.wi[i], true));
    i = (i + 1) & (kPairs - 1);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CornellLookup);

void BM_MeasuredModelSampleF(benchmark::State& state) {
  ParamSet params;
  params.set("path", kData + "krylon_blue.brdf");
  const BxDFPtr m = make("measured", params);
  const Pairs& p = pairs();
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(m->sample_f(p.wo[i], p.u[i]));
    i = (i + 1) & (kPairs - 1);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MeasuredModelSampleF);

void BM_LoadCornellUncached(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(MeasuredData::read(kData + "krylon_blue.brdf"));
}
BENCHMARK(BM_LoadCornellUncached)->Unit(benchmark::kMillisecond);

void BM_Fit(benchmark::State& state, const std::string& file, const std::string& model, int lobes) {
  const auto samples = load_measured_data(kData + file)->samples();
  fit::FitOptions o;
  o.model = model;
  o.lobes = lobes;
  double error = 0.0;
  for (auto _ : state) error = fit::fit(samples, o).report.error;
  state.counters["error"] = error;
}
BENCHMARK_CAPTURE(BM_Fit, lafortune2_krylon, "krylon_blue.brdf", "lafortune", 2)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_Fit, lafortune2_acryl, "acryl_blue.brdf", "lafortune", 2)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_Fit, lafortune2_garnet, "garnet_red.brdf", "lafortune", 2)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_Fit, cook_torrance_krylon, "krylon_blue.brdf", "cook_torrance", 1)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
