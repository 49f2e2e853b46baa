#pragma once
// verify's judgement of one view: the device's hits against the CPU oracle's, pixel by pixel, and
// which differences are only grazing touches, float ties at an atom's surface or at a clip plane
// (they flip when every radius, one atom's radius or every clip plane moves by a hair), or the same
// atom of the same copy at a depth within the float resolution of compartment space.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "format/package.hpp"
#include "runtime/oracle/explicit_scene.hpp"
#include "runtime/oracle/oracle_render.hpp"
#include "runtime/oracle/render_compare.hpp"
#include "shared/camera.h"

namespace nano::session {

// Relative radius change that separates grazing touches and float ties from real differences:
// 1e-3·r is 0.0017 Å on a carbon, far above float error in molecule space yet far below any
// misplaced atom.
inline constexpr double kRadiusEpsilon = 1e-3;
// Å by which clip planes move to tell float ties at a plane from real clipping errors: the device
// tests atom centres in compartment space in float (~4e-3 Å ulp at 4·10^4 Å).
inline constexpr double kClipEpsilon = 1e-2;
// Float steps of compartment space by which a copy may stand apart in the device and the oracle:
// both place a copy's origin in float at compartment-space magnitudes (4·10^4 Å on a red blood
// cell's rim, a 0.004 Å step) but not through bit-identical operations (the device's fused and
// approximate arithmetic), so the same atom of the same copy may lie that much nearer or farther.
inline constexpr double kPlacementUlps = 4;

struct ViewVerdict {
  oracle::CompareResult comparison;
  std::uint64_t unexplained = 0;     // differing pixels no radius or clip tie explains
  std::uint64_t reference_hits = 0;  // pixels the oracle sees an atom in
  oracle::OracleRenderStats oracle;
};

class ViewJudge {
public:
  // `clip`: the half-spaces the frame clipped with (empty: none); the scene must outlive the judge.
  // `tubes_only`: the oracle traces every pixel's ray alone (OracleRenderOptions::tubes_only).
  ViewJudge(const format::Package& package, const oracle::ExplicitScene& scene, std::vector<glm::dvec4> clip,
            bool tubes_only = false);

  // `hits`: width × height pixels as the device rendered `camera`.
  ViewVerdict judge(const std::string& view_name, const gpu::Camera& camera, const std::vector<gpu::PixelHit>& hits,
                    std::uint32_t width, std::uint32_t height) const;

private:
  std::uint64_t unexplained_pixels(const oracle::OracleRenderOptions& options, const gpu::Camera& camera,
                                   const std::vector<gpu::PixelHit>& reference, const std::vector<gpu::PixelHit>& hits,
                                   std::uint32_t width) const;

  const format::Package& package_;
  const oracle::ExplicitScene& scene_;
  std::vector<glm::dvec4> clip_;
  bool tubes_only_ = false;
  double largest_atom_ = 0;
  double grazing_slack_ = 0;
  double placement_slack_ = 0;  // kPlacementUlps float steps at the meshes' largest coordinate, Å
  oracle::WorldBox bounds_;
};

}  // namespace nano::session
