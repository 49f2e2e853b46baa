#include "runtime/render/camera_spec.hpp"

#include <cmath>
#include <iterator>
#include <cstdio>
#include <sstream>

#include <glm/geometric.hpp>

namespace nano::render {
namespace {

glm::dvec3 parse_vector(std::string_view key, std::string_view value, const InputSource& source) {
  glm::dvec3 v;
  std::string s(value);
  char tail = 0;
  if (std::sscanf(s.c_str(), "%lf,%lf,%lf%c", &v.x, &v.y, &v.z, &tail) != 3 || !std::isfinite(v.x) ||
      !std::isfinite(v.y) || !std::isfinite(v.z))
    source.fail("camera: '" + std::string(key) + "=" + s + "' is not three finite numbers x,y,z");
  return v;
}

}  // namespace

float focus_distance_for(const Camera& camera) { return float(glm::length(camera.look_at - camera.position)); }

Camera parse_camera(std::string_view text, const Camera& base, const InputSource& source) {
  // The scene file's words, and the short aliases older command lines and scripts use.
  struct Key {
    std::string_view name, alias;
  };
  static constexpr Key keys[] = {{"position", "pos"}, {"look_at", "at"}, {"up", ""}, {"fov_degrees", "fov"}};
  Camera c = base;
  std::string_view given[std::size(keys)] = {};  // the spelling each key came as, to refuse it twice
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(';', start), text.size());
    const std::string_view part = text.substr(start, end - start);
    start = end + 1;
    if (part.empty()) continue;
    const std::size_t eq = part.find('=');
    if (eq == std::string_view::npos) source.fail("camera: '" + std::string(part) + "' has no '='");
    const std::string_view key = part.substr(0, eq), value = part.substr(eq + 1);
    std::size_t k = 0;
    while (k < std::size(keys) && key != keys[k].name && (keys[k].alias.empty() || key != keys[k].alias)) ++k;
    if (k == std::size(keys))
      source.fail("camera: unknown key '" + std::string(key) + "' (position, look_at, up, fov_degrees; aliases pos, at, fov)");
    if (!given[k].empty())
      source.fail("camera: '" + std::string(key) + "' repeats '" + std::string(given[k]) + "'");
    given[k] = key;
    if (k == 0) c.position = parse_vector(key, value, source);
    else if (k == 1) c.look_at = parse_vector(key, value, source);
    else if (k == 2) c.up = parse_vector(key, value, source);
    else {
      std::string s(value);
      char tail = 0;
      if (std::sscanf(s.c_str(), "%lf%c", &c.fov_degrees, &tail) != 1)
        source.fail("camera: '" + std::string(key) + "=" + s + "' is not a number of degrees");
    }
  }
  if (const std::string wrong = c.problem(); !wrong.empty()) source.fail(wrong);
  return c;
}

Camera package_camera(const format::Package& package) {
  const auto scene = package.records<format::SectionKind::scene>();
  if (scene.empty()) return {};
  const Camera c = camera_from_scene(scene[0]);
  c.check();
  return c;
}

}  // namespace nano::render
