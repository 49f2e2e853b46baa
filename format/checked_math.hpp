#pragma once
// Offset arithmetic on untrusted 64-bit values: nullopt instead of wrapping around.
#include <cstdint>
#include <optional>

namespace nano::format {

inline std::optional<std::uint64_t> checked_add(std::uint64_t a, std::uint64_t b) {
  std::uint64_t r;
  if (__builtin_add_overflow(a, b, &r)) return std::nullopt;
  return r;
}

inline std::optional<std::uint64_t> checked_mul(std::uint64_t a, std::uint64_t b) {
  std::uint64_t r;
  if (__builtin_mul_overflow(a, b, &r)) return std::nullopt;
  return r;
}

// True if [first, first + count) lies inside [0, size).
inline bool range_within(std::uint64_t first, std::uint64_t count, std::uint64_t size) {
  const auto end = checked_add(first, count);
  return end && *end <= size;
}

}  // namespace nano::format
