// nano_fuzzer's reader "package": arbitrary bytes through the package reader and the semantic validator.
// Rejection as a PackageError is the expected outcome; anything else (another exception, a crash,
// a sanitizer report, a leak, an allocation over -rss_limit_mb) is a finding.
#include <cstddef>
#include <cstdint>
#include <span>

#include "format/validator.hpp"

namespace {

// Reads every record of every section a valid package hands out, so the sanitizers see any span
// that reaches past its storage.
template <nano::format::SectionKind K> std::uint64_t touch(const nano::format::Package& p) {
  std::uint64_t sum = 0;
  for (const auto& r : p.records<K>()) sum += reinterpret_cast<const unsigned char*>(&r)[sizeof(r) - 1];
  return sum;
}

template <std::size_t... I> std::uint64_t touch_all(const nano::format::Package& p, std::index_sequence<I...>) {
  return (touch<nano::format::kAllSectionKinds[I]>(p) + ...);
}

}  // namespace

namespace nano::fuzz {

void fuzz_package(std::span<const std::byte> bytes) {
  try {
    const auto p = nano::format::Package::from_bytes(bytes, "fuzz.nup");
    nano::format::validate_semantics(p);
    volatile std::uint64_t sink = touch_all(p, std::make_index_sequence<std::size(nano::format::kAllSectionKinds)>());
    (void)sink;
  } catch (const nano::format::PackageError&) {
  }
}

}  // namespace nano::fuzz
