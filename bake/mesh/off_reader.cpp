// Geomview's Object File Format: a header keyword [ST][C][N]OFF, then the counts (vertices, faces
// and an optional edge count nobody checks), the vertices (x y z [nx ny nz] [colour] [s t]), then
// the faces (n i0 .. in-1 [colour]). Numbers are whitespace-separated anywhere, '#' comments and
// blank lines may come anywhere (tools such as CGAL's put comments before the keyword), and a
// colour runs to the end of its line, which is the only reason line breaks matter.
#include <algorithm>

#include "bake/mesh/mesh_parse.hpp"
#include "bake/mesh/polygon_soup.hpp"
#include "common/error.hpp"

namespace nano::mesh {

namespace {

struct OffHeader {
  bool uvs = false, colours = false, normals = false;
};

class OffReader {
public:
  OffReader(std::string_view bytes, const std::string& file) : file_(file), size_(bytes.size()), tokens_(bytes, {.comment = '#'}) {}

  PolygonSoup read() {
    std::string_view first = expect_token("the file is empty");
    // The keyword may be left out: a file starting with its counts is plain OFF.
    if (!parse::to_int(first)) {
      header_ = keyword(first);
      first = expect_token("the file ends before the vertex and face counts");
    }
    const std::int64_t vertices = count(first, "vertex count");
    const std::int64_t faces = count(expect_token("the file ends before the face count"), "face count");
    tokens_.rest_of_line();  // the edge count, if given
    // Each vertex takes at least 3 numbers and each face 4, each number with a separator: a
    // promise of more than that must not make us allocate for it.
    const auto bytes = static_cast<std::uint64_t>(size_);
    if (static_cast<std::uint64_t>(vertices) > bytes || static_cast<std::uint64_t>(faces) > bytes ||
        2 * (3 * static_cast<std::uint64_t>(vertices) + 4 * static_cast<std::uint64_t>(faces)) > bytes + 1)
      fail(std::to_string(vertices) + " vertices and " + std::to_string(faces) + " faces cannot fit in a file of " +
           std::to_string(size_) + " bytes");
    soup_.positions.reserve(static_cast<std::size_t>(vertices));
    for (std::int64_t v = 0; v < vertices; ++v) read_vertex(v, vertices);
    for (std::int64_t f = 0; f < faces; ++f) read_face(f, faces);
    return std::move(soup_);
  }

private:
  [[noreturn]] void fail(const std::string& rule) const { throw InputError(file_, tokens_.where(), rule); }

  std::string_view expect_token(const std::string& rule_at_end) {
    const auto token = tokens_.next();
    if (!token) fail(rule_at_end);
    return *token;
  }

  OffHeader keyword(std::string_view token) const {
    if (!token.ends_with("OFF"))
      fail("not an OFF file: '" + std::string(token) + "' is neither a header keyword such as OFF, NOFF, COFF, STOFF nor a count");
    OffHeader header;
    for (std::string_view prefix = token.substr(0, token.size() - 3); !prefix.empty();) {
      if (prefix.starts_with("ST") && !header.uvs) {
        header.uvs = true;
        prefix.remove_prefix(2);
      } else if (prefix[0] == 'C' && !header.colours) {
        header.colours = true;
        prefix.remove_prefix(1);
      } else if (prefix[0] == 'N' && !header.normals) {
        header.normals = true;
        prefix.remove_prefix(1);
      } else if (prefix[0] == '4' || prefix[0] == 'n') {
        fail("'" + std::string(token) + "': 4D and n-dimensional OFF are not supported (3D only)");
      } else {
        fail("'" + std::string(token) + "' is not an OFF header keyword ([ST][C][N]OFF)");
      }
    }
    return header;
  }

  std::int64_t count(std::string_view token, const char* what) const {
    if (token == "BINARY") fail("binary OFF is not supported (ASCII only)");
    const auto value = parse::to_int(token);
    if (!value) fail(std::string(what) + " '" + std::string(token) + "' is not a whole number");
    if (*value < 0) fail(std::string(what) + " is negative");
    return *value;
  }

  double number(std::string_view token) const {
    const auto value = parse::to_double(token);
    if (!value) fail("'" + std::string(token) + "' is not a number");
    return *value;
  }

  double next_number(const std::string& what, std::int64_t index, std::int64_t total) {
    return number(expect_token("the file ends in " + what + " " + std::to_string(index) + " of " + std::to_string(total)));
  }

  void read_vertex(std::int64_t v, std::int64_t total) {
    const auto coordinate = [&] { return next_number("vertex", v, total); };
    glm::dvec3 p;
    p.x = coordinate();
    const std::size_t line = tokens_.line();
    p.y = coordinate();
    p.z = coordinate();
    soup_.add_position(p, line);
    if (header_.normals) {
      glm::dvec3 n;
      n.x = coordinate();
      n.y = coordinate();
      n.z = coordinate();
      soup_.normals.push_back(n);
    }
    glm::dvec2 uv(0.0);
    if (header_.colours && header_.uvs) {
      // Colours have 1 to 4 components: the texture coordinates are the last two numbers.
      const std::vector<std::string_view> rest = tokens_.rest_of_line();
      if (rest.size() < 2) fail("vertex " + std::to_string(v) + " has no texture coordinates after its colour");
      uv = {number(rest[rest.size() - 2]), number(rest.back())};
    } else if (header_.colours) {
      tokens_.rest_of_line();
    } else if (header_.uvs) {
      uv.x = coordinate();
      uv.y = coordinate();
    }
    if (header_.uvs) soup_.uvs.push_back(uv);
  }

  void read_face(std::int64_t f, std::int64_t total) {
    const auto token = [&] { return expect_token("the file ends in face " + std::to_string(f) + " of " + std::to_string(total)); };
    const std::int64_t n = count(token(), "corner count");
    const std::size_t line = tokens_.line();
    if (static_cast<std::uint64_t>(n) > size_) fail("face " + std::to_string(f) + " has more corners than the file has bytes");
    for (std::int64_t k = 0; k < n; ++k) {
      const std::string_view text = token();
      const auto index = parse::to_int(text);
      if (!index) fail("vertex index '" + std::string(text) + "' is not a whole number");
      // A per-vertex UV or normal has the vertex's own index.
      soup_.corners.push_back({.position = *index,
                               .uv = header_.uvs ? *index : -1,
                               .normal = header_.normals ? *index : -1});
    }
    tokens_.rest_of_line();  // the face's colour
    soup_.end_face(line);
  }

  const std::string& file_;
  std::size_t size_;
  parse::TokenReader tokens_;
  OffHeader header_;
  PolygonSoup soup_;
};

}  // namespace

PolygonSoup read_off_soup(std::string_view bytes, const std::string& file) { return OffReader(bytes, file).read(); }

}  // namespace nano::mesh
