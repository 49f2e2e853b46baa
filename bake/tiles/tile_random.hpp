#pragma once
// Our own generator and hashes: std::uniform_*_distribution differs between standard libraries,
// and a seed must give byte-identical tiles everywhere.
#include <cstdint>

namespace nano::tiles {

inline uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

class SplitMix64 {
public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}
  uint64_t next() { return mix64(state_ += 0x9E3779B97F4A7C15ull); }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  uint32_t below(uint32_t n) { return static_cast<uint32_t>(((next() >> 32) * n) >> 32); }

private:
  uint64_t state_;
};

// Hash of a lattice element (cell or face): independent of visiting order, so recipes are O(1) per cell.
inline uint64_t lattice_hash(uint64_t seed, int64_t i, int64_t j, int64_t k, uint32_t tag) {
  uint64_t h = mix64(seed ^ 0x243F6A8885A308D3ull);
  h = mix64(h ^ static_cast<uint64_t>(i));
  h = mix64(h ^ static_cast<uint64_t>(j) * 0x9E3779B97F4A7C15ull);
  h = mix64(h ^ static_cast<uint64_t>(k) * 0xC2B2AE3D27D4EB4Full);
  return mix64(h ^ (static_cast<uint64_t>(tag) << 32));
}

}  // namespace nano::tiles
