#include "bxdf/measured/measured_data.h"

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <future>
#include <list>
#include <mutex>

#include "bxdf/input_file.h"
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
  if (!in) throw ParameterError("measured file '" + printable(path) + "' cannot be opened");
  int32_t dims[3] = {0, 0, 0};
  in.read(reinterpret_cast<char*>(dims), sizeof(dims));
  if (in && dims[0] == kMerlThetaH && dims[1] == kMerlThetaD && dims[2] == kMerlPhiD)
    return MeasuredFormat::Merl;
  in.clear();
  in.seekg(0);
  std::string first;
  std::getline(in, first);
  if (!first.empty() && first[0] == '#') return MeasuredFormat::Cornell;
  throw ParameterError("measured file '" + printable(path) +
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
  check_input_file(path, std::max<std::uintmax_t>(kMaxMeasuredFileBytes, kMerlFileBytes),
                   "measured file");
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(fs::path(path), ec);
  const std::string key = ec ? path : canonical.string();
  const auto mtime = fs::last_write_time(key, ec);
  const auto size = fs::file_size(key, ec);

  using Loaded = std::shared_future<std::shared_ptr<const MeasuredData>>;
  struct Entry {
    std::string key;
    fs::file_time_type mtime;
    uintmax_t size;
    Loaded data;  // ready, or being read by another thread
  };
  static std::mutex mutex;
  static std::list<Entry> cache;  // most recently used first
  constexpr size_t kCapacity = 8;

  std::promise<std::shared_ptr<const MeasuredData>> promise;
  const Loaded mine = promise.get_future().share();
  Loaded loaded;
  {
    // The lock guards the list only; files are read outside it, so that one slow read does not
    // stall loads of other files. A thread asking for a file being read waits for that read.
    std::lock_guard<std::mutex> lock(mutex);
    for (auto it = cache.begin(); it != cache.end(); ++it) {
      if (it->key != key) continue;
      if (it->mtime == mtime && it->size == size) {
        cache.splice(cache.begin(), cache, it);
        loaded = cache.front().data;
      } else {
        cache.erase(it);  // the file changed: read it again
      }
      break;
    }
    if (!loaded.valid()) {
      cache.push_front({key, mtime, size, mine});
      if (cache.size() > kCapacity) cache.pop_back();
    }
  }
  if (loaded.valid()) return loaded.get();  // rethrows the reader's error, if it failed

  try {
    promise.set_value(MeasuredData::read(key));
  } catch (...) {
    promise.set_exception(std::current_exception());
    std::lock_guard<std::mutex> lock(mutex);  // a failed read is not cached
    cache.remove_if([&](const Entry& e) { return e.key == key && e.mtime == mtime && e.size == size; });
  }
  return mine.get();
}

size_t measured_file_reads() { return g_reads.load(); }

}  // namespace bxdf
