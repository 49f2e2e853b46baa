// Helpers of the placement tests: fixed-seed random numbers and double-precision vector maths used by
// the independent oracles (never the code under test).
#pragma once
#include <cmath>
#include <cstdint>
#include <random>

#include <glm/glm.hpp>

namespace placement_test {

using glm::dvec2;
using glm::dvec3;

struct Rng {
  std::mt19937_64 gen;
  explicit Rng(std::uint64_t seed) : gen(seed) {}
  double uniform(double lo = 0.0, double hi = 1.0) { return std::uniform_real_distribution<double>(lo, hi)(gen); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(gen); }  // inclusive
  glm::vec3 unit_vector() {
    for (;;) {
      dvec3 v(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
      double l = glm::length(v);
      if (l > 0.1 && l <= 1.0) return glm::vec3(v / l);
    }
  }
  glm::vec3 in_box(double lo, double hi) {
    return glm::vec3(float(uniform(lo, hi)), float(uniform(lo, hi)), float(uniform(lo, hi)));
  }
};

inline dvec3 D(const glm::vec3& v) { return dvec3(v); }
inline dvec2 D(const glm::vec2& v) { return dvec2(v); }

// Relative difference |a − b| / max(|b|, floor).
inline double rel_err(double a, double b, double floor_ = 1e-30) {
  return std::abs(a - b) / std::max(std::abs(b), floor_);
}

}  // namespace placement_test
