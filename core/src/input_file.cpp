#include "bxdf/input_file.h"

#include <filesystem>
#include <fstream>
#include <system_error>

#include "bxdf/params.h"

namespace bxdf {

namespace {

// Length of the valid UTF-8 sequence starting at s[i] (1 to 4), or 0 if it is not valid
// (overlong forms, surrogates and code points past U+10FFFF are not).
size_t utf8_sequence_length(std::string_view s, size_t i) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  size_t n;
  unsigned lo = 0x80, hi = 0xBF;  // range of the second byte
  if (c < 0x80) return 1;
  if (c >= 0xC2 && c <= 0xDF) n = 2;
  else if (c >= 0xE0 && c <= 0xEF) {
    n = 3;
    if (c == 0xE0) lo = 0xA0;
    if (c == 0xED) hi = 0x9F;
  } else if (c >= 0xF0 && c <= 0xF4) {
    n = 4;
    if (c == 0xF0) lo = 0x90;
    if (c == 0xF4) hi = 0x8F;
  } else {
    return 0;
  }
  if (i + n > s.size()) return 0;
  if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (size_t k = 2; k < n; ++k)
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  return n;
}

}  // namespace

std::string printable(std::string_view text) {
  static const char* kHex = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const size_t n = utf8_sequence_length(text, i);
    if (n == 0 || (n == 1 && (c < 0x20 || c == 0x7F))) {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
      ++i;
    } else {
      out.append(text.substr(i, n));
      i += n;
    }
  }
  return out;
}

std::uintmax_t check_input_file(const std::string& path, std::uintmax_t max_bytes,
                                const std::string& what) {
  namespace fs = std::filesystem;
  const std::string name = what + " '" + printable(path) + "'";
  if (path.find('\0') != std::string::npos)
    throw ParameterError(name + ": the path contains a NUL character");
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) throw ParameterError(name + " cannot be opened: it does not exist");
  if (!fs::is_regular_file(status))
    throw ParameterError(name + " is not a regular file (a device, FIFO or folder cannot be read)");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw ParameterError(name + " cannot be read: " + ec.message());
  if (size > max_bytes)
    throw ParameterError(name + " is " + std::to_string(size) + " bytes; the limit is " +
                         std::to_string(max_bytes));
  return size;
}

std::string read_input_file(const std::string& path, std::uintmax_t max_bytes,
                            const std::string& what) {
  const std::uintmax_t size = check_input_file(path, max_bytes, what);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ParameterError(what + " '" + printable(path) + "' cannot be opened");
  std::string bytes(static_cast<size_t>(size), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  // A file that shrank while being read is reported; one that grew is read up to its old size.
  if (static_cast<std::uintmax_t>(in.gcount()) != size)
    throw ParameterError(what + " '" + printable(path) + "': read failed");
  return bytes;
}

}  // namespace bxdf
