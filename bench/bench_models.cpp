// Single-thread throughput of every registered model's f, sample_f and pdf through the batch
// API, over 1M random upper-hemisphere (wo, wi) pairs (wi mirrored below the surface for
// transmission-only models), reported in items/s. Each model runs
// with its defaults and with every choice of each enum parameter (microfacet distributions,
// Fresnel kinds, shadowing), plus the combinations pbrt-v3's figures are quoted for; the
// Fresnel functions are timed on their own as well.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <string>
#include <vector>

#include "bxdf/fresnel.h"
#include "bxdf/registry.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"

using namespace bxdf;

namespace {

constexpr size_t kPairs = 1 << 20;

// Structure-of-arrays inputs and outputs, made once.
struct Data {
  std::vector<float> ox, oy, oz, ix, iy, iz, u1, u2;
  std::vector<float> r, g, b, x, y, z, pdf;
  Data() {
    for (auto* v : {&ox, &oy, &oz, &ix, &iy, &iz, &u1, &u2, &r, &g, &b, &x, &y, &z, &pdf})
      v->resize(kPairs);
    PCG32 rng(7);
    for (size_t i = 0; i < kPairs; ++i) {
      const Vec3 wo = sample_uniform_hemisphere(Point2(rng.uniform(), rng.uniform()));
      const Vec3 wi = sample_uniform_hemisphere(Point2(rng.uniform(), rng.uniform()));
      ox[i] = wo.x, oy[i] = wo.y, oz[i] = wo.z, ix[i] = wi.x, iy[i] = wi.y, iz[i] = wi.z;
      u1[i] = rng.uniform(), u2[i] = rng.uniform();
    }
  }
  DirectionsIn wo() const { return {ox.data(), oy.data(), oz.data()}; }
  DirectionsIn wi() const { return {ix.data(), iy.data(), iz.data()}; }
  // wi mirrored below the surface, for models that only transmit.
  std::vector<float> iz_below;
  DirectionsIn wi_below() {
    if (iz_below.empty())
      for (float v : iz) iz_below.push_back(-v);
    return {ix.data(), iy.data(), iz_below.data()};
  }
  // The pairs that give a transmission-only model something to evaluate.
  DirectionsIn wi_for(const BxDF& m) { return (m.flags() & kReflection) ? wi() : wi_below(); }
};

Data& data() {
  static Data d;
  return d;
}

void bench_f(benchmark::State& state, BxDFPtr m) {
  Data& d = data();
  for (auto _ : state) {
    m->f_batch(kPairs, d.wo(), d.wi_for(*m), {d.r.data(), d.g.data(), d.b.data()});
    benchmark::DoNotOptimize(d.r.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * kPairs);
}

void bench_sample_f(benchmark::State& state, BxDFPtr m) {
  Data& d = data();
  for (auto _ : state) {
    m->sample_f_batch(kPairs, d.wo(), d.u1.data(), d.u2.data(), {d.x.data(), d.y.data(), d.z.data()},
                      {d.r.data(), d.g.data(), d.b.data()}, d.pdf.data());
    benchmark::DoNotOptimize(d.pdf.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * kPairs);
}

void bench_pdf(benchmark::State& state, BxDFPtr m) {
  Data& d = data();
  for (auto _ : state) {
    m->pdf_batch(kPairs, d.wo(), d.wi_for(*m), d.pdf.data());
    benchmark::DoNotOptimize(d.pdf.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * kPairs);
}

// The Fresnel terms alone, over the cosines of the 1M wo directions.
void bench_fresnel_dielectric(benchmark::State& state) {
  Data& d = data();
  for (auto _ : state) {
    for (size_t i = 0; i < kPairs; ++i) d.r[i] = fresnel_dielectric(d.oz[i], 1.0f, 1.5f);
    benchmark::DoNotOptimize(d.r.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * kPairs);
}

void bench_fresnel_conductor(benchmark::State& state) {
  Data& d = data();
  const RGB eta(0.200f, 0.924f, 1.102f), k(3.912f, 2.452f, 2.142f);
  for (auto _ : state) {
    for (size_t i = 0; i < kPairs; ++i) {
      const RGB f = fresnel_conductor_seed(d.oz[i], eta, k);
      d.r[i] = f.r, d.g[i] = f.g, d.b[i] = f.b;
    }
    benchmark::DoNotOptimize(d.r.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * kPairs);
}

struct Config {
  std::string model, label;
  ParamSet params;
};

// Defaults, then each enum choice on its own, then the combinations quoted for pbrt-v3.
std::vector<Config> configs() {
  std::vector<Config> out;
  for (const ModelInfo& info : models()) {
    out.push_back({info.name, "defaults", {}});
    for (const ParamSpec& s : info.params) {
      if (s.kind != ParamKind::Enum) continue;
      for (const std::string& choice : s.choices) {
        if (choice == s.default_value.as_string()) continue;
        ParamSet p;
        p.set(s.name, choice);
        out.push_back({info.name, s.name + "=" + choice, p});
      }
    }
  }
  if (find_model("microfacet")) {
    ParamSet ggx;
    ggx.set("distribution", "ggx");
    out.push_back({"microfacet", "ggx", ggx});  // pbrt-v3's "GGX" row
    for (const char* dist : {"beckmann", "ggx"}) {
      for (const char* fresnel : {"dielectric", "conductor"}) {
        ParamSet p;
        p.set("distribution", dist);
        p.set("fresnel", fresnel);
        out.push_back({"microfacet", std::string(dist) + "+" + fresnel, p});
      }
    }
  }
  if (find_model("cycles_principled")) {
    // Every closure on: diffuse, sheen, specular, glass reflection and refraction, clearcoat.
    ParamSet p;
    p.set("metallic", 0.2);
    p.set("sheen", 0.5);
    p.set("clearcoat", 0.5);
    p.set("clearcoat_roughness", 0.2);
    p.set("transmission", 0.5);
    p.set("transmission_roughness", 0.2);
    out.push_back({"cycles_principled", "all_lobes", p});
  }
  if (find_model("cycles_glass")) {
    // The node's default roughness 0 is the delta form; the rough forms at roughness 0.3.
    for (const char* dist : {"ggx", "beckmann", "multi_ggx"}) {
      ParamSet p;
      p.set("distribution", dist);
      p.set("roughness", 0.3);
      out.push_back({"cycles_glass", std::string(dist) + "_r0.3", p});
    }
  }
  return out;
}

void register_all() {
  for (const Config& c : configs()) {
    BxDFPtr m;
    try {
      m = make(c.model, c.params);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "skipping %s %s: %s\n", c.model.c_str(), c.label.c_str(), e.what());
      continue;
    }
    const std::string name = c.model + "/" + c.label;
    benchmark::RegisterBenchmark(("f/" + name).c_str(), bench_f, m)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("sample_f/" + name).c_str(), bench_sample_f, m)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("pdf/" + name).c_str(), bench_pdf, m)->Unit(benchmark::kMillisecond);
  }
  benchmark::RegisterBenchmark("fresnel/dielectric", bench_fresnel_dielectric)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("fresnel/conductor", bench_fresnel_conductor)->Unit(benchmark::kMillisecond);
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
