// Writing and reading images through OpenImageIO. EXR holds linear float RGBA; PNG holds
// 8-bit sRGB-encoded colour (alpha stays linear). A file is written to a temporary name in the
// same folder and renamed over the target only when complete, so a failed write never damages
// an existing file.
#pragma once

#include <string>
#include <vector>

namespace bxdf::render {

struct Image {
  int width = 0, height = 0;
  std::vector<float> rgba;  // linear, row-major, top row first
};

// The format comes from the extension (.exr, .png). Throws std::runtime_error with the path and
// OIIO's message on failure; ParameterError for an unknown extension or bad sizes.
void write_image(const std::string& path, const Image& image);
// Reads any OIIO format into linear float RGBA (PNG/JPEG are decoded from sRGB).
Image read_image(const std::string& path);

}  // namespace bxdf::render
