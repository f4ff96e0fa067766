// Writing a file so that a failure never leaves a half-written or clobbered file behind:
// write beside the target under a temporary name, then rename over it.
#pragma once

#include <functional>
#include <string>

namespace bxdf::io {

// Calls write(temp_path) and renames temp_path to path if it returns without throwing.
// On failure the temporary file is removed, the target is untouched, and the exception
// propagates.
void write_file_atomically(const std::string& path,
                           const std::function<void(const std::string& temp_path)>& write);

// A temporary name in the same folder (so the rename stays on one file system), keeping the
// extension so that writers choosing a format by extension still work: "a/b.exr" →
// "a/.b.exr.tmp-<pid>-<n>.exr".
std::string temporary_sibling(const std::string& path);

}  // namespace bxdf::io
