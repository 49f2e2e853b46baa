#pragma once
// The cameras of `nanoview verify`: close views chosen from a package's own geometry so that every
// hard case of the renderer is looked at — membrane from outside, grazing rays along it, rays
// through a mesh vertex (shared triangle edges) and through a Wang tile corner, an eye inside a
// prism, inside the core grid, inside an atom, and exactly axis-aligned rays through the core grid.
// Close views keep the oracle's explicit instancing small (it holds every atom in view).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "common/camera.hpp"
#include "format/package.hpp"
#include "runtime/oracle/explicit_scene.hpp"

namespace nano::oracle {

struct VerifyCamera {
  std::string name;
  Camera view;
  bool odd_size = false;  // render at an odd width and height so the centre pixel's ray is exactly `at − eye`
};

// Up to `count` cameras (at least the hard cases the package has: a scene without a core grid has no
// core cameras), deterministic for a package.
std::vector<VerifyCamera> verify_cameras(const format::Package& package, const ExplicitScene& scene, std::size_t count);

}  // namespace nano::oracle
