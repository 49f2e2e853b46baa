#include "common/user_cache_directory.hpp"

#include <cstdlib>

namespace nano {

namespace {

std::optional<std::filesystem::path> absolute_path_from(const char* variable) {
  const char* value = std::getenv(variable);
  if (value == nullptr || *value == '\0') return std::nullopt;
  std::filesystem::path path(value);
  if (!path.is_absolute()) return std::nullopt;
  return path;
}

}  // namespace

std::optional<std::filesystem::path> user_cache_directory() {
  if (auto xdg = absolute_path_from("XDG_CACHE_HOME")) return xdg;
  if (auto home = absolute_path_from("HOME")) return *home / ".cache";
  return std::nullopt;
}

}  // namespace nano
