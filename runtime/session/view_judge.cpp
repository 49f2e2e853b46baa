#include "runtime/session/view_judge.hpp"

#include <algorithm>
#include <cmath>

#include "runtime/oracle/atom_radii_judge.hpp"

namespace nano::session {

ViewJudge::ViewJudge(const format::Package& package, const oracle::ExplicitScene& scene, std::vector<glm::dvec4> clip,
                     bool tubes_only)
    : package_(package), scene_(scene), clip_(std::move(clip)), tubes_only_(tubes_only), bounds_(oracle::scene_world_bounds(package, &scene)) {
  for (const gpu::Atom& a : package.records<format::SectionKind::atoms>())
    largest_atom_ = std::max(largest_atom_, double(a.centre_radius.w));
  grazing_slack_ = largest_atom_ * std::sqrt(2 * kRadiusEpsilon);
  float largest = 0.f;
  for (const gpu::Mesh& m : package.records<format::SectionKind::meshes>())
    for (int a = 0; a < 3; ++a) largest = std::max({largest, std::abs(m.aabb_min[a]), std::abs(m.aabb_max[a])});
  placement_slack_ = kPlacementUlps * double(std::nextafter(largest, INFINITY) - largest);
}

ViewVerdict ViewJudge::judge(const std::string& view_name, const gpu::Camera& camera, const std::vector<gpu::PixelHit>& hits,
                             std::uint32_t width, std::uint32_t height) const {
  oracle::OracleRenderOptions options;
  options.camera_name = view_name;
  options.clip = clip_;
  options.tubes_only = tubes_only_;
  ViewVerdict v;
  const std::vector<gpu::PixelHit> reference = oracle::oracle_render(scene_, package_, camera, options, &v.oracle);
  v.comparison = oracle::compare_images(reference, hits, width, height);
  if (v.comparison.agree != v.comparison.pixels) v.unexplained = unexplained_pixels(options, camera, reference, hits, width);
  for (const gpu::PixelHit& p : reference) v.reference_hits += p.atom != gpu::kNoHit;
  return v;
}

std::uint64_t ViewJudge::unexplained_pixels(const oracle::OracleRenderOptions& options, const gpu::Camera& camera,
                                            const std::vector<gpu::PixelHit>& reference,
                                            const std::vector<gpu::PixelHit>& hits, std::uint32_t width) const {
  // Which differences a relative change of every radius by ±ε flips: grazing touches and ties. Only
  // the differing pixels are traced again (a pixel's hit does not depend on which others are traced).
  oracle::OracleRenderOptions differing = options;
  for (std::uint32_t i = 0; i < reference.size(); ++i)
    if (oracle::classify(reference[i], hits[i]) != oracle::PixelDifference::none) differing.only_pixels.push_back(i);
  oracle::OracleRenderOptions shrink = differing, grow = differing;
  shrink.radius_scale = 1 - kRadiusEpsilon;
  grow.radius_scale = 1 + kRadiusEpsilon;
  const auto shrunk = oracle::oracle_render(scene_, package_, camera, shrink);
  const auto grown = oracle::oracle_render(scene_, package_, camera, grow);
  // Clip ties: an atom centre within ε of a plane is kept or removed by float rounding; the oracle
  // with every half-space moved by ±ε says which pixels such ties decide.
  std::vector<gpu::PixelHit> clipped_more, clipped_less;
  if (!clip_.empty()) {
    oracle::OracleRenderOptions more = differing, less = differing;
    for (glm::dvec4& h : more.clip) h.w -= kClipEpsilon;
    for (glm::dvec4& h : less.clip) h.w += kClipEpsilon;
    clipped_more = oracle::oracle_render(scene_, package_, camera, more);
    clipped_less = oracle::oracle_render(scene_, package_, camera, less);
  }
  std::uint64_t unexplained = 0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    if (oracle::classify(reference[i], hits[i]) == oracle::PixelDifference::none ||
        oracle::explained_by_radius_change(hits[i], reference[i], shrunk[i], grown[i], grazing_slack_))
      continue;
    const std::uint32_t x = std::uint32_t(i % width), y = std::uint32_t(i / width);
    const glm::dvec3 eye(glm::vec3(camera.position)), direction(gpu::camera_ray_direction(camera, x, y));
    if (oracle::classify(reference[i], hits[i]) == oracle::PixelDifference::depth_only &&
        (std::abs(double(hits[i].depth) - double(reference[i].depth)) <= placement_slack_ + oracle::depth_tolerance(reference[i].depth) ||
         oracle::explained_by_placement(scene_, eye, direction, hits[i], placement_slack_, largest_atom_)))
      continue;
    if (!clip_.empty() && (oracle::classify(clipped_more[i], hits[i]) == oracle::PixelDifference::none ||
                           oracle::classify(clipped_less[i], hits[i]) == oracle::PixelDifference::none))
      continue;
    // Per-atom radii: two grazing touches on one ray, one shrunk and one grown; or two atoms met at one depth.
    if (!oracle::explained_by_atom_radii(scene_, bounds_, eye, direction, hits[i], kRadiusEpsilon, largest_atom_, clip_,
                                         kPlacementUlps) &&
        !oracle::explained_as_tie(scene_, eye, direction, hits[i], reference[i], largest_atom_))
      ++unexplained;
  }
  return unexplained;
}

}  // namespace nano::session
