// Images read at one point, stored interleaved (TextureGroup): every image's outputs are the
// very floats its own lookup gives, for each storage, interpolation, extension and colour space.
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <vector>

#include "bxdf/render/texture.h"
#include "bxdf/render/texture_group.h"

using namespace bxdf;
using namespace bxdf::render;

namespace {

enum class Storage { Float, Bytes, GreyBytes };

std::shared_ptr<const Texture> make_texture(Storage storage, int width, int height,
                                            TextureSettings settings, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  TexelGrid g;
  g.width = width;
  g.height = height;
  const size_t n = size_t(width) * size_t(height);
  for (size_t i = 0; i < n; ++i) {
    switch (storage) {
      case Storage::Float: {
        // Alpha below 1 on some texels, so that unassociating has work to do.
        const float a = i % 3 == 0 ? 0.5f : 1.0f;
        g.texels.push_back({byte(rng) / 97.0f * a, byte(rng) / 301.0f * a, byte(rng) / 255.0f * a, a});
        break;
      }
      case Storage::Bytes:
        g.bytes.push_back({static_cast<unsigned char>(byte(rng)), static_cast<unsigned char>(byte(rng)),
                           static_cast<unsigned char>(byte(rng)),
                           static_cast<unsigned char>(i % 5 == 0 ? 128 : 255)});
        break;
      case Storage::GreyBytes: g.grey_bytes.push_back(static_cast<unsigned char>(byte(rng))); break;
    }
  }
  return std::make_shared<Texture>(settings, std::move(g));
}

}  // namespace

TEST(TextureGroup, EveryImageReadsAsItsOwnLookup) {
  for (const auto interpolation :
       {TextureInterpolation::Closest, TextureInterpolation::Linear, TextureInterpolation::Cubic}) {
    for (const auto extension :
         {TextureExtension::Repeat, TextureExtension::Extend, TextureExtension::Clip}) {
      TextureSettings s;
      s.interpolation = interpolation;
      s.extension = extension;
      TextureSettings srgb = s, non_color = s, linear = s;
      srgb.colorspace = TextureColorspace::SRGB;
      non_color.colorspace = TextureColorspace::NonColor;
      linear.colorspace = TextureColorspace::Linear;
      // Storages in an order that is not the record's (bytes, float, grey, bytes).
      const std::vector<std::shared_ptr<const Texture>> owned = {
          make_texture(Storage::Bytes, 7, 5, srgb, 1), make_texture(Storage::Float, 7, 5, linear, 2),
          make_texture(Storage::GreyBytes, 7, 5, non_color, 3),
          make_texture(Storage::Bytes, 7, 5, non_color, 4)};
      std::vector<const Texture*> images;
      for (const auto& t : owned) images.push_back(t.get());
      const auto group = TextureGroup::make(images);
      ASSERT_TRUE(group);
      ASSERT_EQ(group->size(), 4u);
      const uint8_t unassociate[4] = {1, 1, 0, 0};
      const int outputs[4] = {0, 2, 4, 6};
      std::mt19937 rng(7);
      std::uniform_real_distribution<float> coordinate(-1.3f, 2.3f);
      for (int trial = 0; trial < 400; ++trial) {
        // Texel centres and edges too, not only random points.
        const float u = trial < 35 ? float(trial % 7) / 7.0f + (trial % 2 ? 0.5f / 7.0f : 0.0f)
                                   : coordinate(rng);
        const float v = trial < 35 ? float(trial % 5) / 5.0f : coordinate(rng);
        const TexelFootprint f = images[0]->footprint(u, v);
        Vec3 grouped[8], own[8];
        group->lookup(f, unassociate, outputs, grouped);
        for (int k = 0; k < 4; ++k) {
          images[size_t(k)]->lookup(f, unassociate[k] != 0, own + outputs[k]);
          for (int o = 0; o < 2; ++o) {
            const Vec3 a = grouped[outputs[k] + o], b = own[outputs[k] + o];
            ASSERT_TRUE(a.x == b.x && a.y == b.y && a.z == b.z)
                << "image " << k << " output " << o << " at (" << u << ", " << v
                << "), interpolation " << int(interpolation) << ", extension " << int(extension);
          }
        }
      }
    }
  }
}

TEST(TextureGroup, IsNotMadeForOneImageOrPastItsMemoryBound) {
  TextureSettings s;
  const auto one = make_texture(Storage::GreyBytes, 4, 4, s, 1);
  EXPECT_FALSE(TextureGroup::make({one.get()}));
  // Two 1500² RGBA float images: 72 MB interleaved, past the 64 MB bound.
  TexelGrid big;
  big.width = big.height = 1500;
  big.texels.resize(size_t(1500) * 1500);
  const auto a = std::make_shared<Texture>(s, big);
  const auto b = std::make_shared<Texture>(s, std::move(big));
  EXPECT_FALSE(TextureGroup::make({a.get(), b.get()}));
  // Two small ones: a record per texel of 4 + 1 bytes, rounded up to 8.
  const auto c = make_texture(Storage::Bytes, 4, 4, s, 2);
  const auto group = TextureGroup::make({c.get(), one.get()});
  ASSERT_TRUE(group);
  EXPECT_EQ(group->bytes(), size_t(16) * 8);
}
