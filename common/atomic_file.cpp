#include "common/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <random>
#include <unistd.h>

#include "common/error.hpp"

namespace nano {
namespace {

std::filesystem::path temporary_sibling(const std::filesystem::path& path) {
  std::random_device rd;
  char suffix[32];
  std::snprintf(suffix, sizeof suffix, ".tmp-%d-%08x", static_cast<int>(getpid()), rd());
  std::filesystem::path tmp = path;
  tmp += suffix;
  return tmp;
}

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what) {
  throw InputError(path.string(), "", what + ": " + std::strerror(errno));
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::FILE*)>& fill) {
  const auto tmp = temporary_sibling(path);
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) fail(path, "cannot create temporary file " + tmp.string());
  try {
    fill(f);
    if (std::fflush(f) != 0 || std::ferror(f)) fail(path, "write failed");
    if (fsync(fileno(f)) != 0) fail(path, "fsync failed");
  } catch (...) {
    std::fclose(f);
    std::remove(tmp.c_str());
    throw;
  }
  if (std::fclose(f) != 0) {
    std::remove(tmp.c_str());
    fail(path, "close failed");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    fail(path, "cannot rename temporary file into place");
  }
}

void write_file_atomically(const std::filesystem::path& path, std::span<const std::byte> bytes) {
  write_file_atomically(path, [&](std::FILE* f) {
    if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size())
      fail(path, "write failed");
  });
}

}  // namespace nano
