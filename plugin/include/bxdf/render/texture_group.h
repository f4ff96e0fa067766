// Images a material reads at one point, of one size and settings (a set of textures on one UV
// map: colour, roughness, normal map, mix factor), stored interleaved: texel i of every image
// side by side. A lookup's footprint then reads the same few cache lines for all of them;
// stored apart, each image's texels lie in lines of their own (one per image and row), and the
// scattered hits of a path miss the cache on every one.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "bxdf/math.h"
#include "bxdf/render/texture.h"

namespace bxdf::render {

class TextureGroup {
 public:
  // The copy takes the images' memory once more, so it is made only up to this size (a set of
  // four 2K images fits; larger sets are read apart).
  static constexpr size_t kMaxBytes = size_t(64) << 20;

  // The interleaved copy of `images` (at least two, all shares_footprints() with the first);
  // null above kMaxBytes.
  static std::shared_ptr<const TextureGroup> make(const std::vector<const Texture*>& images);

  size_t size() const { return members_.size(); }
  size_t bytes() const { return data_.size(); }
  // Every image's node outputs at `footprint`, the same floats as Texture::lookup(footprint,
  // unassociate[k], registers + outputs[k]) gives for image k.
  void lookup(const TexelFootprint& footprint, const uint8_t* unassociate, const int* outputs,
              Vec3* registers) const;
  // Starts loading the footprint's records (a hint, for a batch of lookups to come).
  void prefetch(const TexelFootprint& footprint) const;

 private:
  struct Member {
    TexelStorage storage;
    size_t offset;  // of the image's texel within a record
    TextureSettings settings;
  };
  void lookup_bilinear_inside(const TexelFootprint& footprint, const uint8_t* unassociate,
                              const int* outputs, Vec3* registers) const;
  int width_ = 0, height_ = 0;
  size_t stride_ = 0;  // bytes per record (one texel of every image)
  std::vector<Member> members_;
  std::vector<unsigned char> data_;
};

}  // namespace bxdf::render
