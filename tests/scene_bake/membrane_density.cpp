// How many copies stand in a piece of membrane, counted by explicit instancing (the oracle), as a
// structural biologist would count lipids in a patch: every copy whose origin lies in the cylinder
// of radius RADIUS around the surface normal through the point, within HALF_HEIGHT of the point.
//   membrane_density PKG INSTANCE RADIUS HALF_HEIGHT  X Y Z NX NY NZ  [X Y Z NX NY NZ ...]
// Points and normals are in the compartment space of the instance. Prints one JSON object per point:
//   {"point": i, "copies": {"<molecule name>": count, ...}}
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include "format/package_view.hpp"
#include "format/validator.hpp"
#include "runtime/oracle/explicit_scene.hpp"

namespace {

using nano::format::SectionKind;

std::string json_escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) >= 0x20) out += c;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 11 || (argc - 5) % 6 != 0) {
    std::fprintf(stderr, "usage: membrane_density PKG INSTANCE RADIUS HALF_HEIGHT X Y Z NX NY NZ [...]\n");
    return 2;
  }
  try {
    const nano::format::Package package = nano::format::open_validated(argv[1]);
    const nano::oracle::ExplicitScene scene(package);
    const auto instances = package.records<SectionKind::compartment_instances>();
    const unsigned long which = std::strtoul(argv[2], nullptr, 10);
    if (which >= instances.size()) throw std::runtime_error("no compartment instance " + std::to_string(which));
    const nano::format::InstanceTransform to_world = nano::format::instance_transform(instances[which]);
    const double radius = std::atof(argv[3]), half_height = std::atof(argv[4]);
    const auto molecules = package.records<SectionKind::molecules>();
    const auto strings = package.raw_bytes(SectionKind::strings);
    const auto name_of = [&](std::uint32_t type) {
      const auto& m = molecules[type];
      return std::string(reinterpret_cast<const char*>(strings.data()) + m.name_offset, m.name_length);
    };
    for (int i = 5, point = 0; i < argc; i += 6, ++point) {
      const glm::dvec3 p =
          to_world.linear * glm::dvec3(std::atof(argv[i]), std::atof(argv[i + 1]), std::atof(argv[i + 2])) + to_world.translation;
      const glm::dvec3 n =
          glm::normalize(to_world.linear * glm::dvec3(std::atof(argv[i + 3]), std::atof(argv[i + 4]), std::atof(argv[i + 5])));
      const double reach = std::hypot(radius, half_height);
      std::map<std::string, std::size_t> counts;
      scene.for_each_copy({p - reach, p + reach}, [&](const nano::oracle::Copy& copy) {
        const glm::dvec3 d = copy.origin - p;
        const double along = glm::dot(d, n);
        if (std::abs(along) > half_height || glm::length(d - along * n) > radius) return;
        ++counts[name_of(copy.molecule_type)];
      });
      std::printf("{\"point\": %d, \"copies\": {", point);
      const char* sep = "";
      for (const auto& [name, count] : counts) {
        std::printf("%s\"%s\": %zu", sep, json_escaped(name).c_str(), count);
        sep = ", ";
      }
      std::printf("}}\n");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "membrane_density: %s\n", e.what());
    return 1;
  }
  return 0;
}
