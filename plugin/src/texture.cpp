#include "bxdf/render/texture.h"

#include <OpenImageIO/imagecache.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "bxdf/params.h"
#include "texel_reads.h"

namespace bxdf::render {

namespace {


// Cycles' frac(): the integer part towards −∞ (float_to_int truncates, hence the correction).
float frac(float x, int* ix) {
  const int i = static_cast<int>(x) - (x < 0.0f ? 1 : 0);
  *ix = i;
  return x - static_cast<float>(i);
}
int wrap_periodic(int x, int width) {
  x %= width;
  return x < 0 ? x + width : x;
}
// The same, without a division in the common case of an index already inside the grid.
int wrap_repeat(int x, int width) {
  return static_cast<unsigned>(x) < static_cast<unsigned>(width) ? x : wrap_periodic(x, width);
}
int wrap_clamp(int x, int width) { return x < 0 ? 0 : (x > width - 1 ? width - 1 : x); }


// Texel indices of the footprint of a linear (n = 2) or cubic (n = 4) lookup along one axis:
// from ix − 1 (cubic) or ix (linear), each wrapped as the extension says. False when Clip
// leaves no texel inside.
bool axis_footprint(int ix, int width, TextureExtension extension, int n, int* out) {
  const int first = n == 4 ? ix - 1 : ix;
  switch (extension) {
    case TextureExtension::Repeat: {
      int i = wrap_repeat(first, width);
      for (int k = 0; k < n; ++k, i = i + 1 == width ? 0 : i + 1) out[k] = i;
      return true;
    }
    case TextureExtension::Extend:
      for (int k = 0; k < n; ++k) out[k] = wrap_clamp(first + k, width);
      return true;
    case TextureExtension::Clip:
      if (first + n - 1 < 0 || first >= width) return false;
      for (int k = 0; k < n; ++k) out[k] = first + k;
      return true;
  }
  return false;
}

// Cycles' SET_CUBIC_SPLINE_WEIGHTS: the uniform cubic B-spline.
void cubic_weights(float t, float* w) {
  w[0] = (((-1.0f / 6.0f) * t + 0.5f) * t - 0.5f) * t + (1.0f / 6.0f);
  w[1] = ((0.5f * t - 1.0f) * t) * t + (2.0f / 3.0f);
  w[2] = ((-0.5f * t + 0.5f) * t + 0.5f) * t + (1.0f / 6.0f);
  w[3] = (1.0f / 6.0f) * t * t * t;
}

float bits_to_float(int32_t i) {
  float f;
  std::memcpy(&f, &i, sizeof f);
  return f;
}

// Cycles' CPU kernels convert with fastpow24 (util/color.h, the SSE path every x86-64 build
// takes, on the three channels at once), not powf: x^(4/5) guessed from the float's bits,
// three Newton steps on x⁵ = c⁴, then x³ = c^2.4; within 1e-6 of powf and several times
// faster. The guess is a float of magnitude ~1e9, an integer already, so the conversion back
// (Cycles rounds, vector conversion truncates) is exact either way.
Float4 fastpow24(Float4 arg) {
  Float4 x = arg * splat4(bits_to_float(0x4F55A7FB));
  x = __builtin_convertvector((Int4)x, Float4);  // a vector cast reinterprets the bits
  x *= splat4(bits_to_float(0x3F4CCCCD));
  x = (Float4)__builtin_convertvector(x, Int4);
  const Float4 arg2 = arg * arg, arg4 = arg2 * arg2;
  for (int i = 0; i < 3; ++i) {
    const Float4 x2 = x * x, x4 = x2 * x2;
    x = (splat4(4.0f) * x + arg4 / x4) * splat4(1.0f / 5.0f);
  }
  return x * (x * x);
}

// Cycles' color_srgb_to_linear on each channel (the fourth, alpha, is left as it is).
Float4 srgb_to_linear(Float4 c) {
  const Float4 low = c * splat4(1.0f / 12.92f);
  const Float4 low_clamped = low > splat4(0.0f) ? low : splat4(0.0f);
  const Float4 high = fastpow24((c + splat4(0.055f)) * splat4(1.0f / 1.055f));
  Float4 out = c < splat4(0.04045f) ? low_clamped : high;
  out[3] = c[3];
  return out;
}

// The same conversion tabulated at 4097 points of [0, 1] and interpolated linearly: within
// 3e-8 of the function (its second derivative stays below 3.4), well inside fastpow24's own
// 1e-6 from powf, and several times cheaper than three dependent divisions. 8-bit images, the
// sRGB ones Cycles converts after the lookup, only give values in [0, 1]; anything outside
// takes the function.
class SrgbTable {
 public:
  static constexpr int kIntervals = 4096;
  SrgbTable() {
    for (int i = 0; i <= kIntervals; ++i)
      value_[size_t(i)] = srgb_to_linear(splat4(float(i) / float(kIntervals)))[0];
  }
  Float4 convert(Float4 c) const {
    // The range test and the table positions for the three channels at once (the same
    // truncations and floats as channel by channel); only the table reads are per channel.
    const Int4 in_range = (c >= splat4(0.0f)) & (c <= splat4(1.0f));
    if (!(in_range[0] & in_range[1] & in_range[2])) return srgb_to_linear(c);
    const Float4 x = c * splat4(float(kIntervals));
    Int4 i = __builtin_convertvector(x, Int4);
    i = i < kIntervals - 1 ? i : Int4{} + (kIntervals - 1);
    const Float4 t = x - __builtin_convertvector(i, Float4);
    for (int k = 0; k < 3; ++k) {
      const float* v = &value_[size_t(i[k])];
      c[k] = v[0] + t[k] * (v[1] - v[0]);
    }
    return c;
  }

 private:
  std::array<float, kIntervals + 1> value_;
};

// Built at start-up rather than on first use, so that no lookup pays for a guard.
const SrgbTable srgb_table_instance;
const SrgbTable& srgb_table() { return srgb_table_instance; }


Float4 gather_grid(const TexelGrid& g, const TexelFootprint& f) {
  const TexelArray a = texel_array(g);
  return gather_stored(g.width, g.height, a.storage, a.base, a.size, f);
}

}  // namespace

TexelFootprint texel_footprint(int width, int height, TextureInterpolation interpolation,
                               TextureExtension extension, float x, float y) {
  TexelFootprint f;
  if (width <= 0 || height <= 0) return f;  // no texels (a missing image): nothing to read
  int ix, iy;
  if (interpolation == TextureInterpolation::Closest) {
    frac(x * static_cast<float>(width), &ix);
    frac(y * static_cast<float>(height), &iy);
    if (extension == TextureExtension::Repeat) {
      ix = wrap_repeat(ix, width);
      iy = wrap_repeat(iy, height);
    } else {
      if (extension == TextureExtension::Clip && (x < 0.0f || y < 0.0f || x > 1.0f || y > 1.0f))
        return f;
      ix = wrap_clamp(ix, width);
      iy = wrap_clamp(iy, height);
    }
    f.n = 1;
    f.xs[0] = ix;
    f.ys[0] = iy;
    f.inside = true;  // wrapped or clamped into the grid
    f.rows[0] = size_t(iy) * size_t(width);
    return f;
  }
  // A −0.5 offset centres the samples on the texel centres (i + 0.5)/width.
  const float tx = frac(x * static_cast<float>(width) - 0.5f, &ix);
  const float ty = frac(y * static_cast<float>(height) - 0.5f, &iy);
  const int n = interpolation == TextureInterpolation::Linear ? 2 : 4;
  if (n == 2 && extension == TextureExtension::Repeat) {
    // The common case in one pass: both columns and rows wrapped, always inside the grid.
    const int x0 = wrap_repeat(ix, width), y0 = wrap_repeat(iy, height);
    const int x1 = x0 + 1 == width ? 0 : x0 + 1, y1 = y0 + 1 == height ? 0 : y0 + 1;
    f.n = 2;
    f.inside = true;
    f.xs[0] = x0;
    f.xs[1] = x1;
    f.ys[0] = y0;
    f.ys[1] = y1;
    f.rows[0] = size_t(y0) * size_t(width);
    f.rows[1] = size_t(y1) * size_t(width);
    f.wx[0] = 1.0f - tx;
    f.wx[1] = tx;
    f.wy[0] = 1.0f - ty;
    f.wy[1] = ty;
    return f;
  }
  if (!axis_footprint(ix, width, extension, n, f.xs) ||
      !axis_footprint(iy, height, extension, n, f.ys))
    return f;
  f.n = n;
  f.inside = true;
  for (int k = 0; k < n; ++k) {
    f.inside = f.inside && f.xs[k] >= 0 && f.xs[k] < width && f.ys[k] >= 0 && f.ys[k] < height;
    f.rows[k] = size_t(f.ys[k] < 0 ? 0 : f.ys[k]) * size_t(width);
  }
  if (n == 2) {
    f.wx[0] = 1.0f - tx;
    f.wx[1] = tx;
    f.wy[0] = 1.0f - ty;
    f.wy[1] = ty;
  } else {
    cubic_weights(tx, f.wx);
    cubic_weights(ty, f.wy);
  }
  return f;
}

RGBA interpolate_texels(const TexelGrid& g, TextureInterpolation interpolation,
                        TextureExtension extension, float x, float y) {
  return to_rgba(gather_grid(g, texel_footprint(g.width, g.height, interpolation, extension, x, y)));
}

Texture::Texture(const TextureSettings& settings, TexelGrid texels)
    : settings_(settings), grid_(std::move(texels)) {}

namespace {

// The image node's Color and Alpha from the texels the footprint names.
Float4 image_node_lookup(const TextureSettings& s, const TexelGrid& grid,
                         const TexelFootprint& footprint, bool unassociate) {
  if (s.missing) return Float4{1.0f, 0.0f, 1.0f, 1.0f};  // Cycles' TEX_IMAGE_MISSING
  return image_node_convert(s, gather_grid(grid, footprint), unassociate);
}

}  // namespace

Float4 image_node_convert(const TextureSettings& s, Float4 c, bool unassociate) {
  const float alpha = c[3];
  if (unassociate && alpha != 1.0f && alpha != 0.0f) {
    c *= splat4(1.0f / alpha);
    c[3] = alpha;
  }
  if (s.colorspace == TextureColorspace::SRGB) c = srgb_table().convert(c);
  return c;
}

void Texture::prefetch(const TexelFootprint& f) const {
  if (!f.inside) return;
  const TexelArray a = texel_array(grid_);
  for (int j = 0; j < f.n; ++j) __builtin_prefetch(a.base + (f.rows[j] + size_t(f.xs[0])) * a.size);
}

TexelFootprint Texture::footprint(float u, float v) const {
  return texel_footprint(grid_.width, grid_.height, settings_.interpolation, settings_.extension,
                         u, v);
}

bool Texture::shares_footprints(const Texture& other) const {
  return !settings_.missing && !other.settings_.missing && grid_.width == other.grid_.width &&
         grid_.height == other.grid_.height &&
         settings_.interpolation == other.settings_.interpolation &&
         settings_.extension == other.settings_.extension;
}

RGBA Texture::lookup(float u, float v, bool unassociate) const {
  return to_rgba(image_node_lookup(settings_, grid_, footprint(u, v), unassociate));
}

void Texture::lookup(float u, float v, bool unassociate, Vec3* out) const {
  store_node_outputs(image_node_lookup(settings_, grid_, footprint(u, v), unassociate), out);
}

void Texture::lookup(const TexelFootprint& f, bool unassociate, Vec3* out) const {
  store_node_outputs(image_node_lookup(settings_, grid_, f, unassociate), out);
}

struct TextureStore::Cache {
  OIIO::ImageCache* cache = OIIO::ImageCache::create(/*shared=*/false);
  Cache() { cache->attribute("unassociatedalpha", 1); }
  ~Cache() { OIIO::ImageCache::destroy(cache); }
};

TextureStore::TextureStore() : cache_(std::make_unique<Cache>()) {}
TextureStore::~TextureStore() = default;

namespace {

// Reads every texel through the ImageCache (which opens, tiles and caches the file) into
// Cycles' layout: RGBA, bottom row first, colour associated with alpha as Cycles' loader does
// (in the stored values: for bytes, c·a/255 truncated, Cycles' util_image_multiply_native).
TexelGrid read_texels(OIIO::ImageCache& cache, const TextureSettings& s) {
  const OIIO::ustring file(s.path);
  OIIO::ImageSpec spec;
  if (!cache.get_imagespec(file, spec))
    throw ParameterError("texture '" + s.path + "': cannot be read (" + cache.geterror() + ")");
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    throw ParameterError("texture '" + s.path + "': the image is empty");
  const int w = spec.width, h = spec.height, nc = spec.nchannels;
  const bool bytes = spec.format == OIIO::TypeDesc::UINT8;
  const OIIO::TypeDesc type = bytes ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
  std::vector<unsigned char> raw(size_t(w) * size_t(h) * size_t(nc) * type.size());
  if (!cache.get_pixels(file, 0, 0, spec.x, spec.x + w, spec.y, spec.y + h, spec.z, spec.z + 1,
                        type, raw.data()))
    throw ParameterError("texture '" + s.path + "': cannot be read (" + cache.geterror() + ")");
  // Files that store straight alpha (PNG, TGA...) come unassociated (the cache is set to keep
  // them so, and marks them oiio:UnassociatedAlpha) and are associated here, as Cycles' loader
  // does, unless the channels are independent data (Non-Color, Channel Packed) or alpha is
  // ignored.
  const bool has_alpha = nc == 4 || nc == 2;
  const bool associate = has_alpha && s.alpha != TextureAlpha::ChannelPacked &&
                         s.alpha != TextureAlpha::None &&
                         s.colorspace != TextureColorspace::NonColor &&
                         spec.get_int_attribute("oiio:UnassociatedAlpha", 0) != 0;
  TexelGrid g;
  g.width = w;
  g.height = h;
  const size_t count = size_t(w) * size_t(h);
  const bool grey = bytes && nc == 1;
  if (grey) g.grey_bytes.assign(raw.begin(), raw.end());  // flipped below
  else if (bytes) g.bytes.resize(count);
  else g.texels.resize(count);
  for (int y = 0; y < h; ++y) {
    const size_t src_row = size_t(h - 1 - y) * size_t(w) * size_t(nc);
    for (int x = 0; x < w; ++x) {
      const size_t src = src_row + size_t(x) * size_t(nc), dst = size_t(y) * size_t(w) + size_t(x);
      if (grey) {
        g.grey_bytes[dst] = raw[src];
      } else if (bytes) {
        const unsigned char* p = raw.data() + src;
        std::array<unsigned char, 4> t = nc >= 3 ? std::array<unsigned char, 4>{p[0], p[1], p[2], nc >= 4 ? p[3] : (unsigned char)255}
                                                 : std::array<unsigned char, 4>{p[0], p[0], p[0], nc == 2 ? p[1] : (unsigned char)255};
        if (s.alpha == TextureAlpha::None) t[3] = 255;
        if (associate && t[3] != 255)
          for (int c = 0; c < 3; ++c) t[size_t(c)] = static_cast<unsigned char>((unsigned(t[size_t(c)]) * t[3]) / 255u);
        g.bytes[dst] = t;
      } else {
        const float* p = reinterpret_cast<const float*>(raw.data()) + src;
        RGBA t = nc >= 3 ? RGBA{p[0], p[1], p[2], nc >= 4 ? p[3] : 1.0f}
                         : RGBA{p[0], p[0], p[0], nc == 2 ? p[1] : 1.0f};
        if (s.alpha == TextureAlpha::None) t.a = 1.0f;
        if (associate) {
          t.r *= t.a;
          t.g *= t.a;
          t.b *= t.a;
        }
        g.texels[dst] = t;
      }
    }
  }
  return g;
}

std::string cache_key(const TextureSettings& s) {
  return s.path + "|" + std::to_string(int(s.interpolation)) + std::to_string(int(s.extension)) +
         std::to_string(int(s.colorspace)) + std::to_string(int(s.alpha)) + (s.missing ? "m" : "");
}

}  // namespace

std::shared_ptr<const Texture> TextureStore::get(const TextureSettings& settings) {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::string key = cache_key(settings);
  auto found = loaded_.find(key);
  if (found != loaded_.end()) return found->second;
  TexelGrid texels;
  if (!settings.missing) texels = read_texels(*cache_->cache, settings);
  auto texture = std::make_shared<const Texture>(settings, std::move(texels));
  loaded_[key] = texture;
  return texture;
}

}  // namespace bxdf::render
