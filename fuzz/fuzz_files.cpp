#include "fuzz_files.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace bxdf::fuzz {

namespace fs = std::filesystem;

const std::string& scratch_folder() {
  // Never destroyed: the exit handler that removes the folder runs after static destructors.
  static const std::string* folder = [] {
    const fs::path base = fs::is_directory("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
    const fs::path dir = base / ("bxdf-fuzz-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::atexit([] { std::error_code ec; fs::remove_all(scratch_folder(), ec); });
    return new std::string(dir.string());
  }();
  return *folder;
}

std::string write_scratch(const std::string& name, const void* data, size_t size) {
  const std::string path = scratch_folder() + "/" + name;
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
  return path;
}

}  // namespace bxdf::fuzz
