// PLY (Turk's polygon file format) in all three encodings: ascii, binary_little_endian and
// binary_big_endian. The header declares elements and their properties; from "vertex" we take x, y,
// z, optionally nx, ny, nz and a UV pair (u v, s t, texture_u texture_v or texture_s texture_t),
// from "face" the vertex_indices (or vertex_index) list and MeshLab's per-corner "texcoord" list.
// Every other property and element is read past by its declared types, so colours, confidences or
// an edge list cannot throw the reading out of step.
#include <cmath>
#include <optional>

#include "bake/mesh/mesh_parse.hpp"
#include "bake/mesh/number_text.hpp"
#include "bake/mesh/polygon_soup.hpp"
#include "common/error.hpp"

namespace nano::mesh {

namespace {

enum class Scalar { i8, u8, i16, u16, i32, u32, f32, f64 };

std::optional<Scalar> scalar_named(std::string_view name) {
  struct Name {
    std::string_view old_name, sized_name;
    Scalar type;
  };
  static constexpr Name kNames[] = {
      {"char", "int8", Scalar::i8},     {"uchar", "uint8", Scalar::u8},   {"short", "int16", Scalar::i16},
      {"ushort", "uint16", Scalar::u16}, {"int", "int32", Scalar::i32},   {"uint", "uint32", Scalar::u32},
      {"float", "float32", Scalar::f32}, {"double", "float64", Scalar::f64}};
  for (const Name& n : kNames)
    if (name == n.old_name || name == n.sized_name) return n.type;
  return std::nullopt;
}

std::size_t size_of(Scalar type) {
  switch (type) {
    case Scalar::i8: case Scalar::u8: return 1;
    case Scalar::i16: case Scalar::u16: return 2;
    case Scalar::i32: case Scalar::u32: case Scalar::f32: return 4;
    case Scalar::f64: return 8;
  }
  return 1;
}

bool is_float(Scalar type) { return type == Scalar::f32 || type == Scalar::f64; }

std::optional<double> ascii_number(std::string_view token, bool whole) {
  if (!whole) return parse::to_double(token);
  if (const auto i = parse::to_int(token)) return static_cast<double>(*i);
  return std::nullopt;
}

// What a property feeds; vertex slots are indices into a vertex's values, the face roles are lists.
enum Role : int { kSkipped = -1, kX, kY, kZ, kNx, kNy, kNz, kU, kV, kVertexSlots, kIndices = 0, kTexcoords = 1 };

struct Property {
  std::string name;
  Scalar type = Scalar::f32;           // of the value, or of a list's items
  std::optional<Scalar> count_type;    // lists only
  int role = kSkipped;
};

struct Element {
  std::string name;
  std::int64_t count = 0;
  std::size_t line = 0;  // of its declaration in the header
  std::vector<Property> properties;
};

enum class Encoding { ascii, little_endian, big_endian };

class PlyReader {
public:
  PlyReader(std::string_view bytes, const std::string& file) : file_(file), bytes_(bytes) {}

  PolygonSoup read() {
    read_header();
    for (const Element& element : elements_) {
      check_fits(element);
      if (element.name == "vertex") {
        soup_.positions.reserve(static_cast<std::size_t>(element.count));
        soup_.position_lines.reserve(static_cast<std::size_t>(element.count));
      }
      for (std::int64_t entry = 0; entry < element.count && !element.properties.empty(); ++entry) {
        if (&element == vertex_) read_vertex(element, entry);
        else if (&element == face_) read_face(element, entry);
        else for (const Property& property : element.properties) read_property(element, entry, property, nullptr);
      }
    }
    soup_.uvs.insert(soup_.uvs.end(), corner_uvs_.begin(), corner_uvs_.end());
    return std::move(soup_);
  }

private:
  [[noreturn]] void fail(const std::string& where, const std::string& rule) const { throw InputError(file_, where, rule); }

  // ---- header ----

  void read_header() {
    parse::LineReader lines(bytes_);
    std::vector<std::string_view> tokens;
    if (!lines.next(tokens) || tokens.size() != 1 || tokens[0] != "ply")
      fail("", "not a PLY file (its first line is not 'ply')");
    std::optional<Encoding> encoding;
    const auto where = [&] { return parse::at_line(lines.line()); };
    while (true) {
      if (!lines.next(tokens)) fail("", "the header has no end_header line");
      const std::string_view keyword = tokens[0];
      if (keyword == "end_header") break;
      if (keyword == "comment" || keyword == "obj_info") continue;
      if (keyword == "format") {
        if (tokens.size() < 2) fail(where(), "format line without an encoding");
        if (tokens[1] == "ascii") encoding = Encoding::ascii;
        else if (tokens[1] == "binary_little_endian") encoding = Encoding::little_endian;
        else if (tokens[1] == "binary_big_endian") encoding = Encoding::big_endian;
        else fail(where(), "unknown encoding '" + std::string(tokens[1]) + "' (ascii, binary_little_endian or binary_big_endian)");
      } else if (keyword == "element") {
        if (tokens.size() != 3) fail(where(), "an element line is 'element NAME COUNT'");
        const auto count = parse::to_int(tokens[2]);
        if (!count || *count < 0)
          fail(where(), "element count '" + std::string(tokens[2]) + "' is not a whole number of at least 0");
        elements_.push_back({std::string(tokens[1]), *count, lines.line(), {}});
      } else if (keyword == "property") {
        if (elements_.empty()) fail(where(), "a property before any element");
        elements_.back().properties.push_back(property(tokens, where()));
      } else {
        fail(where(), "unknown header line '" + std::string(keyword) + "'");
      }
    }
    if (!encoding) fail("", "the header has no format line");
    body_ = lines.offset();
    if (*encoding == Encoding::ascii) ascii_.emplace(bytes_.substr(body_), parse::LineReader::Options{.first_line = lines.line() + 1});
    big_endian_ = *encoding == Encoding::big_endian;
    pos_ = body_;
    assign_roles();
  }

  Property property(const std::vector<std::string_view>& tokens, const std::string& where) const {
    const bool list = tokens.size() == 5 && tokens[1] == "list";
    if (!list && tokens.size() != 3)
      fail(where, "a property line is 'property TYPE NAME' or 'property list COUNT_TYPE ITEM_TYPE NAME'");
    const auto type_of = [&](std::string_view name) {
      const auto type = scalar_named(name);
      if (!type) fail(where, "unknown property type '" + std::string(name) + "'");
      return *type;
    };
    Property p;
    p.name = tokens.back();
    p.type = type_of(tokens[tokens.size() - 2]);
    if (list) {
      p.count_type = type_of(tokens[2]);
      if (is_float(*p.count_type)) fail(where, "a list count must have an integer type");
    }
    return p;
  }

  Property* find(Element& element, std::string_view name) {
    for (Property& p : element.properties)
      if (p.name == name) return &p;
    return nullptr;
  }

  void assign_roles() {
    for (Element& element : elements_) {
      if (element.name == "vertex" && !vertex_) vertex_ = &element;
      else if (element.name == "face" && !face_) face_ = &element;
      else if (element.name == "vertex" || element.name == "face")
        fail(parse::at_line(element.line), "a second '" + element.name + "' element");
    }
    if (vertex_) {
      Element& v = *vertex_;
      // A role is taken only by a scalar, and only when its whole group (x y z, a normal, a UV pair) is there.
      const auto take = [&](std::initializer_list<std::pair<const char*, int>> group) {
        std::vector<Property*> found;
        for (const auto& [name, role] : group) {
          Property* p = find(v, name);
          if (!p || p->count_type) return false;
          found.push_back(p);
        }
        for (std::size_t k = 0; k < found.size(); ++k) found[k]->role = (group.begin() + k)->second;
        return true;
      };
      if (!take({{"x", kX}, {"y", kY}, {"z", kZ}}))
        fail(parse::at_line(v.line), "the vertex element has no x, y and z properties (scalars)");
      vertex_normals_ = take({{"nx", kNx}, {"ny", kNy}, {"nz", kNz}});
      vertex_uvs_ = take({{"u", kU}, {"v", kV}}) || take({{"s", kU}, {"t", kV}}) ||
                    take({{"texture_u", kU}, {"texture_v", kV}}) || take({{"texture_s", kU}, {"texture_t", kV}});
    }
    if (face_) {
      Property* indices = find(*face_, "vertex_indices");
      if (!indices) indices = find(*face_, "vertex_index");
      if (!indices || !indices->count_type)
        fail(parse::at_line(face_->line), "the face element has no vertex_indices list");
      indices->role = kIndices;
      if (Property* texcoords = find(*face_, "texcoord"); texcoords && texcoords->count_type) texcoords->role = kTexcoords;
      // Per-corner UVs come after the per-vertex ones, which are numbered as the vertices.
      corner_uv_base_ = vertex_uvs_ ? static_cast<std::size_t>(vertex_->count) : 0;
    }
  }

  // ---- body ----

  std::string entry_place(const Element& element, std::int64_t entry) const {
    const std::string s = element.name + " " + std::to_string(entry);
    return ascii_ && ascii_->line() > 0 ? ascii_->where() + ", " + s : s;
  }

  // A file that declares more entries than it could hold is refused before anything is allocated
  // for them: in binary every entry takes at least its scalars and list counts, in ASCII at least
  // one digit and a separator per value.
  void check_fits(const Element& element) const {
    std::uint64_t least = 0;
    for (const Property& p : element.properties) least += ascii_ ? 2 : size_of(p.count_type.value_or(p.type));
    const std::uint64_t left = ascii_ ? bytes_.size() - body_ + 1 : bytes_.size() - pos_;
    if (least > 0 && static_cast<std::uint64_t>(element.count) > left / least)
      fail(parse::at_line(element.line), "element '" + element.name + "' declares " + std::to_string(element.count) +
                                              " entries, more than the " + std::to_string(left) +
                                              " bytes after the header can hold");
  }

  // One value, as a double (exact for every PLY type).
  double value(Scalar type, const Element& element, std::int64_t entry) {
    if (ascii_) {
      const auto token = ascii_->next();
      if (!token) fail(entry_place(element, entry), "the file ends inside this entry");
      const std::optional<double> v = ascii_number(*token, !is_float(type));
      if (!v) fail(entry_place(element, entry), "'" + std::string(*token) + "' is not " + (is_float(type) ? "a number" : "a whole number"));
      return *v;
    }
    const std::size_t size = size_of(type);
    if (bytes_.size() - pos_ < size) fail(entry_place(element, entry), "the file ends inside this entry (truncated)");
    const auto* at = reinterpret_cast<const unsigned char*>(bytes_.data() + pos_);
    pos_ += size;
    switch (type) {
      case Scalar::i8: return parse::load<std::int8_t>(at, big_endian_);
      case Scalar::u8: return parse::load<std::uint8_t>(at, big_endian_);
      case Scalar::i16: return parse::load<std::int16_t>(at, big_endian_);
      case Scalar::u16: return parse::load<std::uint16_t>(at, big_endian_);
      case Scalar::i32: return parse::load<std::int32_t>(at, big_endian_);
      case Scalar::u32: return parse::load<std::uint32_t>(at, big_endian_);
      case Scalar::f32: return parse::load<float>(at, big_endian_);
      case Scalar::f64: return parse::load<double>(at, big_endian_);
    }
    return 0.0;
  }

  // Reads one property of one entry; a list's items go to `items` (nullptr: read past them).
  void read_property(const Element& element, std::int64_t entry, const Property& p, std::vector<double>* items) {
    if (!p.count_type) {
      const double v = value(p.type, element, entry);
      if (items) items->push_back(v);
      return;
    }
    const double n = value(*p.count_type, element, entry);
    if (n < 0) fail(entry_place(element, entry), "list '" + p.name + "' has a negative length");
    const auto count = static_cast<std::uint64_t>(n);
    const std::uint64_t left = ascii_ ? bytes_.size() : bytes_.size() - pos_;
    if (count > left / size_of(p.type))
      fail(entry_place(element, entry), "list '" + p.name + "' of " + std::to_string(count) + " items runs past the end of the file (truncated)");
    if (!items && !ascii_) {
      pos_ += count * size_of(p.type);
      return;
    }
    for (std::uint64_t k = 0; k < count; ++k) {
      const double v = value(p.type, element, entry);
      if (items) items->push_back(v);
    }
  }

  void read_vertex(const Element& element, std::int64_t entry) {
    double slots[kVertexSlots] = {};
    for (const Property& p : element.properties) {
      if (p.role == kSkipped) {
        read_property(element, entry, p, nullptr);
      } else {
        slots[p.role] = value(p.type, element, entry);
      }
    }
    soup_.add_position({slots[kX], slots[kY], slots[kZ]}, ascii_ ? ascii_->line() : 0);
    if (vertex_normals_) soup_.normals.push_back({slots[kNx], slots[kNy], slots[kNz]});
    if (vertex_uvs_) soup_.uvs.push_back({slots[kU], slots[kV]});
  }

  void read_face(const Element& element, std::int64_t entry) {
    indices_.clear();
    texcoords_.clear();
    for (const Property& p : element.properties)
      read_property(element, entry, p, p.role == kIndices ? &indices_ : p.role == kTexcoords ? &texcoords_ : nullptr);
    if (!texcoords_.empty() && texcoords_.size() != 2 * indices_.size())
      fail(entry_place(element, entry), "texcoord list has " + std::to_string(texcoords_.size()) + " numbers for " +
                                            std::to_string(indices_.size()) + " corners");
    for (std::size_t k = 0; k < indices_.size(); ++k) {
      const double index = indices_[k];
      // Checked before the cast, which is undefined for NaN and for values no int64 holds (a float
      // or double index list, or an ASCII index of 2^63 or more, can say anything).
      if (!std::isfinite(index) || index != std::trunc(index))
        fail(entry_place(element, entry), "vertex index " + number_text("%.17g", index) + " is not a whole number");
      if (!(std::abs(index) < 0x1p63))
        fail(entry_place(element, entry), "vertex index " + number_text("%.17g", index) + " references a vertex that does not exist");
      PolygonSoup::Corner corner{.position = static_cast<std::int64_t>(index)};
      if (vertex_normals_) corner.normal = corner.position;
      if (!texcoords_.empty()) {
        corner.uv = static_cast<std::int64_t>(corner_uv_base_ + corner_uvs_.size());
        corner_uvs_.push_back({texcoords_[2 * k], texcoords_[2 * k + 1]});
      } else if (vertex_uvs_) {
        corner.uv = corner.position;
      }
      soup_.corners.push_back(corner);
    }
    soup_.end_face(ascii_ ? ascii_->line() : 0);
  }

  const std::string& file_;
  std::string_view bytes_;
  std::vector<Element> elements_;
  Element* vertex_ = nullptr;
  Element* face_ = nullptr;
  bool vertex_normals_ = false, vertex_uvs_ = false;
  std::size_t corner_uv_base_ = 0;
  std::size_t body_ = 0;               // where the data start
  std::optional<parse::TokenReader> ascii_;
  bool big_endian_ = false;
  std::size_t pos_ = 0;                // binary: the next byte to read
  std::vector<double> indices_, texcoords_;
  std::vector<glm::dvec2> corner_uvs_;
  PolygonSoup soup_;
};

}  // namespace

PolygonSoup read_ply_soup(std::string_view bytes, const std::string& file) { return PlyReader(bytes, file).read(); }

}  // namespace nano::mesh
