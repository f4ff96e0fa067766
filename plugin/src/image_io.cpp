#include "bxdf/render/image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "bxdf/io/atomic_file.h"
#include "bxdf/params.h"

namespace bxdf::render {

namespace fs = std::filesystem;

namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

float linear_to_srgb(float v) {
  if (!(v > 0.0f)) return 0.0f;
  if (v >= 1.0f) return 1.0f;
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

// Reads the file just written back in full. Writers do not always notice a failed write (the PNG
// writer misses a short write under a file-size limit or on a full disk); a truncated or
// corrupt file fails to decode.
void verify_written_image(const std::string& file, const std::string& shown, const Image& image) {
  if (lower_extension(file) == ".png") {
    // A complete PNG ends with its IEND chunk. Checked first: OIIO's PNG reader cannot be
    // trusted with a truncated file (it has crashed on one).
    static const unsigned char kIend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
    unsigned char tail[12] = {};
    std::ifstream f(file, std::ios::binary | std::ios::ate);
    const bool complete = f && f.tellg() >= 12 && f.seekg(-12, std::ios::end) &&
                          f.read(reinterpret_cast<char*>(tail), 12) &&
                          std::equal(tail, tail + 12, kIend);
    if (!complete)
      throw std::runtime_error("cannot write '" + shown +
                               "': the PNG file is incomplete (a full disk or a file-size limit?)");
  }
  auto in = OIIO::ImageInput::open(file);
  if (!in) throw std::runtime_error("cannot write '" + shown + "': the written file does not read back (" +
                                    OIIO::geterror() + ")");
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> pixels(static_cast<size_t>(spec.width) * static_cast<size_t>(spec.height) *
                            static_cast<size_t>(std::max(spec.nchannels, 1)));
  const bool ok = spec.width == image.width && spec.height == image.height && spec.nchannels == 4 &&
                  in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, pixels.data());
  const std::string error = ok ? "" : in->geterror();
  in->close();
  if (!ok)
    throw std::runtime_error("cannot write '" + shown + "': the written file is incomplete or corrupt" +
                             (error.empty() ? std::string() : " (" + error + ")"));
}

}  // namespace

void write_image(const std::string& path, const Image& image) {
  const std::string ext = lower_extension(path);
  if (ext != ".exr" && ext != ".png")
    throw ParameterError("output file '" + path + "': extension '" + ext +
                         "' is not one of {.exr, .png}");
  if (image.width < 1 || image.height < 1 ||
      image.rgba.size() != 4 * static_cast<size_t>(image.width) * static_cast<size_t>(image.height))
    throw ParameterError("write_image: image of " + std::to_string(image.width) + "x" +
                         std::to_string(image.height) + " has " +
                         std::to_string(image.rgba.size()) + " floats, expected width*height*4");

  // Written beside the target and renamed over it only when complete (bxdf::io).
  io::write_file_atomically(path, [&](const std::string& temp) {
    auto out = OIIO::ImageOutput::create(temp);
    if (!out) throw std::runtime_error("cannot write '" + path + "': " + OIIO::geterror());
    bool ok = false;
    if (ext == ".exr") {
      OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::FLOAT);
      spec.attribute("oiio:ColorSpace", "Linear");
      spec.attribute("compression", "zip");
      ok = out->open(temp, spec) && out->write_image(OIIO::TypeDesc::FLOAT, image.rgba.data());
    } else {
      std::vector<float> encoded(image.rgba.size());
      for (size_t i = 0; i < image.rgba.size(); i += 4) {
        for (int c = 0; c < 3; ++c) encoded[i + c] = linear_to_srgb(image.rgba[i + c]);
        encoded[i + 3] = std::clamp(image.rgba[i + 3], 0.0f, 1.0f);
      }
      OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::UINT8);
      spec.attribute("oiio:ColorSpace", "sRGB");
      // OIIO quantises the (already sRGB-encoded) floats to 8 bits with rounding.
      ok = out->open(temp, spec) && out->write_image(OIIO::TypeDesc::FLOAT, encoded.data());
    }
    const std::string error = ok ? "" : out->geterror();
    if (!out->close() || !ok)
      throw std::runtime_error("cannot write '" + path + "': " +
                               (error.empty() ? out->geterror() : error));
    out.reset();
    verify_written_image(temp, path, image);
  });
}

Image read_image(const std::string& path) {
  // Straight from the file, not through an ImageBuf: an ImageBuf takes the file's size from
  // OIIO's shared ImageCache, which may still hold an earlier file of the same name rewritten
  // within its timestamp's resolution, and then reads the new pixels into a buffer of the old
  // size (a heap overflow).
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw std::runtime_error("cannot read '" + path + "': " + OIIO::geterror());
  const OIIO::ImageSpec spec = in->spec();
  std::vector<float> pixels(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
  const bool ok = in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data());
  const std::string error = ok ? "" : in->geterror();
  in->close();
  if (!ok) throw std::runtime_error("cannot read '" + path + "': " + error);
  Image img;
  img.width = spec.width;
  img.height = spec.height;
  img.rgba.assign(4 * static_cast<size_t>(img.width) * img.height, 1.0f);
  const bool srgb = spec.get_string_attribute("oiio:ColorSpace") == "sRGB" ||
                    spec.format == OIIO::TypeDesc::UINT8;
  const int nc = spec.nchannels;
  const bool grey = nc < 3;  // 1 = grey, 2 = grey + alpha
  const bool has_alpha = nc == 2 || nc >= 4;
  for (size_t i = 0; i < static_cast<size_t>(img.width) * img.height; ++i) {
    const float* px = &pixels[i * nc];
    for (int c = 0; c < 3; ++c) {
      float v = px[grey ? 0 : c];
      if (srgb) v = v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
      img.rgba[4 * i + c] = v;
    }
    img.rgba[4 * i + 3] = has_alpha ? px[grey ? 1 : 3] : 1.0f;
  }
  return img;
}

}  // namespace bxdf::render
