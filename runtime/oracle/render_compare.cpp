#include "runtime/oracle/render_compare.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace nano::oracle {
namespace {

bool is_background(const gpu::PixelHit& h) { return h.atom == gpu::kNoHit; }

std::uint64_t copy_number(const gpu::PixelHit& h) { return std::uint64_t{h.copy_number_hi} << 32 | h.copy_number_lo; }

bool depth_valid(const gpu::PixelHit& h) {
  return is_background(h) ? h.depth == std::numeric_limits<float>::infinity() : std::isfinite(h.depth);
}

// JSON has no infinities or NaN: such depths are written as strings.
nlohmann::json depth_json(float d) {
  if (std::isfinite(d)) return d;
  return std::isnan(d) ? "nan" : (d > 0 ? "inf" : "-inf");
}

}  // namespace

const char* to_string(PixelDifference d) {
  switch (d) {
    case PixelDifference::none: return "none";
    case PixelDifference::bad_depth: return "bad_depth";
    case PixelDifference::missed: return "missed";
    case PixelDifference::different_atom: return "different_atom";
    case PixelDifference::different_ids: return "different_ids";
    case PixelDifference::depth_only: return "depth_only";
  }
  return "?";
}

double depth_tolerance(double t) { return std::max(1e-3, 1e-5 * t); }

PixelDifference classify(const gpu::PixelHit& a, const gpu::PixelHit& b) {
  if (!depth_valid(a) || !depth_valid(b)) return PixelDifference::bad_depth;
  if (is_background(a) != is_background(b)) return PixelDifference::missed;
  if (is_background(a)) return PixelDifference::none;
  if (copy_number(a) != copy_number(b) || a.atom != b.atom) return PixelDifference::different_atom;
  if (a.compartment_instance != b.compartment_instance || a.element != b.element || a.kind != b.kind ||
      a.cell != b.cell || a.instance != b.instance)
    return PixelDifference::different_ids;
  if (std::abs(double(a.depth) - double(b.depth)) > depth_tolerance(a.depth)) return PixelDifference::depth_only;
  return PixelDifference::none;
}

CompareResult compare_images(const std::vector<gpu::PixelHit>& reference, const std::vector<gpu::PixelHit>& test,
                             std::uint32_t width, std::uint32_t height, std::size_t keep) {
  const std::size_t n = std::size_t(width) * height;
  if (reference.size() != n || test.size() != n)
    throw std::invalid_argument("compare_images: images of " + std::to_string(reference.size()) + " and " +
                                std::to_string(test.size()) + " pixels for a " + std::to_string(width) + "×" +
                                std::to_string(height) + " view");
  CompareResult r;
  r.pixels = n;
  for (std::size_t i = 0; i < n; ++i) {
    const gpu::PixelHit &a = reference[i], &b = test[i];
    const PixelDifference why = classify(a, b);
    switch (why) {
      case PixelDifference::none: ++r.agree; break;
      case PixelDifference::bad_depth: ++r.bad_depth; break;
      case PixelDifference::missed: ++r.missed; break;
      case PixelDifference::different_atom: ++r.different_atom; break;
      case PixelDifference::different_ids: ++r.different_ids; break;
      case PixelDifference::depth_only: ++r.depth_only; break;
    }
    if (why == PixelDifference::none || why == PixelDifference::depth_only || why == PixelDifference::different_ids)
      if (!is_background(a) && std::isfinite(a.depth))
        r.max_depth_difference = std::max(r.max_depth_difference, std::abs(double(a.depth) - double(b.depth)));
    if (why != PixelDifference::none && r.first.size() < keep)
      r.first.push_back({std::uint32_t(i % width), std::uint32_t(i / width), why, a, b});
  }
  return r;
}

nlohmann::json to_json(const gpu::PixelHit& h) {
  if (is_background(h) && h.depth == std::numeric_limits<float>::infinity()) return {{"background", true}};
  return {{"depth", depth_json(h.depth)},
          {"copy_number", copy_number(h)},
          {"atom", h.atom},
          {"compartment_instance", h.compartment_instance},
          {"kind", h.kind},
          {"element", h.element},
          {"cell", {h.cell.x, h.cell.y, h.cell.z}},
          {"instance", h.instance}};
}

nlohmann::json to_json(const CompareResult& r) {
  nlohmann::json first = nlohmann::json::array();
  for (const PixelMismatch& m : r.first)
    first.push_back({{"x", m.x}, {"y", m.y}, {"why", to_string(m.why)}, {"reference", to_json(m.reference)}, {"test", to_json(m.test)}});
  return {{"pixels", r.pixels},
          {"agree", r.agree},
          {"agreement", r.agreement()},
          {"bad_depth", r.bad_depth},
          {"missed", r.missed},
          {"different_atom", r.different_atom},
          {"different_ids", r.different_ids},
          {"depth_only", r.depth_only},
          {"max_depth_difference", r.max_depth_difference},
          {"first_differences", first}};
}

bool explained_by_radius_change(const gpu::PixelHit& test, const gpu::PixelHit& reference, const gpu::PixelHit& shrunk,
                                const gpu::PixelHit& grown, double grazing_slack) {
  if (classify(shrunk, test) == PixelDifference::none || classify(grown, test) == PixelDifference::none) return true;
  const auto same_atom = [](const gpu::PixelHit& a, const gpu::PixelHit& b) {
    return a.atom != gpu::kNoHit && a.atom == b.atom && a.copy_number_lo == b.copy_number_lo &&
           a.copy_number_hi == b.copy_number_hi;
  };
  // Same atom in the device's image and in a perturbed one: a depth between the perturbed depths.
  for (const gpu::PixelHit* p : {&reference, &shrunk, &grown}) {
    if (!same_atom(test, *p)) continue;
    double lo = p->depth, hi = p->depth;
    for (const gpu::PixelHit* q : {&reference, &shrunk, &grown})
      if (same_atom(test, *q)) lo = std::min(lo, double(q->depth)), hi = std::max(hi, double(q->depth));
    const double tol = depth_tolerance(lo);
    if (test.depth >= lo - tol && test.depth <= hi + tol) return true;
  }
  if (same_atom(test, reference) && !same_atom(shrunk, reference) &&
      std::abs(double(test.depth) - double(reference.depth)) <= grazing_slack + depth_tolerance(reference.depth))
    return true;
  return false;
}

}  // namespace nano::oracle
