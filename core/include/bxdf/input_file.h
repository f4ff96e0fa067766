// Input files from untrusted sources: text echoed into messages, and the checks every reader
// makes before it reads (a regular file, not too large), so that "/dev/zero", a FIFO or a huge
// file gets a message instead of an endless read.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace bxdf {

// Size limits of the readers (bytes). They are far above any real file of the kind and far below
// what would exhaust memory on a workstation.
constexpr std::uintmax_t kMaxJsonFileBytes = std::uintmax_t(256) << 20;     // scene, material
constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t(4) << 30;       // OBJ
constexpr std::uintmax_t kMaxMeasuredFileBytes = std::uintmax_t(256) << 20;  // Cornell .brdf

// `text` safe to print: valid UTF-8 is kept, control characters and bytes that are not valid
// UTF-8 become \xNN, so that a message is always valid UTF-8 (Python's ValueError can hold it).
std::string printable(std::string_view text);

// Throws ParameterError ("<what> '<path>' ...") unless `path` names a regular file (after
// following symbolic links) of at most max_bytes bytes; refuses an embedded NUL. Returns the size.
std::uintmax_t check_input_file(const std::string& path, std::uintmax_t max_bytes,
                                const std::string& what);

// The whole file as bytes, after check_input_file.
std::string read_input_file(const std::string& path, std::uintmax_t max_bytes,
                            const std::string& what);

}  // namespace bxdf
