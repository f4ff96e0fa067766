// A measured isotropic BRDF loaded from a file (MERL .binary or Cornell .brdf), with its
// lookup, its importance sampler and its raw measurements (for fitting). Loading goes through
// a small cache keyed by the file's path, modification time and size, so making several models
// from one file reads it once.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bxdf/measured/cornell.h"
#include "bxdf/measured/isotropic_sampler.h"
#include "bxdf/measured/merl.h"

namespace bxdf {

enum class MeasuredFormat { Merl, Cornell };

// One measurement: directions (unit, upper hemisphere, away from the surface) and the BRDF.
struct MeasuredSample {
  Vec3 wo, wi;
  RGB value;
};

class MeasuredData {
 public:
  // Reads a file; the format comes from the extension (.binary, .brdf) or, failing that, from
  // the first bytes. Throws ParameterError naming the file and the problem.
  static std::shared_ptr<const MeasuredData> read(const std::string& path);

  MeasuredFormat format() const { return format_; }
  const std::string& path() const { return path_; }
  const char* format_name() const { return format_ == MeasuredFormat::Merl ? "MERL" : "Cornell"; }

  // BRDF for unit wo, wi in the upper hemisphere. `interpolate` selects MERL's trilinear lookup
  // instead of its nearest cell; Cornell data are always interpolated (cornell.h).
  RGB lookup(const Vec3& wo, const Vec3& wi, bool interpolate) const {
    if (merl_) {
      const HalfDiff a = half_diff_from_directions(wi, wo);
      return interpolate ? merl_->lookup_trilinear(a) : merl_->lookup_nearest(a);
    }
    return cornell_table_->lookup(wo, wi);
  }
  const IsotropicSampler& sampler() const { return *sampler_; }

  // The measurements: every Cornell row; for MERL the centres of measured cells, every θh
  // and every `merl_stride`-th θd and φd cell (stride 1 = all 1.46M cells).
  std::vector<MeasuredSample> samples(int merl_stride = 1) const;

  const MerlData* merl() const { return merl_.get(); }
  const std::vector<CornellSample>& cornell() const { return cornell_; }

 private:
  MeasuredFormat format_ = MeasuredFormat::Cornell;
  std::string path_;
  std::unique_ptr<MerlData> merl_;
  std::vector<CornellSample> cornell_;
  std::unique_ptr<CornellTable> cornell_table_;
  std::unique_ptr<IsotropicSampler> sampler_;
};

// MeasuredData::read through the cache (path + modification time + size; a changed file is
// read again). Thread-safe.
std::shared_ptr<const MeasuredData> load_measured_data(const std::string& path);
// Number of actual file reads so far (for tests of the cache).
size_t measured_file_reads();

}  // namespace bxdf
