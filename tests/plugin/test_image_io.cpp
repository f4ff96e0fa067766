// Reading images back: a file rewritten under the same name is read as it is now.
#include <gtest/gtest.h>

#include <string>

#include "bxdf/render/image_io.h"
#include "../scratch_folder.h"

using namespace bxdf::render;

namespace {

class ReadImage : public bxdf::test_support::ScratchFolderTest {};

Image ramp(int width, int height) {
  Image image;
  image.width = width;
  image.height = height;
  image.rgba.resize(4 * size_t(width) * size_t(height));
  for (size_t i = 0; i < image.rgba.size(); ++i)  // opaque: PNG stores colour unassociated
    image.rgba[i] = i % 4 == 3 ? 1.0f : float(i % 97) / 96.0f;
  return image;
}

}  // namespace

TEST_F(ReadImage, SeesAFileRewrittenUnderTheSameNameAtOnce) {
  // A small image read, then a larger one written over it within the same second: OIIO's
  // shared cache still knew the small size, and reading through it overflowed the heap (a
  // crash in one of about ten runs of the PNG-failure test).
  for (const char* name : {"same.exr", "same.png"}) {
    const std::string path = (dir_ / name).string();
    write_image(path, ramp(2, 2));
    ASSERT_EQ(read_image(path).width, 2);
    const Image large = ramp(64, 48);
    write_image(path, large);
    const Image back = read_image(path);
    ASSERT_EQ(back.width, 64) << name;
    ASSERT_EQ(back.height, 48) << name;
    ASSERT_EQ(back.rgba.size(), large.rgba.size());
    if (std::string(name) == "same.exr") {
      EXPECT_EQ(back.rgba, large.rgba);  // float storage: the very values
    } else {
      for (size_t i = 0; i < back.rgba.size(); ++i)  // 8-bit sRGB storage: within a step
        ASSERT_NEAR(back.rgba[i], large.rgba[i], 0.01f) << i;
    }
  }
}
