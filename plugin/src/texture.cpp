#include "bxdf/render/texture.h"

#include <OpenImageIO/imagecache.h>

#include <cmath>

#include "bxdf/params.h"

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
int wrap_clamp(int x, int width) { return x < 0 ? 0 : (x > width - 1 ? width - 1 : x); }

RGBA scaled(const RGBA& c, float s) { return {c.r * s, c.g * s, c.b * s, c.a * s}; }
RGBA sum(const RGBA& a, const RGBA& b) { return {a.r + b.r, a.g + b.g, a.b + b.b, a.a + b.a}; }

// Texel (x, y), or zero outside the grid (only Clip reaches outside).
RGBA read_clip(const TexelGrid& g, int x, int y) {
  if (x < 0 || x >= g.width || y < 0 || y >= g.height) return RGBA{};
  return g.texels[size_t(y) * size_t(g.width) + size_t(x)];
}

RGBA closest(const TexelGrid& g, TextureExtension extension, float x, float y) {
  int ix, iy;
  frac(x * static_cast<float>(g.width), &ix);
  frac(y * static_cast<float>(g.height), &iy);
  if (extension == TextureExtension::Repeat) {
    ix = wrap_periodic(ix, g.width);
    iy = wrap_periodic(iy, g.height);
  } else {
    if (extension == TextureExtension::Clip && (x < 0.0f || y < 0.0f || x > 1.0f || y > 1.0f))
      return RGBA{};
    ix = wrap_clamp(ix, g.width);
    iy = wrap_clamp(iy, g.height);
  }
  return read_clip(g, ix, iy);
}

// Texel indices of the footprint of a linear (n = 2) or cubic (n = 4) lookup along one axis:
// from ix − 1 (cubic) or ix (linear), each wrapped as the extension says. False when Clip
// leaves no texel inside.
bool footprint(int ix, int width, TextureExtension extension, int n, int* out) {
  const int first = n == 4 ? ix - 1 : ix;
  if (extension == TextureExtension::Clip && (first + n - 1 < 0 || first >= width)) return false;
  for (int k = 0; k < n; ++k) {
    const int i = first + k;
    out[k] = extension == TextureExtension::Repeat   ? wrap_periodic(i, width)
             : extension == TextureExtension::Extend ? wrap_clamp(i, width)
                                                     : i;
  }
  return true;
}

// Cycles' SET_CUBIC_SPLINE_WEIGHTS: the uniform cubic B-spline.
void cubic_weights(float t, float* w) {
  w[0] = (((-1.0f / 6.0f) * t + 0.5f) * t - 0.5f) * t + (1.0f / 6.0f);
  w[1] = ((0.5f * t - 1.0f) * t) * t + (2.0f / 3.0f);
  w[2] = ((-0.5f * t + 0.5f) * t + 0.5f) * t + (1.0f / 6.0f);
  w[3] = (1.0f / 6.0f) * t * t * t;
}

float srgb_to_linear(float c) {
  if (c < 0.04045f) return c < 0.0f ? 0.0f : c * (1.0f / 12.92f);
  return std::pow((c + 0.055f) * (1.0f / 1.055f), 2.4f);
}

}  // namespace

RGBA interpolate_texels(const TexelGrid& g, TextureInterpolation interpolation,
                        TextureExtension extension, float x, float y) {
  if (interpolation == TextureInterpolation::Closest) return closest(g, extension, x, y);
  // A −0.5 offset centres the samples on the texel centres (i + 0.5)/width.
  int ix, iy;
  const float tx = frac(x * static_cast<float>(g.width) - 0.5f, &ix);
  const float ty = frac(y * static_cast<float>(g.height) - 0.5f, &iy);
  const int n = interpolation == TextureInterpolation::Linear ? 2 : 4;
  int xs[4], ys[4];
  if (!footprint(ix, g.width, extension, n, xs) || !footprint(iy, g.height, extension, n, ys))
    return RGBA{};
  float wx[4], wy[4];
  if (n == 2) {
    wx[0] = 1.0f - tx;
    wx[1] = tx;
    wy[0] = 1.0f - ty;
    wy[1] = ty;
  } else {
    cubic_weights(tx, wx);
    cubic_weights(ty, wy);
  }
  RGBA out;
  for (int j = 0; j < n; ++j) {
    RGBA row;
    for (int i = 0; i < n; ++i) row = sum(row, scaled(read_clip(g, xs[i], ys[j]), wx[i]));
    out = sum(out, scaled(row, wy[j]));
  }
  return out;
}

Texture::Texture(const TextureSettings& settings, TexelGrid texels)
    : settings_(settings), grid_(std::move(texels)) {}

RGBA Texture::lookup(float u, float v, bool unassociate) const {
  if (settings_.missing) return {1.0f, 0.0f, 1.0f, 1.0f};  // Cycles' TEX_IMAGE_MISSING
  RGBA c = interpolate_texels(grid_, settings_.interpolation, settings_.extension, u, v);
  if (unassociate && c.a != 1.0f && c.a != 0.0f) {
    const float inv = 1.0f / c.a;
    c.r *= inv;
    c.g *= inv;
    c.b *= inv;
  }
  if (settings_.colorspace == TextureColorspace::SRGB) {
    c.r = srgb_to_linear(c.r);
    c.g = srgb_to_linear(c.g);
    c.b = srgb_to_linear(c.b);
  }
  return c;
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
// Cycles' layout: RGBA, bottom row first, colour associated with alpha as Cycles' loader does.
TexelGrid read_texels(OIIO::ImageCache& cache, const TextureSettings& s) {
  const OIIO::ustring file(s.path);
  OIIO::ImageSpec spec;
  if (!cache.get_imagespec(file, spec))
    throw ParameterError("texture '" + s.path + "': cannot be read (" + cache.geterror() + ")");
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    throw ParameterError("texture '" + s.path + "': the image is empty");
  const int w = spec.width, h = spec.height, nc = spec.nchannels;
  std::vector<float> pixels(size_t(w) * size_t(h) * size_t(nc));
  if (!cache.get_pixels(file, 0, 0, spec.x, spec.x + w, spec.y, spec.y + h, spec.z, spec.z + 1,
                        OIIO::TypeDesc::FLOAT, pixels.data()))
    throw ParameterError("texture '" + s.path + "': cannot be read (" + cache.geterror() + ")");
  // Files that store straight alpha (PNG, TGA...) come unassociated (the cache is set to keep
  // them so, and marks them oiio:UnassociatedAlpha) and are associated here on the stored
  // values, as Cycles' loader does, unless the channels are independent data (Non-Color,
  // Channel Packed) or alpha is ignored.
  const bool has_alpha = spec.alpha_channel >= 0 || nc == 4 || nc == 2;
  const bool associate = has_alpha && s.alpha != TextureAlpha::ChannelPacked &&
                         s.alpha != TextureAlpha::None &&
                         s.colorspace != TextureColorspace::NonColor &&
                         spec.get_int_attribute("oiio:UnassociatedAlpha", 0) != 0;
  TexelGrid g;
  g.width = w;
  g.height = h;
  g.texels.resize(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y) {
    const float* row = pixels.data() + size_t(h - 1 - y) * size_t(w) * size_t(nc);
    for (int x = 0; x < w; ++x) {
      const float* p = row + size_t(x) * size_t(nc);
      RGBA t;
      if (nc >= 3) {
        t = {p[0], p[1], p[2], nc >= 4 ? p[3] : 1.0f};
      } else {
        t = {p[0], p[0], p[0], nc == 2 ? p[1] : 1.0f};
      }
      if (s.alpha == TextureAlpha::None) t.a = 1.0f;
      if (associate) {
        t.r *= t.a;
        t.g *= t.a;
        t.b *= t.a;
      }
      g.texels[size_t(y) * size_t(w) + size_t(x)] = t;
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
