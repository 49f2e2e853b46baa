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

// Whether a differing pixel is explained by a relative change of every atom radius by ±ε: the
// device's answer equals (same atom and copy, depth within tolerance, or both background) the
// oracle's answer in the world with radii·(1 − ε) or radii·(1 + ε), or its depth on the same atom
// lies between those answers' depths. Such a difference is a grazing touch or a float tie. When
// shrinking the radii loses the reference's atom, the ray passes within ε·r of tangency and its depth
// is only known to within r·sqrt(2ε) (`grazing_slack`, for the largest atom radius r): a device depth
// on the same atom up to that much beyond the reference's counts as explained too.
bool explained_by_radius_change(const gpu::PixelHit& test, const gpu::PixelHit& reference, const gpu::PixelHit& shrunk,
                                const gpu::PixelHit& grown, double grazing_slack);

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
