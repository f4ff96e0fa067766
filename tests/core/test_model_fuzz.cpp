// Hostile-input fuzzing of every model: the curated parameter sets plus random valid ones
// (with range extremes), each given zero, NaN, Inf, unnormalised, huge, tiny, grazing,
// coincident and opposite directions and out-of-range random numbers through f, sample_f, pdf,
// rho_hd, rho_hh and the batch APIs. Every output must be finite and non-negative, sampled
// directions unit length, and each batch result identical to the scalar call.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "bxdf/registry.h"
#include "bxdf/rng.h"
#include "bxdf/sampling.h"
#include "model_grid.h"
#include "random_params.h"

using namespace bxdf;
using namespace bxdf::test;

namespace {

constexpr int kRandomParamSets = 24;
constexpr int kBatch = 512;
constexpr int kBatchesPerModel = 4;  // × kBatch pairs × (3 scalar + 3 batch calls)
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

float random_sign(PCG32& rng) { return rng.bounded(2) ? 1.0f : -1.0f; }

Vec3 random_unit(PCG32& rng) { return sample_uniform_sphere(Point2(rng.uniform(), rng.uniform())); }

// A direction chosen to hurt, sometimes related to `other` (the partner direction).
Vec3 hostile_direction(PCG32& rng, const Vec3& other) {
  Vec3 v = random_unit(rng);
  switch (rng.bounded(18)) {
    case 0: case 1: case 2: case 3: return v;
    case 4: return v * std::pow(10.0f, -20.0f + 40.0f * rng.uniform());  // unnormalised
    case 5: return v * (rng.bounded(2) ? 1e-20f : 1e-40f);                // tiny, denormal
    case 6: return v * (rng.bounded(2) ? 1e30f : std::numeric_limits<float>::max());
    case 7: return Vec3(0.0f * random_sign(rng), 0.0f * random_sign(rng), 0.0f * random_sign(rng));
    case 8: { float c[3] = {v.x, v.y, v.z}; c[rng.bounded(3)] = kNaN; return {c[0], c[1], c[2]}; }
    case 9: { float c[3] = {v.x, v.y, v.z}; c[rng.bounded(3)] = kInf * random_sign(rng); return {c[0], c[1], c[2]}; }
    case 10: return Vec3(v.x, v.y, rng.bounded(2) ? 0.0f : -0.0f);        // exactly grazing
    case 11: return Vec3(v.x, v.y, 1e-7f * random_sign(rng));              // nearly grazing
    case 12: return Vec3(0.0f, 0.0f, random_sign(rng));                    // the poles
    case 13: return other;                                                 // wi = wo
    case 14: return -other;                                                // half vector 0
    case 15: return Vec3(-other.x, -other.y, other.z);                     // the mirror direction
    case 16: return Vec3(-other.x * 0.66f, -other.y * 0.66f, -other.z);    // near a refraction
    default: return Vec3(v.x, v.y, -std::fabs(v.z));                       // below the horizon
  }
}

float hostile_u(PCG32& rng) {
  switch (rng.bounded(12)) {
    case 0: return 0.0f;
    case 1: return 0x1.fffffep-1f;  // just under 1
    case 2: return 1.0f;
    case 3: return kNaN;
    case 4: return -0.25f;
    case 5: return 7.0f;
    case 6: return kInf * random_sign(rng);
    case 7: return 0.5f;
    default: return rng.uniform();
  }
}

bool good(float x) { return finite_nonnegative(x); }
bool good(const RGB& c) { return finite_nonnegative(c); }
bool same(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0 || a == b; }

std::string vec(const Vec3& v) {
  char buf[100];
  std::snprintf(buf, sizeof buf, "(%.9g, %.9g, %.9g)", v.x, v.y, v.z);
  return buf;
}

// Counts failures and keeps the first one's description (built only then: the loop is hot).
struct Failures {
  int count = 0;
  std::string first;
  template <class Describe>
  void add(Describe describe) {
    if (count++ == 0) first = describe();
  }
};

// Runs one model instance through kBatchesPerModel hostile batches.
void fuzz_instance(const BxDF& m, PCG32& rng, Failures& fail) {
  std::vector<float> ox(kBatch), oy(kBatch), oz(kBatch), ix(kBatch), iy(kBatch), iz(kBatch),
      u1(kBatch), u2(kBatch), fr(kBatch), fg(kBatch), fb(kBatch), p(kBatch), sx(kBatch),
      sy(kBatch), sz(kBatch), sr(kBatch), sg(kBatch), sb(kBatch), sp(kBatch);
  for (int batch = 0; batch < kBatchesPerModel; ++batch) {
    for (int i = 0; i < kBatch; ++i) {
      const Vec3 wo = hostile_direction(rng, random_unit(rng));
      const Vec3 wi = hostile_direction(rng, wo);
      ox[i] = wo.x, oy[i] = wo.y, oz[i] = wo.z, ix[i] = wi.x, iy[i] = wi.y, iz[i] = wi.z;
      u1[i] = hostile_u(rng), u2[i] = hostile_u(rng);
    }
    const DirectionsIn wo_in{ox.data(), oy.data(), oz.data()}, wi_in{ix.data(), iy.data(), iz.data()};
    m.f_batch(kBatch, wo_in, wi_in, {fr.data(), fg.data(), fb.data()});
    m.pdf_batch(kBatch, wo_in, wi_in, p.data());
    m.sample_f_batch(kBatch, wo_in, u1.data(), u2.data(), {sx.data(), sy.data(), sz.data()},
                     {sr.data(), sg.data(), sb.data()}, sp.data());
    for (int i = 0; i < kBatch; ++i) {
      const Vec3 wo(ox[i], oy[i], oz[i]), wi(ix[i], iy[i], iz[i]);
      auto at = [&] { return " at wo " + vec(wo) + " wi " + vec(wi); };
      const RGB f = m.f(wo, wi);
      if (!good(f)) fail.add([&] { return "f not finite/non-negative" + at(); });
      if (!same(f.r, fr[i]) || !same(f.g, fg[i]) || !same(f.b, fb[i])) fail.add([&] { return "f_batch != f" + at(); });
      const float pdf = m.pdf(wo, wi);
      if (!good(pdf)) fail.add([&] { return "pdf not finite/non-negative" + at(); });
      if (!same(pdf, p[i])) fail.add([&] { return "pdf_batch != pdf" + at(); });

      const BxDFSample s = m.sample_f(wo, Point2(u1[i], u2[i]));
      auto sat = [&] {
        char u_text[64];
        std::snprintf(u_text, sizeof u_text, " u (%.9g, %.9g)", u1[i], u2[i]);
        return " at wo " + vec(wo) + u_text;
      };
      if (!good(s.pdf) || !good(s.f) || !is_finite(s.wi)) fail.add([&] { return "sample_f output not finite/non-negative" + sat(); });
      if (s.pdf > 0.0f && std::fabs(length(s.wi) - 1.0f) > 1e-3f) fail.add([&] { return "sampled wi not unit: " + vec(s.wi) + sat(); });
      if (!same(s.pdf, sp[i]) || !same(s.wi.x, sx[i]) || !same(s.wi.y, sy[i]) ||
          !same(s.wi.z, sz[i]) || !same(s.f.r, sr[i]) || !same(s.f.g, sg[i]) || !same(s.f.b, sb[i]))
        fail.add([&] { return "sample_f_batch != sample_f" + sat(); });
    }
  }
  // The reflectance estimators with hostile directions and sample counts.
  for (int n : {-3, 0, 1, 7}) {
    const Vec3 wo = hostile_direction(rng, random_unit(rng));
    if (!good(m.rho_hd(wo, n, rng.next_u32()))) fail.add([&] { return "rho_hd not finite/non-negative at wo " + vec(wo) + " n " + std::to_string(n); });
    if (!good(m.rho_hh(n, rng.next_u32()))) fail.add([&] { return "rho_hh not finite/non-negative, n " + std::to_string(n); });
  }
}

// A model that bypasses BxDFImpl's guards: NaN for directions below the horizon, and a batch
// path that disagrees with the scalar one. The fuzzer must notice both.
class Broken final : public BxDF {
 public:
  explicit Broken(bool nan) : BxDF(kReflection | kDiffuse), nan_(nan) {}
  RGB f(const Vec3&, const Vec3& wi) const override {
    return RGB(nan_ && wi.z < 0 ? kNaN : 0.1f);
  }
  BxDFSample sample_f(const Vec3&, Point2) const override { return {}; }
  float pdf(const Vec3&, const Vec3&) const override { return 0.0f; }
  void f_batch(size_t n, DirectionsIn wo, DirectionsIn wi, RGBOut out) const override {
    for (size_t i = 0; i < n; ++i) {
      const RGB v = f(Vec3(wo.x[i], wo.y[i], wo.z[i]), Vec3(wi.x[i], wi.y[i], wi.z[i]));
      out.r[i] = v.r, out.g[i] = nan_ ? v.g : 0.2f, out.b[i] = v.b;
    }
  }
  void sample_f_batch(size_t n, DirectionsIn, const float*, const float*, DirectionsOut wi,
                      RGBOut f, float* pdf) const override {
    for (size_t i = 0; i < n; ++i)
      wi.x[i] = wi.y[i] = wi.z[i] = f.r[i] = f.g[i] = f.b[i] = pdf[i] = 0.0f;
  }
  void pdf_batch(size_t n, DirectionsIn, DirectionsIn, float* out) const override {
    for (size_t i = 0; i < n; ++i) out[i] = 0.0f;
  }

 private:
  bool nan_;
};

class ModelFuzz : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(ModelFuzz, HostileInputsGiveFiniteNonNegativeOutputs) {
  const std::string& model = GetParam();
  const ModelInfo* info = find_model(model);
  ASSERT_NE(info, nullptr);
  PCG32 rng(0xf022 + std::hash<std::string>()(model));
  std::vector<std::pair<std::string, ParamSet>> sets;
  for (const GridEntry& e : grid_for(model)) sets.push_back({describe(model, e), e.params});
  // Random sets drawn parameter by parameter. A model may refuse a combination whose values
  // are each in range (lafortune bounds max|C|^n) with a ParameterError; such draws are
  // redrawn, and counted so that a model refusing most in-range draws shows up.
  int refused = 0;
  std::string first_refusal;
  for (int i = 0; i < kRandomParamSets; ++i) {
    for (int attempt = 0; attempt < 20; ++attempt) {
      ParamSet p = random_valid_params(info->params, rng);
      try {
        make(model, p);
      } catch (const ParameterError& ex) {
        if (refused++ == 0) first_refusal = ex.what();
        continue;
      }
      sets.push_back({model + "[random " + std::to_string(i) + "]", p});
      break;
    }
  }
  if (refused > 0)
    std::printf("[ fuzz ] %s refused %d in-range random parameter sets, e.g. %s\n", model.c_str(),
                refused, first_refusal.c_str());
  EXPECT_GE(sets.size(), grid_for(model).size() + kRandomParamSets * 3 / 4)
      << model << " refuses most in-range parameter sets; first: " << first_refusal;
  std::printf("[ fuzz ] %s: %zu parameter sets, %zu calls\n", model.c_str(), sets.size(),
              sets.size() * kBatchesPerModel * kBatch * 6);
  for (const auto& [label, params] : sets) {
    BxDFPtr m;
    try {
      m = make(model, params);
    } catch (const std::exception& ex) {
      ADD_FAILURE() << label << ": parameters refused: " << ex.what();
      continue;
    }
    Failures fail;
    fuzz_instance(*m, rng, fail);
    EXPECT_EQ(fail.count, 0) << label << " " << m->params().size() << " params "
                             << [&] {
                                  std::string s;
                                  for (size_t k = 0; k < m->params().size(); ++k)
                                    s += m->params().names()[k] + "=" + m->params().values()[k].to_string() + " ";
                                  return s;
                                }()
                             << ": " << fail.count << " failures; first: " << fail.first;
  }
}

TEST(FuzzHarness, CatchesNaNAndBatchMismatch) {
  PCG32 rng(1);
  Failures nan, mismatch;
  fuzz_instance(Broken(true), rng, nan);
  fuzz_instance(Broken(false), rng, mismatch);
  EXPECT_GT(nan.count, 0);
  EXPECT_NE(nan.first.find("f not finite"), std::string::npos) << nan.first;
  EXPECT_GT(mismatch.count, 0);
  EXPECT_NE(mismatch.first.find("f_batch != f"), std::string::npos) << mismatch.first;
}

INSTANTIATE_TEST_SUITE_P(AllModels, ModelFuzz, ::testing::ValuesIn(registered_model_names()),
                         [](const auto& info) { return info.param; });
