// The world: radiance arriving from infinitely far away along each direction, as Cycles' world
// shader gives it for the chains the add-on translates (Background colour × Strength, an
// Environment Texture through Texture Coordinate and Mapping, mixed with a colour):
//
//     L(ω) = constant + weight · image(normalize(M·ω + offset))
//
// with `image` an equirectangular (latitude-longitude) picture looked up as Cycles'
// Environment Texture node does (K/svm/image.h, K/camera/projection.h). A world with an image
// is importance-sampled much as Cycles does (K/light/background.h, scene/light.cpp): a map of
// res_x × res_y cells, a piecewise-constant 2D distribution over it with rows weighted by
// sin θ, combined with BSDF sampling by MIS. Two things differ, neither changing the image's
// expectation. A cell's value is the largest L at nine points of it rather than Cycles' centre
// value: the density then never falls far below L/∫L, which keeps a small bright sun from
// turning into fireflies. And the map holds only what lies above the world's mean radiance
// (MIS compensation, Karlík et al. 2019): BSDF sampling alone finds the smooth rest, which
// under MIS would only add variance (a diffuse sphere in a sky of 0.6 + 0.4 z: 27% less MSE
// at 64 spp; under an HDRI 5-8% less). A constant world is not light-sampled at all (Cycles
// turns background MIS off for a world that does not vary, and nothing lies above its mean),
// so BSDF sampling alone finds it, which is noise-free for a diffuse surface in a furnace.
#pragma once

#include <string>
#include <vector>

#include "bxdf/math.h"
#include "bxdf/spectrum.h"
#include <memory>
#include <string>

#include "bxdf/render/texture.h"  // the one image lookup (interpolate_texels) and its settings

namespace bxdf::render {

// A latitude-longitude image in linear RGB, row 0 at the bottom (v = 0, the −Z pole), as Cycles
// stores images.
struct EquirectImage {
  int width = 0, height = 0;
  std::vector<float> rgb;
};

// Reads an image file through OpenImageIO (EXR/HDR linear; 8-bit formats decoded from sRGB).
// Throws std::runtime_error naming the path on failure. A file read again unchanged (the same
// device, inode, size, modification and change times) is copied from a process-wide cache of
// the last kEquirectCacheEntries images instead: a render in Blender reads its world's HDRI at
// every render (a 1024 × 512 EXR: ~20 ms of a 64-sample preview's ~170 ms).
constexpr int kEquirectCacheEntries = 4;
EquirectImage load_equirect_image(const std::string& path);

struct EnvironmentSettings {
  RGB constant;                  // W/(m² sr)
  RGB weight;                    // multiplies the image
  EquirectImage image;           // empty: a constant world
  float matrix[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};  // 3×4 rows: texture vector of ω
  TextureInterpolation interpolation = TextureInterpolation::Linear;
  bool importance_sample = true;  // Blender's world sampling method None turns it off
  int map_resolution = 0;         // Manual: R gives R × R/2 cells; 0 = Auto (the image's size)
};

class Environment {
 public:
  Environment() = default;
  // Throws ParameterError naming a negative or non-finite colour, an image whose size does not
  // match its pixels, or a bad map resolution.
  explicit Environment(EnvironmentSettings settings);

  RGB eval(const Vec3& dir) const;
  bool is_black() const { return black_; }
  // True when the world is light-sampled (it varies and sampling is on).
  bool importance_sampled() const { return !distribution_.empty(); }
  int map_width() const { return map_w_; }
  int map_height() const { return map_h_; }

  // A direction with density *pdf in solid angle (0 = no sample). Only when importance_sampled.
  Vec3 sample(Point2 u, float* pdf) const;
  float pdf(const Vec3& dir) const;
  // Power estimate for the light sampler: π r² · ∫ avg L dω (pbrt's convention).
  float power(float scene_radius) const { return kPi * scene_radius * scene_radius * integral_; }

 private:
  RGB lookup(float u, float v) const;
  void build_distribution();

  EnvironmentSettings s_;  // its image's pixels move into texels_
  TexelGrid texels_;
  bool black_ = true;
  bool has_image_ = false;
  float integral_ = 0.0f;  // ∫ average(L) dω over the sphere
  int map_w_ = 0, map_h_ = 0;
  // Cycles' layout: per row, res_x + 1 entries of (function value, CDF); the row's last entry
  // holds the row integral as its value. The marginal has res_y + 1 entries likewise.
  std::vector<float> distribution_;  // conditional values and CDFs, (res_x + 1) × res_y × 2
  std::vector<float> marginal_;      // (res_y + 1) × 2
};

// The world of `settings` with the image file at `image_path`, built once and shared: a scene
// whose world is the same file (path and stamp, as load_equirect_image) with the same settings
// takes the Environment an earlier scene built, from a process-wide cache of the last
// kEquirectCacheEntries. Building it (the texels, the light map's grid of lookups) was ~8 ms of
// every render of a 1024 × 512 HDRI, with its 14 MB written fresh each time. `settings.image`
// is ignored (the file's pixels are used). Throws as load_equirect_image and Environment.
std::shared_ptr<const Environment> shared_environment(const std::string& image_path,
                                                      const EnvironmentSettings& settings);

// Cycles' equirectangular mapping: u = (π − atan2(y, x)) / 2π, v = 1 − θ/π (v = 1 at +Z).
Point2 direction_to_equirect(const Vec3& dir);
Vec3 equirect_to_direction(float u, float v);
// Cycles' mirror-ball mapping (direction_to_mirrorball): the ball seen from −Y.
Point2 direction_to_mirrorball(const Vec3& dir);

}  // namespace bxdf::render
