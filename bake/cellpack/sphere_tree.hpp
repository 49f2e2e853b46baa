#pragma once
// cellPACK's packing representation, the .sph sphere tree: "rmin rmax", the number of levels, then
// per level its sphere count and one "x y z r [child indices…]" line per sphere (Å, the
// ingredient's frame); '#' lines and blank lines are comments. A stand-in for an ingredient whose
// structure is missing is drawn from its finest level.
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec4.hpp>

namespace nano::cellpack {

inline constexpr std::size_t kMaxSphereTreeSpheres = 1'000'000;

struct SphereTree {
  double min_radius = 0;                       // rmin
  double max_radius = 0;                       // rmax: the encapsulating radius
  std::vector<std::vector<glm::dvec4>> levels;  // coarsest first; (x, y, z, r)
};

// Parses `text`; a malformed file is an InputError naming `file` and the line.
SphereTree parse_sphere_tree(std::string_view text, const std::string& file);
SphereTree read_sphere_tree(const std::filesystem::path& file);

}  // namespace nano::cellpack
