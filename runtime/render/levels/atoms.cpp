#include "runtime/render/levels/atoms.hpp"

#include <vector>

#include "runtime/render/levels/scene_state.hpp"

namespace nano::levels {

using glm::dvec3;
using glm::vec3;

// nLAS: atom boxes in molecule space; orders hold absolute atom indices.
void build_atoms(SceneState& s) {
  for (std::uint32_t t = 0; t < s.molecules.size(); ++t) {
    const gpu::MoleculeType& m = s.molecules[t];
    if (m.atom_count == 0) continue;
    std::vector<VkAabbPositionsKHR> boxes;
    std::vector<std::uint32_t> atom_indices;
    for (std::uint32_t a = m.first_atom; a < m.first_atom + m.atom_count; ++a) {
      const dvec3 c(s.atoms[a].centre_radius);
      const double r = s.atoms[a].centre_radius.w + 1e-3;  // the exact sphere test decides
      boxes.push_back(box_of(c - r, c + r));
      atom_indices.push_back(a);
    }
    s.levels[t] = s.build_level(boxes, atom_indices, t, s.report.memory.nlas);
    ++s.report.nlas_count;
  }
}

}  // namespace nano::levels
