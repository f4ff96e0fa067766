// The readers under fuzzing take file names; inputs are written to a private folder first.
#pragma once

#include <cstddef>
#include <string>

namespace bxdf::fuzz {

// A folder of this process (in /dev/shm when there is one, so that writes stay in memory).
const std::string& scratch_folder();

// Writes `size` bytes to scratch_folder()/name and returns the path.
std::string write_scratch(const std::string& name, const void* data, size_t size);

}  // namespace bxdf::fuzz
