#include "bxdf/io/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "bxdf/input_file.h"
#include "bxdf/params.h"

namespace bxdf::io {

namespace fs = std::filesystem;

namespace {

constexpr const char* kTempTag = ".partial-";
constexpr size_t kMaxFileNameBytes = 255;  // NAME_MAX on Linux file systems
constexpr int kMaxSymlinkHops = 40;        // as the kernel's ELOOP limit

// "a/b.exr" → "b.exr.partial-" (shortened so that the whole temporary name fits NAME_MAX).
std::string temp_prefix(const fs::path& target) {
  const std::string name = target.filename().string();
  const std::string ext = target.extension().string();
  // Room for the tag, "<pid>-<n>" (at most 10 + 1 + 10 digits) and the extension.
  const size_t reserve = std::char_traits<char>::length(kTempTag) + 21 + ext.size();
  const size_t keep = reserve < kMaxFileNameBytes ? kMaxFileNameBytes - reserve : 0;
  return name.substr(0, std::min(name.size(), keep)) + kTempTag;
}

// Follows symbolic links to the file they name (which need not exist yet).
fs::path resolve_links(const fs::path& path) {
  fs::path p = path;
  for (int hop = 0; fs::is_symlink(p); ++hop) {
    if (hop == kMaxSymlinkHops)
      throw ParameterError("output file '" + printable(path.string()) + "': too many symbolic links");
    const fs::path link = fs::read_symlink(p);
    p = link.is_absolute() ? link : p.parent_path() / link;
  }
  return p;
}

// Removes temporaries of `target` left by processes that no longer exist (a killed render).
void remove_stale_temporaries(const fs::path& target) {
  const std::string prefix = temp_prefix(target);
  const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
    if (pid <= 0 || pid == ::getpid()) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // still running
    std::error_code ignored;
    fs::remove(it->path(), ignored);
  }
}

void sync_path(const std::string& path, int flags) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0 || ::fsync(fd) != 0) {
    const int error = errno;
    if (fd >= 0) ::close(fd);
    throw std::runtime_error("cannot sync '" + printable(path) + "': " +
                             std::generic_category().message(error));
  }
  ::close(fd);
}

}  // namespace

std::string temporary_sibling(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  const fs::path p(path);
  const std::string name = temp_prefix(p) + std::to_string(::getpid()) + "-" +
                           std::to_string(counter++) + p.extension().string();
  return (p.parent_path() / name).string();
}

void write_file_atomically(const std::string& path,
                           const std::function<void(const std::string& temp_path)>& write) {
  const std::string shown = printable(path);
  if (path.empty()) throw ParameterError("output file: the path is empty");
  if (path.find('\0') != std::string::npos)
    throw ParameterError("output file '" + shown + "': the path contains a NUL character");
  // A symbolic link is written through: the file it names is replaced, the link stays.
  const fs::path target = resolve_links(fs::path(path));
  struct stat old {};
  const bool exists = ::stat(target.c_str(), &old) == 0;
  if (exists) {
    if (!S_ISREG(old.st_mode))
      throw ParameterError("output file '" + shown + "' exists and is not a regular file");
    // Mode bits, not access(): root may write anything, but a read-only file says "keep me".
    if ((old.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0 || ::access(target.c_str(), W_OK) != 0)
      throw ParameterError("output file '" + shown + "' is read-only; it was not replaced");
  }
  remove_stale_temporaries(target);

  const std::string temp = temporary_sibling(target.string());
  try {
    write(temp);
    if (exists) {  // the new file keeps the old one's permissions (and owner, where allowed)
      ::chmod(temp.c_str(), old.st_mode & 07777);
      if (::chown(temp.c_str(), old.st_uid, old.st_gid) != 0) {
        // Only root may give a file away; another owner's writable file becomes ours.
      }
    }
    sync_path(temp, O_RDONLY);  // the data is on disk before the rename makes it visible
  } catch (...) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw;
  }
  std::error_code ec;
  fs::rename(temp, target, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw std::runtime_error("cannot write '" + shown + "': " + ec.message());
  }
  const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  try {
    sync_path(folder.string(), O_RDONLY | O_DIRECTORY);  // the rename itself is durable
  } catch (const std::runtime_error&) {
    // Some file systems cannot sync a directory; the file is complete either way.
  }
}

}  // namespace bxdf::io
