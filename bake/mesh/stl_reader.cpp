// STL, ASCII (solid / facet normal / outer loop / vertex / endloop / endfacet / endsolid) or binary
// (80-byte header, a little-endian triangle count, 50 bytes per triangle). Many binary writers
// start their header with "solid" too, so the size decides first: a file of exactly 84 + 50·n
// bytes is binary. Facet normals are not kept: they are per face, often zero, and the proxy mesh wants
// vertex normals, which the assembly computes. Every facet has corners of its own; the assembly
// welds them by position.
#include <cctype>

#include "bake/mesh/mesh_parse.hpp"
#include "bake/mesh/polygon_soup.hpp"
#include "common/error.hpp"

namespace nano::mesh {

namespace {

constexpr std::size_t kHeaderBytes = 80 + 4;
constexpr std::size_t kTriangleBytes = 50;

bool same_word(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (std::tolower(static_cast<unsigned char>(a[k])) != b[k]) return false;
  return true;
}

void add_corner(PolygonSoup& soup, const glm::dvec3& p, std::size_t line) {
  soup.corners.push_back({.position = static_cast<std::int64_t>(soup.positions.size())});
  soup.add_position(p, line);
}

PolygonSoup read_binary(std::string_view bytes, std::size_t triangles) {
  PolygonSoup soup;
  soup.positions.reserve(3 * triangles);
  for (std::size_t t = 0; t < triangles; ++t) {
    const auto* record = reinterpret_cast<const unsigned char*>(bytes.data() + kHeaderBytes + t * kTriangleBytes);
    for (int c = 0; c < 3; ++c) {
      const unsigned char* xyz = record + 12 * (c + 1);  // after the facet normal
      add_corner(soup, {parse::load<float>(xyz, false), parse::load<float>(xyz + 4, false), parse::load<float>(xyz + 8, false)}, 0);
    }
    soup.end_face();
  }
  return soup;
}

class AsciiStlReader {
public:
  AsciiStlReader(std::string_view bytes, const std::string& file) : file_(file), tokens_(bytes) {}

  PolygonSoup read() {
    while (const auto token = tokens_.next()) {
      if (same_word(*token, "solid") || same_word(*token, "endsolid")) {
        tokens_.rest_of_line();  // the solid's name
      } else if (same_word(*token, "facet")) {
        read_facet();
      } else {
        fail("'" + std::string(*token) + "' where a facet or endsolid should be");
      }
    }
    return std::move(soup_);
  }

private:
  [[noreturn]] void fail(const std::string& rule) const { throw InputError(file_, tokens_.where(), rule); }

  std::string_view next(const char* expected) {
    const auto token = tokens_.next();
    if (!token) fail(std::string("the file ends where '") + expected + "' should be");
    return *token;
  }
  void expect(const char* word) {
    if (const std::string_view token = next(word); !same_word(token, word))
      fail("'" + std::string(token) + "' where '" + word + "' should be");
  }

  void read_facet() {
    const std::size_t line = tokens_.line();
    expect("normal");
    for (int k = 0; k < 3; ++k) next("a normal component");  // not kept (see above); some writers put nan here
    expect("outer");
    expect("loop");
    for (std::string_view token = next("vertex"); !same_word(token, "endloop"); token = next("endloop")) {
      if (!same_word(token, "vertex")) fail("'" + std::string(token) + "' where 'vertex' or 'endloop' should be");
      glm::dvec3 p;
      for (int k = 0; k < 3; ++k) {
        const std::string_view text = next("a vertex coordinate");
        const auto value = parse::to_double(text);
        if (!value) fail("'" + std::string(text) + "' is not a number");
        p[k] = *value;
      }
      add_corner(soup_, p, tokens_.line());
    }
    expect("endfacet");
    soup_.end_face(line);
  }

  const std::string& file_;
  parse::TokenReader tokens_;
  PolygonSoup soup_;
};

bool starts_with_solid(std::string_view bytes) {
  if (bytes.starts_with("\xEF\xBB\xBF")) bytes.remove_prefix(3);  // a UTF-8 byte order mark (the token reader skips it too)
  const std::size_t start = bytes.find_first_not_of(" \t\r\n");
  if (start == std::string_view::npos) return false;
  const std::string_view word = bytes.substr(start, 5);
  return same_word(word, "solid") && (bytes.size() == start + 5 || std::isspace(static_cast<unsigned char>(bytes[start + 5])));
}

}  // namespace

PolygonSoup read_stl_soup(std::string_view bytes, const std::string& file) {
  std::uint64_t expected = 0;
  if (bytes.size() >= kHeaderBytes) {
    const std::uint32_t triangles = parse::load<std::uint32_t>(reinterpret_cast<const unsigned char*>(bytes.data() + 80), false);
    expected = kHeaderBytes + kTriangleBytes * static_cast<std::uint64_t>(triangles);
    if (bytes.size() == expected) return read_binary(bytes, triangles);
  }
  // A binary header may say "solid" too; the count and the records of a binary file all but
  // always hold a zero byte, text never does.
  if (starts_with_solid(bytes) && bytes.find('\0') == std::string_view::npos) return AsciiStlReader(bytes, file).read();
  if (bytes.size() < kHeaderBytes)
    throw InputError(file, "", "not an STL file: neither ASCII (starting with 'solid') nor long enough for a binary header (84 bytes)");
  throw InputError(file, "", "binary STL header says " + std::to_string((expected - kHeaderBytes) / kTriangleBytes) +
                                 " triangles, so " + std::to_string(expected) + " bytes, but the file has " +
                                 std::to_string(bytes.size()) + " (truncated, or not an STL file)");
}

}  // namespace nano::mesh
