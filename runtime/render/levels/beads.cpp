#include "runtime/render/levels/beads.hpp"

#include <vector>

#include "runtime/render/levels/scene_state.hpp"

namespace nano::levels {

using glm::dvec3;
using glm::vec3;

// The level of detail: per molecule type a level over the beads the baker stored for it
// (sections beads / bead_ranges, validated: indices in range, every type has beads). A package
// without them (format < 2.5) has no bead levels, and has_beads() says so.
void build_beads(SceneState& s) {
  if (s.bead_ranges.empty()) return;
  for (std::uint32_t t = 0; t < s.molecules.size(); ++t) {
    std::vector<VkAabbPositionsKHR> boxes;
    std::vector<std::uint32_t> indices;
    for (std::uint32_t b = s.bead_ranges[t].first; b < s.bead_ranges[t].first + s.bead_ranges[t].count; ++b) {
      const dvec3 centre(vec3(s.beads[b].centre_radius));
      const double radius = s.beads[b].centre_radius.w;
      indices.push_back(b);
      boxes.push_back(box_of(centre - radius, centre + radius));
    }
    s.levels[s.first_bead + t] = s.build_level(boxes, indices, s.first_bead + t, s.report.memory.nlas);
  }
}

}  // namespace nano::levels
