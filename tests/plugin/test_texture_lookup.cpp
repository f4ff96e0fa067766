// Texture lookups against Cycles 3.4's formulas written independently: a lookup is the sum over
// every texel of the texel times the interpolation kernel at its distance from the sample point
// (texel centres at (i + 0.5)/width), with the extension deciding which texel stands in for an
// index outside the grid. Checked at texel centres, edges and outside [0, 1] for each
// interpolation and extension; and image files read through OpenImageIO (8-bit sRGB converted
// after the lookup, associated alpha), missing images magenta.
#include <gtest/gtest.h>

#include "../scratch_folder.h"

#include <cmath>
#include <cstdio>
#include <array>
#include <filesystem>
#include <fstream>

#include <OpenImageIO/imageio.h>

#include "bxdf/params.h"
#include "bxdf/render/texture.h"

using namespace bxdf;
using namespace bxdf::render;

namespace {

TexelGrid test_grid() {
  TexelGrid g;
  g.width = 4;
  g.height = 3;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x)
      g.texels.push_back({0.1f * float(x + 1), 0.05f * float(y + 1), float(x * 3 + y) / 11.0f,
                          1.0f - 0.2f * float(x)});
  return g;
}

float kernel(TextureInterpolation interpolation, float d) {
  d = std::fabs(d);
  if (interpolation == TextureInterpolation::Linear) return d < 1.0f ? 1.0f - d : 0.0f;
  // Uniform cubic B-spline.
  if (d < 1.0f) return (4.0f - 6.0f * d * d + 3.0f * d * d * d) / 6.0f;
  if (d < 2.0f) return (2.0f - d) * (2.0f - d) * (2.0f - d) / 6.0f;
  return 0.0f;
}

// Which texel index i (any integer) reads as, or −1 for "zero" (Clip outside).
int extend_index(TextureExtension e, int i, int n) {
  if (e == TextureExtension::Repeat) return ((i % n) + n) % n;
  if (e == TextureExtension::Extend) return std::min(std::max(i, 0), n - 1);
  return (i >= 0 && i < n) ? i : -1;
}

RGBA reference(const TexelGrid& g, TextureInterpolation interpolation, TextureExtension e, float u,
               float v) {
  RGBA out;
  const float x = u * float(g.width) - 0.5f, y = v * float(g.height) - 0.5f;
  if (interpolation == TextureInterpolation::Closest) {
    if (e == TextureExtension::Clip && (u < 0 || v < 0 || u > 1 || v > 1)) return out;
    const int ix = extend_index(e == TextureExtension::Clip ? TextureExtension::Extend : e,
                                int(std::floor(u * float(g.width))), g.width);
    const int iy = extend_index(e == TextureExtension::Clip ? TextureExtension::Extend : e,
                                int(std::floor(v * float(g.height))), g.height);
    return g.texels[size_t(iy * g.width + ix)];
  }
  for (int j = int(std::floor(y)) - 3; j <= int(std::floor(y)) + 3; ++j)
    for (int i = int(std::floor(x)) - 3; i <= int(std::floor(x)) + 3; ++i) {
      const float w = kernel(interpolation, x - float(i)) * kernel(interpolation, y - float(j));
      const int ti = extend_index(e, i, g.width), tj = extend_index(e, j, g.height);
      if (w == 0.0f || ti < 0 || tj < 0) continue;
      const RGBA& t = g.texels[size_t(tj * g.width + ti)];
      out.r += w * t.r;
      out.g += w * t.g;
      out.b += w * t.b;
      out.a += w * t.a;
    }
  return out;
}

void expect_rgba(const RGBA& got, const RGBA& want, float tol) {
  EXPECT_NEAR(got.r, want.r, tol);
  EXPECT_NEAR(got.g, want.g, tol);
  EXPECT_NEAR(got.b, want.b, tol);
  EXPECT_NEAR(got.a, want.a, tol);
}

}  // namespace

TEST(TextureLookup, EveryInterpolationAndExtensionAtCentresEdgesAndOutside) {
  const TexelGrid g = test_grid();
  std::vector<float> us, vs;
  for (int i = 0; i < g.width; ++i) us.push_back((float(i) + 0.5f) / float(g.width));   // centres
  for (int i = 0; i <= g.width; ++i) us.push_back(float(i) / float(g.width));           // edges
  for (float u : {-0.3f, -0.01f, 0.37f, 1.01f, 1.6f, 2.1f}) us.push_back(u);            // inside/out
  for (int j = 0; j < g.height; ++j) vs.push_back((float(j) + 0.5f) / float(g.height));
  for (int j = 0; j <= g.height; ++j) vs.push_back(float(j) / float(g.height));
  for (float v : {-0.2f, 0.61f, 1.3f}) vs.push_back(v);
  for (auto interpolation : {TextureInterpolation::Closest, TextureInterpolation::Linear,
                             TextureInterpolation::Cubic})
    for (auto extension : {TextureExtension::Repeat, TextureExtension::Extend, TextureExtension::Clip})
      for (float u : us)
        for (float v : vs) {
          // Closest at an exact texel edge depends on rounding; the reference floors the same way.
          SCOPED_TRACE(::testing::Message() << "interp " << int(interpolation) << " ext "
                                            << int(extension) << " u " << u << " v " << v);
          expect_rgba(interpolate_texels(g, interpolation, extension, u, v),
                      reference(g, interpolation, extension, u, v), 2e-6f);
        }
}

TEST(TextureLookup, TexelCentresAreExactForClosestAndLinear) {
  const TexelGrid g = test_grid();
  for (int j = 0; j < g.height; ++j)
    for (int i = 0; i < g.width; ++i) {
      const float u = (float(i) + 0.5f) / float(g.width), v = (float(j) + 0.5f) / float(g.height);
      const RGBA& t = g.texels[size_t(j * g.width + i)];
      for (auto interpolation : {TextureInterpolation::Closest, TextureInterpolation::Linear})
        expect_rgba(interpolate_texels(g, interpolation, TextureExtension::Repeat, u, v), t, 1e-6f);
    }
  // Linear, Clip, at the image's corner: a quarter of the corner texel (the rest is outside).
  const RGBA corner = interpolate_texels(g, TextureInterpolation::Linear, TextureExtension::Clip, 0, 0);
  EXPECT_NEAR(corner.r, 0.25f * g.texels[0].r, 1e-6f);
  // Repeat at u = 0: half the first and half the last column.
  const RGBA seam = interpolate_texels(g, TextureInterpolation::Linear, TextureExtension::Repeat, 0.0f,
                                       0.5f / 3.0f);
  EXPECT_NEAR(seam.r, 0.5f * (g.texels[0].r + g.texels[3].r), 1e-6f);
}

namespace {

// An 8-bit RGBA PNG (straight alpha, row 0 at the top), written with OpenImageIO.
std::string write_png(const std::string& name, int w, int h, const std::vector<unsigned char>& rgba) {
  const std::string path = bxdf::test_support::process_temp_path(name);
  auto out = OIIO::ImageOutput::create(path);
  OIIO::ImageSpec spec(w, h, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:UnassociatedAlpha", 1);
  if (!out || !out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, rgba.data()) ||
      !out->close())
    ADD_FAILURE() << "cannot write " << path;
  return path;
}

float srgb_to_linear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

}  // namespace

TEST(TextureLookup, FilesThroughOpenImageIO) {
  // Two texels: top (row 0 in the file) opaque grey 200, bottom half-transparent red.
  const std::string path = write_png("bxdf_texture_test.png", 1, 2, {200, 200, 200, 255, 255, 0, 0, 128});
  TextureStore store;
  TextureSettings s;
  s.path = path;
  s.interpolation = TextureInterpolation::Closest;
  const auto tex = store.get(s);
  EXPECT_EQ(store.get(s), tex);  // loaded once
  // v = 0 is the bottom row: the red texel, associated with alpha in the stored (sRGB) values.
  const float a = 128.0f / 255.0f;
  RGBA bottom = tex->lookup(0.5f, 0.25f, false);
  EXPECT_NEAR(bottom.r, srgb_to_linear(a), 1e-5f);
  EXPECT_NEAR(bottom.a, a, 1e-6f);
  bottom = tex->lookup(0.5f, 0.25f, true);  // Alpha output used: colour unassociated
  EXPECT_NEAR(bottom.r, 1.0f, 1e-5f);
  const RGBA top = tex->lookup(0.5f, 0.75f, false);
  EXPECT_NEAR(top.g, srgb_to_linear(200.0f / 255.0f), 1e-5f);
  // Linear colour space and linear interpolation: the midpoint averages stored values.
  s.colorspace = TextureColorspace::Linear;
  s.interpolation = TextureInterpolation::Linear;
  s.extension = TextureExtension::Extend;
  const RGBA mid = store.get(s)->lookup(0.5f, 0.5f, false);
  EXPECT_NEAR(mid.r, 0.5f * (200.0f / 255.0f + a), 1e-5f);
  // Channel packed: no association.
  s.alpha = TextureAlpha::ChannelPacked;
  EXPECT_NEAR(store.get(s)->lookup(0.5f, 0.0f, false).r, 1.0f, 1e-6f);
  // Missing: magenta.
  TextureSettings missing;
  missing.missing = true;
  const RGBA m = store.get(missing)->lookup(0.3f, 0.3f, false);
  EXPECT_EQ(m.r, 1.0f);
  EXPECT_EQ(m.g, 0.0f);
  EXPECT_EQ(m.b, 1.0f);
  EXPECT_EQ(m.a, 1.0f);
  TextureSettings unreadable;
  unreadable.path = path + ".does-not-exist.png";
  EXPECT_THROW(store.get(unreadable), ParameterError);
  std::remove(path.c_str());
}

// 8-bit storage (RGBA and one-channel) reads as the float grid of byte/255 values, to the bit,
// for every interpolation and extension: one formula whatever the storage. Includes a grid one
// texel wide, where Repeat wraps every neighbour onto the same texel, and points far outside.
TEST(TextureLookup, ByteStoragesReadAsTheirFloatValues) {
  for (const auto& [w, h] : {std::pair{5, 3}, std::pair{1, 4}}) {
    TexelGrid bytes, grey, as_float, grey_as_float;
    for (TexelGrid* g : {&bytes, &grey, &as_float, &grey_as_float}) {
      g->width = w;
      g->height = h;
    }
    for (int i = 0; i < w * h; ++i) {
      const std::array<unsigned char, 4> b{static_cast<unsigned char>(37 * i + 3),
                                           static_cast<unsigned char>(255 - 11 * i),
                                           static_cast<unsigned char>(91 * i % 256),
                                           static_cast<unsigned char>(128 + 9 * i)};
      bytes.bytes.push_back(b);
      grey.grey_bytes.push_back(b[0]);
      constexpr float k = 1.0f / 255.0f;
      as_float.texels.push_back({float(b[0]) * k, float(b[1]) * k, float(b[2]) * k, float(b[3]) * k});
      grey_as_float.texels.push_back({float(b[0]) * k, float(b[0]) * k, float(b[0]) * k, 1.0f});
    }
    for (auto interpolation : {TextureInterpolation::Closest, TextureInterpolation::Linear,
                               TextureInterpolation::Cubic})
      for (auto extension : {TextureExtension::Repeat, TextureExtension::Extend, TextureExtension::Clip})
        for (float u : {-3.7f, -0.05f, 0.0f, 0.1f, 0.5f, 0.93f, 1.0f, 5.2f})
          for (float v : {-1.4f, 0.0f, 0.3f, 0.77f, 1.02f, 9.6f}) {
            SCOPED_TRACE(::testing::Message() << w << "x" << h << " interp " << int(interpolation)
                                              << " ext " << int(extension) << " u " << u << " v " << v);
            const RGBA b = interpolate_texels(bytes, interpolation, extension, u, v);
            const RGBA f = interpolate_texels(as_float, interpolation, extension, u, v);
            EXPECT_EQ(b.r, f.r);
            EXPECT_EQ(b.g, f.g);
            EXPECT_EQ(b.b, f.b);
            EXPECT_EQ(b.a, f.a);
            const RGBA gb = interpolate_texels(grey, interpolation, extension, u, v);
            const RGBA gf = interpolate_texels(grey_as_float, interpolation, extension, u, v);
            EXPECT_EQ(gb.r, gf.r);
            EXPECT_EQ(gb.b, gf.b);
            EXPECT_EQ(gb.a, gf.a);
          }
  }
}

// Every 8-bit sRGB value converts as Cycles' color_srgb_to_linear (its fastpow24 is within
// ~1e-6 of powf), on both sides of the linear segment's end at 0.04045.
TEST(TextureLookup, SrgbBytesConvertAsCycles) {
  std::vector<unsigned char> row;
  for (int i = 0; i < 256; ++i) row.insert(row.end(), {static_cast<unsigned char>(i), 0, 255, 255});
  const std::string path = write_png("bxdf_texture_srgb_ramp.png", 256, 1, row);
  TextureStore store;
  TextureSettings s;
  s.path = path;
  s.interpolation = TextureInterpolation::Closest;
  const auto tex = store.get(s);
  for (int i = 0; i < 256; ++i) {
    const RGBA c = tex->lookup((float(i) + 0.5f) / 256.0f, 0.5f, false);
    const float want = srgb_to_linear(float(i) / 255.0f);
    EXPECT_NEAR(c.r, want, 2e-6f * std::max(want, 1.0f)) << "byte " << i;
    EXPECT_EQ(c.g, 0.0f);
    EXPECT_NEAR(c.b, 1.0f, 2e-6f);
    EXPECT_EQ(c.a, 1.0f);
  }
  // Between texel centres the interpolated (still sRGB) value is converted: bilinear along the
  // ramp, at points that fall between the conversion's own tabulation points.
  s.interpolation = TextureInterpolation::Linear;
  s.extension = TextureExtension::Extend;
  const auto linear = store.get(s);
  for (int k = 0; k < 2000; ++k) {
    const float x = 0.5f + 254.999f * float(k) / 1999.0f;  // texel coordinates, centre to centre
    const int i = std::min(static_cast<int>(x - 0.5f), 254);
    const float t = x - 0.5f - float(i);
    const float stored = (1.0f - t) * (float(i) / 255.0f) + t * (float(i + 1) / 255.0f);
    const float want = srgb_to_linear(stored);
    EXPECT_NEAR(linear->lookup(x / 256.0f, 0.5f, false).r, want, 2e-6f * std::max(want, 1.0f))
        << "texel coordinate " << x;
  }
  std::remove(path.c_str());
}
