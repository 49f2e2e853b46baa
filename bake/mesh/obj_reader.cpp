// Wavefront OBJ: the geometry statements v, vt, vn and f (or the old fo); every other statement
// (o, g, s, usemtl, mtllib, l, p, curves and surfaces) says nothing about the polygon surface and
// is skipped, so is anything after '#'. A line ending in '\' goes on on the next line.
#include <array>

#include "bake/mesh/mesh_parse.hpp"
#include "bake/mesh/polygon_soup.hpp"
#include "common/error.hpp"

namespace nano::mesh {

namespace {

class ObjReader {
public:
  ObjReader(std::string_view bytes, const std::string& file)
      : file_(file), lines_(bytes, {.comment = '#', .continuation = true}) {}

  PolygonSoup read() {
    while (lines_.next(tokens_)) {
      const std::string_view keyword = tokens_[0];
      if (keyword == "v") {
        soup_.add_position(numbers<3>(3, "a vertex needs x, y and z"), lines_.line());
      } else if (keyword == "vt") {
        soup_.uvs.push_back(numbers<2>(1, "a texture coordinate needs at least u"));  // v defaults to 0
      } else if (keyword == "vn") {
        soup_.normals.push_back(numbers<3>(3, "a normal needs x, y and z"));
      } else if (keyword == "f" || keyword == "fo") {
        for (std::size_t t = 1; t < tokens_.size(); ++t) soup_.corners.push_back(corner(tokens_[t]));
        soup_.end_face(lines_.line());
      }
    }
    return std::move(soup_);
  }

private:
  [[noreturn]] void fail(const std::string& rule) const { throw InputError(file_, parse::at_line(lines_.line()), rule); }

  // The statement's first N numbers (at least `required` of them, the rest 0); more are
  // allowed (a w, or the vertex colours some writers append).
  template <int N>
  glm::vec<N, double> numbers(std::size_t required, const char* rule) const {
    if (tokens_.size() - 1 < required) fail(rule);
    glm::vec<N, double> values(0.0);
    for (int k = 0; k < N && std::size_t(k) + 1 < tokens_.size(); ++k) {
      const auto value = parse::to_double(tokens_[k + 1]);
      if (!value) fail("'" + std::string(tokens_[k + 1]) + "' is not a number");
      values[k] = *value;
    }
    return values;
  }

  // "v", "v/vt", "v//vn" or "v/vt/vn"; 1-based, or negative to count back from the last one read.
  PolygonSoup::Corner corner(std::string_view token) const {
    std::array<std::string_view, 3> parts;
    std::size_t count = 0;
    for (std::size_t start = 0;;) {
      const std::size_t slash = token.find('/', start);
      if (count == parts.size()) fail("face corner '" + std::string(token) + "' has more than three indices");
      parts[count++] = token.substr(start, slash == std::string_view::npos ? std::string_view::npos : slash - start);
      if (slash == std::string_view::npos) break;
      start = slash + 1;
    }
    PolygonSoup::Corner corner;
    corner.position = index(parts[0], soup_.positions.size(), "vertex", token);
    if (count > 1 && !parts[1].empty()) corner.uv = index(parts[1], soup_.uvs.size(), "texture coordinate", token);
    if (count > 2) corner.normal = index(parts[2], soup_.normals.size(), "normal", token);
    return corner;
  }

  std::int64_t index(std::string_view text, std::size_t read_so_far, const char* what, std::string_view token) const {
    const auto value = parse::to_int(text);
    if (!value) fail("face corner '" + std::string(token) + "' is not of the form v, v/vt, v//vn or v/vt/vn");
    if (*value == 0) fail("face corner '" + std::string(token) + "': OBJ indices start at 1");
    if (*value > 0) return *value - 1;  // a missing one is the soup assembly's to report, with the face
    const std::int64_t resolved = static_cast<std::int64_t>(read_so_far) + *value;
    if (resolved < 0)
      fail("face corner '" + std::string(token) + "' counts back past the first " + what + " (" +
           std::to_string(read_so_far) + " so far)");
    return resolved;
  }

  const std::string& file_;
  parse::LineReader lines_;
  std::vector<std::string_view> tokens_;
  PolygonSoup soup_;
};

}  // namespace

PolygonSoup read_obj_soup(std::string_view bytes, const std::string& file) { return ObjReader(bytes, file).read(); }

}  // namespace nano::mesh
