// Image textures for material graphs, read through OpenImageIO and looked up exactly as
// Cycles 3.4's image node does (kernel/device/cpu/image.h, svm/image.h): closest, bilinear or
// cubic B-spline interpolation of the texel grid with no MIP filtering, texel centres at
// (i + 0.5)/width, Repeat/Extend/Clip, sRGB images interpolated as stored and converted to
// linear after the lookup (Cycles' compress_as_srgb), colour premultiplied by alpha in memory.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "bxdf/math.h"
#include "bxdf/spectrum.h"

namespace bxdf::render {

enum class TextureInterpolation { Closest, Linear, Cubic };
enum class TextureExtension { Repeat, Extend, Clip };
enum class TextureColorspace { SRGB, Linear, NonColor };
enum class TextureAlpha { Straight, Premultiplied, ChannelPacked, None };

struct TextureSettings {
  std::string path;
  bool missing = false;  // the translator found no image: the lookup is magenta, as Cycles
  TextureInterpolation interpolation = TextureInterpolation::Linear;
  TextureExtension extension = TextureExtension::Repeat;
  TextureColorspace colorspace = TextureColorspace::SRGB;
  TextureAlpha alpha = TextureAlpha::Straight;
};

struct RGBA {
  float r = 0.0f, g = 0.0f, b = 0.0f, a = 0.0f;
};

// Texels as Cycles keeps them: row 0 at the bottom (v = 0), colour associated with alpha
// unless the alpha mode says the channels are independent; 8-bit images as bytes (read as
// byte/255, a quarter of the memory of floats; one byte per texel for one-channel images, as
// Cycles' IMAGE_DATA_TYPE_BYTE), others as floats.
struct TexelGrid {
  int width = 0, height = 0;
  std::vector<RGBA> texels;                       // width * height, or empty for bytes
  std::vector<std::array<unsigned char, 4>> bytes;  // width * height, or empty
  std::vector<unsigned char> grey_bytes;  // one-channel 8-bit images (alpha 1), or empty
};

// How a grid keeps its texels (which of TexelGrid's arrays holds them).
enum class TexelStorage : uint8_t { Floats, Bytes, GreyBytes };

// Which texels a lookup at (u, v) reads, and their weights: Cycles' interpolation, extension
// and texel-centre convention. Found once for several images of one size and settings read
// at one point (textures on one UV map), then each image reads its own texels.
struct TexelFootprint {
  int n = 0;           // texels a side: 1 Closest, 2 Linear, 4 Cubic; 0 nothing (Clip, outside)
  int xs[4], ys[4];    // columns and rows, wrapped as the extension says (Clip: may be outside)
  float wx[4], wy[4];  // column and row weights
  bool inside = false;  // every texel in the grid (all but Clip at the edge): read unchecked,
  size_t rows[4];       // then row j starts at texel rows[j]
};
TexelFootprint texel_footprint(int width, int height, TextureInterpolation interpolation,
                               TextureExtension extension, float u, float v);

class Texture {
 public:
  // Reads the image (any format OpenImageIO reads; the scene's textures share an ImageCache).
  // Throws ParameterError naming the path when it cannot be read.
  Texture(const TextureSettings& settings, TexelGrid texels);

  // The image node's Color and Alpha at (u, v): Cycles' interpolation and extension, then
  // alpha unassociated when `unassociate` (the node's Alpha output is used), then sRGB → linear.
  RGBA lookup(float u, float v, bool unassociate) const;
  // The same, stored as a material graph's registers hold the node's outputs: the colour in
  // out[0], the alpha as (a, a, a) in out[1] (no RGBA passes through the stack per hit).
  void lookup(float u, float v, bool unassociate, Vec3* out) const;
  // The same in two steps, the first shared by images that shares_footprints() says agree.
  TexelFootprint footprint(float u, float v) const;
  void lookup(const TexelFootprint& footprint, bool unassociate, Vec3* out) const;
  bool shares_footprints(const Texture& other) const;
  // Starts loading the footprint's texel rows (a hint, for a batch of lookups to come).
  void prefetch(const TexelFootprint& footprint) const;

  const TextureSettings& settings() const { return settings_; }
  const TexelGrid& texels() const { return grid_; }

 private:
  RGBA interpolate(float u, float v) const;

  TextureSettings settings_;
  TexelGrid grid_;
};

// Cycles' interpolation of a texel grid alone (no colour handling), for the lookup and tests.
RGBA interpolate_texels(const TexelGrid& grid, TextureInterpolation interpolation,
                        TextureExtension extension, float u, float v);

// Loads textures once per (settings) and shares them between materials; thread-safe.
class TextureStore {
 public:
  TextureStore();
  ~TextureStore();
  std::shared_ptr<const Texture> get(const TextureSettings& settings);

 private:
  struct Cache;
  std::unique_ptr<Cache> cache_;
  std::mutex mutex_;
  std::map<std::string, std::shared_ptr<const Texture>> loaded_;
};

}  // namespace bxdf::render
