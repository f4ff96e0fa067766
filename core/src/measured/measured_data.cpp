#include "bxdf/measured/measured_data.h"

#include <atomic>
#include <filesystem>
#include <fstream>
#include <list>
#include <mutex>

#include "bxdf/params.h"

namespace bxdf {

namespace {

std::atomic<size_t> g_reads{0};

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

MeasuredFormat detect_format(const std::string& path) {
  if (ends_with(path, ".binary")) return MeasuredFormat::Merl;
  if (ends_with(path, ".brdf")) return MeasuredFormat::Cornell;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ParameterError("measured file '" + path + "' cannot be opened");
  int32_t dims[3] = {0, 0, 0};
  in.read(reinterpret_cast<char*>(dims), sizeof(dims));
  if (in && dims[0] == kMerlThetaH && dims[1] == kMerlThetaD && dims[2] == kMerlPhiD)
    return MeasuredFormat::Merl;
  in.clear();
  in.seekg(0);
  std::string first;
  std::getline(in, first);
  if (!first.empty() && first[0] == '#') return MeasuredFormat::Cornell;
  throw ParameterError("measured file '" + path +
                       "' is neither a MERL .binary (header 90 90 180) nor a Cornell .brdf "
                       "(text starting with '#')");
}

}  // namespace

std::shared_ptr<const MeasuredData> MeasuredData::read(const std::string& path) {
  auto d = std::make_shared<MeasuredData>();
  d->path_ = path;
  d->format_ = detect_format(path);
  ++g_reads;
  if (d->format_ == MeasuredFormat::Merl) {
    d->merl_ = std::make_unique<MerlData>(read_merl(path));
  } else {
    d->cornell_ = read_cornell(path);
    d->cornell_table_ = std::make_unique<CornellTable>(d->cornell_);
  }
  const MeasuredData& self = *d;
  d->sampler_ = std::make_unique<IsotropicSampler>(
      [&self](const Vec3& wo, const Vec3& wi) { return self.lookup(wo, wi, true); });
  return d;
}

std::vector<MeasuredSample> MeasuredData::samples(int merl_stride) const {
  std::vector<MeasuredSample> out;
  if (!merl_) {
    out.reserve(cornell_.size());
    for (const CornellSample& s : cornell_)
      out.push_back({direction_from_angles(s.theta_s, s.phi_s),
                     direction_from_angles(s.theta_i, s.phi_i), s.value});
    return out;
  }
  const int stride = std::max(1, merl_stride);
  for (int h = 0; h < kMerlThetaH; ++h)
    for (int t = 0; t < kMerlThetaD; t += stride)
      for (int p = 0; p < kMerlPhiD; p += stride) {
        const size_t cell = merl_cell(h, t, p);
        if (!merl_->measured[cell]) continue;
        const HalfDiff a = merl_cell_center(h, t, p);
        double wi[3], wo[3];
        directions_from_half_diff(a.theta_h, a.theta_d, a.phi_d, wi, wo);
        if (wi[2] <= 1e-4 || wo[2] <= 1e-4) continue;
        MeasuredSample s;
        s.wi = Vec3(static_cast<float>(wi[0]), static_cast<float>(wi[1]), static_cast<float>(wi[2]));
        s.wo = Vec3(static_cast<float>(wo[0]), static_cast<float>(wo[1]), static_cast<float>(wo[2]));
        s.value = merl_->cell(cell);
        out.push_back(s);
      }
  return out;
}

std::shared_ptr<const MeasuredData> load_measured_data(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(fs::path(path), ec);
  const std::string key = ec ? path : canonical.string();
  if (!fs::is_regular_file(key, ec))
    throw ParameterError("measured file '" + path + "' does not exist or is not a regular file");
  const auto mtime = fs::last_write_time(key, ec);
  const auto size = fs::file_size(key, ec);

  struct Entry {
    std::string key;
    fs::file_time_type mtime;
    uintmax_t size;
    std::shared_ptr<const MeasuredData> data;
  };
  static std::mutex mutex;
  static std::list<Entry> cache;  // most recently used first
  constexpr size_t kCapacity = 8;

  std::lock_guard<std::mutex> lock(mutex);
  for (auto it = cache.begin(); it != cache.end(); ++it) {
    if (it->key != key) continue;
    if (it->mtime == mtime && it->size == size) {
      cache.splice(cache.begin(), cache, it);
      return cache.front().data;
    }
    cache.erase(it);  // the file changed: read it again
    break;
  }
  // Reading under the lock keeps two threads from reading one file twice; loads are rare.
  std::shared_ptr<const MeasuredData> data = MeasuredData::read(key);
  cache.push_front({key, mtime, size, data});
  if (cache.size() > kCapacity) cache.pop_back();
  return data;
}

size_t measured_file_reads() { return g_reads.load(); }

}  // namespace bxdf
