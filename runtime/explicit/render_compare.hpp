#pragma once
// Pixel-by-pixel agreement of two PixelHit images (shaders/shared/camera.h), as `nanoview verify`
// reports it: the device's image against the CPU oracle's.
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "shared/camera.h"

namespace nano::oracle {

// Why a pixel disagrees; the first that applies, in this order.
enum class PixelDifference : std::uint8_t {
  none = 0,
  bad_depth,      // a hit whose depth is NaN or ±inf, or a no-hit pixel whose depth is not +inf
  missed,         // exactly one side hit something
  different_atom, // both hit, but not the same (copy number, atom)
  different_ids,  // same copy number and atom, yet another id field (instance, element, kind, cell, ...) differs
  depth_only,     // same hit, |Δdepth| > max(1e-3 Å, 1e-5·t)
};
const char* to_string(PixelDifference d);

struct PixelMismatch {
  std::uint32_t x = 0, y = 0;
  PixelDifference why = PixelDifference::none;
  gpu::PixelHit reference, test;
};

struct CompareResult {
  std::uint64_t pixels = 0;
  std::uint64_t agree = 0;  // both background, or same hit within the depth tolerance
  std::uint64_t bad_depth = 0, missed = 0, different_atom = 0, different_ids = 0, depth_only = 0;
  double max_depth_difference = 0;  // over pixels with the same hit (finite depths)
  std::vector<PixelMismatch> first;  // the first differing pixels in row-major order

  double agreement() const { return pixels == 0 ? 1.0 : double(agree) / double(pixels); }
};

// Depth tolerance at reference depth t: max(1e-3 Å, 1e-5·t).
double depth_tolerance(double t);
PixelDifference classify(const gpu::PixelHit& reference, const gpu::PixelHit& test);

// `reference` (the oracle) and `test` are row-major width × height images; keeps the first
// `keep` mismatches. Throws std::invalid_argument if a size is not width·height.
CompareResult compare_images(const std::vector<gpu::PixelHit>& reference, const std::vector<gpu::PixelHit>& test,
                             std::uint32_t width, std::uint32_t height, std::size_t keep = 20);

nlohmann::json to_json(const gpu::PixelHit& hit);
nlohmann::json to_json(const CompareResult& result);

}  // namespace nano::oracle
