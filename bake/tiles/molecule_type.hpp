#pragma once
// Plain input/output data of the tile generator, so the structure reader and the scene baker can
// hand molecules over without depending on each other.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace nano::tiles {

struct AtomSphere {
  glm::vec3 centre{0.f};
  float radius = 0.f;
};

// A molecule in its local frame; the frame origin is the point the generator places.
struct MoleculeType {
  std::string name;
  std::vector<AtomSphere> atoms;
  // Informational: the generator measures the extent from the atoms themselves, so a reader that
  // computed the radius about another centre cannot make it place overlapping copies.
  float bounding_radius = 0.f;
  glm::vec3 up_axis{0.f, 0.f, 1.f};  // membrane molecules stand with this along the membrane normal
};

// One placed copy in tile space: x,y (and z for cubes) in [0, edge), half-open.
struct Instance {
  uint32_t type = 0;  // index into the molecule-type list the set was generated from
  glm::vec3 position{0.f};
  glm::quat rotation{1.f, 0.f, 0.f, 0.f};  // glm order (w, x, y, z)
  // Stands in for the copy at its place when that one clashes on the real surface (squares only):
  // it overlaps that copy by design, so the set's flat guarantee does not cover it, and the pruning
  // shows it only where it fits (gpu::NANO_INSTANCE_ALTERNATE).
  bool alternate = false;
  // The layer gave this copy's place an alternate (kept unless a protein refuses it there): the
  // pruning drops such a copy before one without.
  bool has_alternate = false;
};

}  // namespace nano::tiles
