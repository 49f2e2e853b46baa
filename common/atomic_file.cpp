#include "common/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <csignal>
#include <random>
#include <unistd.h>

#include "common/error.hpp"

namespace nano {
namespace {

// The temporary file being written, for the signal handler: a fixed buffer, as a handler may
// only touch what is async-signal-safe.
char pending_temporary[4096];
volatile std::sig_atomic_t has_pending_temporary = 0;

extern "C" void remove_pending_and_reraise(int signal_number) {
  if (has_pending_temporary) unlink(pending_temporary);
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

// Registers `tmp` as the file to remove on an interrupt for as long as it lives.
class PendingTemporary {
public:
  explicit PendingTemporary(const std::filesystem::path& tmp) {
    const std::string text = tmp.string();
    if (text.size() >= sizeof pending_temporary) return;
    has_pending_temporary = 0;
    std::memcpy(pending_temporary, text.c_str(), text.size() + 1);
    has_pending_temporary = 1;
  }
  ~PendingTemporary() { has_pending_temporary = 0; }
  PendingTemporary(const PendingTemporary&) = delete;
  PendingTemporary& operator=(const PendingTemporary&) = delete;
};

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
  const PendingTemporary pending(tmp);
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

void remove_temporaries_on_interrupt() {
  std::signal(SIGINT, remove_pending_and_reraise);
  std::signal(SIGTERM, remove_pending_and_reraise);
}

void write_file_atomically(const std::filesystem::path& path, std::span<const std::byte> bytes) {
  write_file_atomically(path, [&](std::FILE* f) {
    if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size())
      fail(path, "write failed");
  });
}

}  // namespace nano
