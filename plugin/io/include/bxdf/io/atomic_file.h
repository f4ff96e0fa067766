// Writing a file so that a failure never leaves a half-written or clobbered file behind:
// write beside the target under a temporary name, then rename over it.
#pragma once

#include <functional>
#include <string>

namespace bxdf::io {

// Calls write(temp_path), syncs temp_path to disk and renames it to path if write returns
// without throwing. On failure the temporary file is removed, the target is untouched, and the
// exception propagates. Refused up front (ParameterError): an existing target that is read-only
// or not a regular file, a path with a NUL. A symbolic link is written through (the file it
// names is replaced; the link stays). The new file keeps the old one's mode. Temporaries left
// by a killed process (its pid no longer exists) are removed by the next write to the target.
void write_file_atomically(const std::string& path,
                           const std::function<void(const std::string& temp_path)>& write);

// A temporary name in the same folder (so the rename stays on one file system), keeping the
// extension so that writers choosing a format by extension still work: "a/b.exr" →
// "a/b.exr.partial-<pid>-<n>.exr" (visible, so a left-over is found; the first part is shortened
// when the whole name would pass 255 bytes).
std::string temporary_sibling(const std::string& path);

}  // namespace bxdf::io
