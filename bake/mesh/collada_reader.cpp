// Collada (.dae), the geometry format of cellPACK's database, read through Assimp: the only
// translation unit of bake/ that includes Assimp. Assimp parses the XML and resolves sources,
// accessors and node instances; what it hands back becomes a polygon soup like every other
// format's, so polygon_soup.cpp checks, triangulates and welds it by mesh_reader.hpp's rules.
//
// What Assimp is allowed to do is kept narrow:
// - only its Collada importer runs (the ".dae" hint names it; no other importer is asked), with
//   no post-processing steps (our soup triangulates and welds) and no logger (it prints nothing);
// - the bytes are checked first (check_collada_declarations): Assimp sizes its arrays by the
//   counts a file declares before reading what they count, so a small file declaring a billion
//   of something would make it allocate for them all;
// - the root node's transform is not applied: the root is the <visual_scene>, which has no
//   transform in Collada, and Assimp 5.2 puts the file's <unit meter> scale and <up_axis>
//   rotation there. Coordinates are therefore taken as written, in the scene's "units", and every
//   node below the root is applied (translate, rotate, scale, matrix), as cellPACK reads them
//   (mesh_reader.hpp says why).
#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/scene.h>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "bake/mesh/polygon_soup.hpp"
#include "common/error.hpp"

namespace nano::mesh {

namespace {

// ---- what a Collada file declares before Assimp allocates for it ----

// A proxy mesh is low-poly (the baker takes at most 4 million triangles: scene_feasibility.hpp,
// mesh_check.hpp); a Collada text of that many triangles with normals and UVs is some 450 MB.
constexpr std::size_t kMaxColladaBytes = std::size_t{512} << 20;
constexpr std::uint64_t kMaxColladaFaces = std::uint64_t{1} << 22;
// Assimp reserves 8 bytes per declared corner and input of a <triangles>, <lines> or <polylist>
// before reading its <p>: at most 3 corners a face over the faces above, and 32 interleaved inputs
// (a Collada corner rarely has more than position, normal, two UV sets and a colour).
constexpr std::uint64_t kMaxColladaCorners = 3 * kMaxColladaFaces;
constexpr std::uint64_t kMaxColladaInputOffset = 31;

struct Tag {
  std::string_view name;        // without a namespace prefix
  std::string_view attributes;  // the text between the name and '>'
  std::size_t end = 0;          // just past the '>'
};

// The start tag at `at` (text[at] == '<'), or nullopt for a comment, declaration, processing
// instruction or end tag (whose end is then returned through `skip_to`).
std::optional<Tag> start_tag(std::string_view text, std::size_t at, std::size_t& skip_to) {
  const auto skip_past = [&](std::string_view closer) {
    const std::size_t close = text.find(closer, at);
    skip_to = close == std::string_view::npos ? text.size() : close + closer.size();
    return std::nullopt;
  };
  const std::string_view rest = text.substr(at);
  if (rest.starts_with("<!--")) return skip_past("-->");
  if (rest.starts_with("<![CDATA[")) return skip_past("]]>");
  if (rest.starts_with("<?")) return skip_past("?>");
  if (rest.starts_with("<!") || rest.starts_with("</")) return skip_past(">");
  const std::size_t close = text.find('>', at);
  Tag tag;
  tag.end = close == std::string_view::npos ? text.size() : close + 1;
  const std::string_view inside = text.substr(at + 1, tag.end - at - 1);
  const std::size_t name_end = std::min(inside.find_first_of(" \t\r\n/>"), inside.size());
  tag.name = inside.substr(0, name_end);
  if (const std::size_t colon = tag.name.rfind(':'); colon != std::string_view::npos) tag.name.remove_prefix(colon + 1);
  tag.attributes = inside.substr(name_end);
  skip_to = tag.end;
  return tag;
}

// The value of attribute `name` in a start tag's attribute text ("name = 'v'" or name="v").
std::optional<std::string_view> attribute(std::string_view attributes, std::string_view name) {
  for (std::size_t at = attributes.find(name); at != std::string_view::npos; at = attributes.find(name, at + 1)) {
    if (at == 0 || !std::isspace(static_cast<unsigned char>(attributes[at - 1]))) continue;
    std::size_t k = attributes.find_first_not_of(" \t\r\n", at + name.size());
    if (k == std::string_view::npos || attributes[k] != '=') continue;
    k = attributes.find_first_not_of(" \t\r\n", k + 1);
    if (k == std::string_view::npos || (attributes[k] != '"' && attributes[k] != '\'')) continue;
    const std::size_t close = attributes.find(attributes[k], k + 1);
    if (close == std::string_view::npos) return attributes.substr(k + 1);
    return attributes.substr(k + 1, close - k - 1);
  }
  return std::nullopt;
}

class ColladaDeclarations {
public:
  ColladaDeclarations(std::string_view text, const std::string& file) : text_(text), file_(file) {}

  // Refuses what could make Assimp allocate far more than the file holds, or read other than XML.
  void check() {
    if (text_.empty()) fail("", "the file is empty");
    if (text_.size() > kMaxColladaBytes)
      fail("", "the file has " + std::to_string(text_.size()) + " bytes, more than this reader takes (" +
                   std::to_string(kMaxColladaBytes) + ": a proxy mesh is low-poly)");
    // XML 1.0 text holds no control characters but tab, line feed and carriage return; refusing
    // them also keeps Assimp from opening the bytes as a zipped Collada (.zae) archive.
    for (std::size_t k = 0; k < text_.size(); ++k) {
      const auto ch = static_cast<unsigned char>(text_[k]);
      if (ch < 0x20 && ch != '\t' && ch != '\n' && ch != '\r')
        fail("byte " + std::to_string(k), "not XML text (a control character; a zipped .zae is not read)");
    }
    std::size_t corners = 0;
    for (std::size_t at = text_.find('<'), next = 0; at != std::string_view::npos; at = text_.find('<', next)) {
      const std::optional<Tag> tag = start_tag(text_, at, next);
      if (!tag) continue;
      for (const char* name : {"count", "offset", "stride", "set"}) whole_number(*tag, name, text_.size());
      if (tag->name == "input") whole_number(*tag, "offset", kMaxColladaInputOffset);
      if (tag->name == "triangles") corners += 3 * whole_number(*tag, "count", text_.size());
      if (tag->name == "lines") corners += 2 * whole_number(*tag, "count", text_.size());
      if (tag->name == "vcount") corners += vcount_sum(*tag);
      if (tag->name == "p") index_list(*tag);
      if (tag->name == "triangles" || tag->name == "polylist" || tag->name == "polygons") index_lists_match_count(*tag);
      if (corners > kMaxColladaCorners)
        fail(element_place(*tag), "the primitives declare more than " + std::to_string(kMaxColladaCorners) +
                                      " corners (" + std::to_string(kMaxColladaFaces) + " triangles), more than this reader takes");
    }
  }

private:
  [[noreturn]] void fail(const std::string& where, const std::string& rule) const { throw InputError(file_, where, rule); }

  std::string element_place(const Tag& tag) const {
    const std::size_t line = 1 + static_cast<std::size_t>(std::count(text_.begin(), text_.begin() + (tag.name.data() - text_.data()), '\n'));
    return "line " + std::to_string(line) + ", <" + std::string(tag.name) + ">";
  }

  // The attribute as a decimal whole number of at most `largest` (0 when absent). Assimp would
  // read a sign, hexadecimal or an entity too, and wrap what does not fit: such values are refused.
  std::uint64_t whole_number(const Tag& tag, const char* name, std::uint64_t largest) const {
    const std::optional<std::string_view> value = attribute(tag.attributes, name);
    if (!value) return 0;
    std::uint64_t n = 0;
    const auto [end, error] = std::from_chars(value->data(), value->data() + value->size(), n);
    if (value->empty() || error != std::errc() || end != value->data() + value->size())
      fail(element_place(tag), std::string(name) + "=\"" + std::string(*value) + "\" is not a decimal whole number");
    if (n > largest)
      fail(element_place(tag), std::string(name) + "=\"" + std::string(*value) + "\" is more than " +
                                   (largest == text_.size() ? "the file's size" : "this reader takes") + " (at most " +
                                   std::to_string(largest) + ")");
    return n;
  }

  // The text of a <vcount> or <p>, to its end tag. Only digits, signs and blanks: Assimp 5.2
  // reads a <p> until its end and never gets past any other character (a loop that grows its index
  // list until memory runs out), and reads the text of a CDATA section or an entity as well.
  std::string_view index_list(const Tag& tag) const {
    const std::size_t to = std::min(text_.find("</", tag.end), text_.size());
    const std::string_view list = text_.substr(tag.end, to - tag.end);
    if (const std::size_t bad = list.find_first_not_of("0123456789+- \t\r\n"); bad != std::string_view::npos)
      fail(element_place(tag), "holds '" + std::string(1, list[bad]) + "' (an index list holds decimal whole numbers only)");
    return list;
  }

  // Debian's Assimp 5.2 is built with its assertions on, and aborts the process unless a
  // <triangles> or <polylist> of count > 0 has one <p> (none for count 0) and a <polygons> one <p>
  // per polygon: refused here instead.
  void index_lists_match_count(const Tag& tag) const {
    const std::uint64_t count = whole_number(tag, "count", text_.size());
    const bool closed = tag.end >= 2 && text_[tag.end - 2] == '/';
    std::size_t end = closed ? tag.end : text_.size();
    for (std::size_t at = text_.find("</", tag.end); !closed && at != std::string_view::npos; at = text_.find("</", at + 2)) {
      std::string_view name = text_.substr(at + 2, std::min(text_.find('>', at), text_.size()) - at - 2);
      if (const std::size_t colon = name.rfind(':'); colon != std::string_view::npos) name.remove_prefix(colon + 1);
      if (name.substr(0, name.find_first_of(" \t\r\n")) == tag.name) {
        end = at;
        break;
      }
    }
    std::uint64_t lists = 0;
    for (std::size_t at = text_.find('<', tag.end), next = 0; at < end; at = text_.find('<', next)) {
      const std::optional<Tag> inner = start_tag(text_, at, next);
      if (inner && inner->name == "p") {
        ++lists;
        next = std::max(next, std::min(text_.find("</", inner->end) + 1, text_.size()));  // past its text
      }
    }
    const std::uint64_t expected = tag.name == "polygons" ? count : std::min<std::uint64_t>(count, 1);
    if (lists != expected)
      fail(element_place(tag), "count=\"" + std::to_string(count) + "\" with " + std::to_string(lists) + " <p> (" +
                                   std::to_string(expected) + " expected)");
  }

  // The corners a <vcount> declares.
  std::uint64_t vcount_sum(const Tag& tag) const {
    const std::string_view list = index_list(tag);
    std::uint64_t sum = 0;
    for (std::size_t k = list.find_first_not_of(" \t\r\n"); k < list.size(); k = list.find_first_not_of(" \t\r\n", k)) {
      std::uint64_t n = 0;
      const auto [end, error] = std::from_chars(list.data() + k, list.data() + list.size(), n);
      if (error != std::errc() || (end != list.data() + list.size() && !std::isspace(static_cast<unsigned char>(*end))))
        fail(element_place(tag), "holds something that is not a decimal whole number");
      sum += std::min(n, kMaxColladaCorners + 1);
      if (sum > kMaxColladaCorners) return sum;
      k = static_cast<std::size_t>(end - list.data());
    }
    return sum;
  }

  std::string_view text_;
  const std::string& file_;
};

// ---- the scene Assimp builds, as a polygon soup ----

glm::dmat4 to_glm(const aiMatrix4x4& m) {
  glm::dmat4 g(1.0);
  for (int row = 0; row < 4; ++row)
    for (int column = 0; column < 4; ++column) g[column][row] = m[row][column];  // glm is column-major
  return g;
}

// Bit-identical positions get one index, so that a face through one position twice is refused
// as degenerate: Assimp gives every corner a vertex of its own, so the file's indices are gone.
class PositionIndex {
public:
  std::int64_t of(const glm::dvec3& p, PolygonSoup& soup) {
    std::array<std::uint64_t, 3> key;
    std::memcpy(key.data(), &p, sizeof p);
    const auto [it, inserted] = index_.try_emplace(key, static_cast<std::int64_t>(soup.positions.size()));
    if (inserted) soup.add_position(p);
    return it->second;
  }

private:
  struct Hash {
    std::size_t operator()(const std::array<std::uint64_t, 3>& k) const {
      std::uint64_t h = k[0] * 0x9E3779B97F4A7C15ull;
      h = (h ^ (h >> 29) ^ k[1]) * 0xBF58476D1CE4E5B9ull;
      h = (h ^ (h >> 32) ^ k[2]) * 0x94D049BB133111EBull;
      return static_cast<std::size_t>(h ^ (h >> 31));
    }
  };
  std::unordered_map<std::array<std::uint64_t, 3>, std::int64_t, Hash> index_;
};

class SceneSoup {
public:
  SceneSoup(const aiScene& scene, const std::string& file) : scene_(scene), file_(file) {}

  // Every mesh every node places, depth first in the order of the file's nodes; the root's own
  // transform (Assimp's unit scale and up-axis rotation, see the top) is left out.
  PolygonSoup build() {
    std::vector<std::pair<const aiNode*, glm::dmat4>> pending;
    if (const aiNode* root = scene_.mRootNode) {
      add_meshes(*root, glm::dmat4(1.0));
      for (unsigned c = root->mNumChildren; c-- > 0;) pending.emplace_back(root->mChildren[c], glm::dmat4(1.0));
    }
    while (!pending.empty()) {
      const auto [node, parent] = pending.back();
      pending.pop_back();
      const glm::dmat4 placed = parent * to_glm(node->mTransformation);
      add_meshes(*node, placed);
      for (unsigned c = node->mNumChildren; c-- > 0;) pending.emplace_back(node->mChildren[c], placed);
    }
    return std::move(soup_);
  }

private:
  void add_meshes(const aiNode& node, const glm::dmat4& placed) {
    for (unsigned k = 0; k < node.mNumMeshes; ++k) {
      if (node.mMeshes[k] >= scene_.mNumMeshes) throw InputError(file_, "", "a node places a mesh that does not exist");
      add_mesh(*scene_.mMeshes[node.mMeshes[k]], placed);
    }
  }

  void add_mesh(const aiMesh& mesh, const glm::dmat4& placed) {
    const glm::dmat3 linear(placed);
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(linear));
    // A mirroring transform turns the faces inside out; their corners are taken in reverse so
    // that what faced out still does.
    const bool mirrored = glm::determinant(linear) < 0.0;
    const bool has_normals = mesh.mNormals != nullptr;
    const bool has_uvs = mesh.mTextureCoords[0] != nullptr;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices < 3) continue;  // points and lines say nothing about the surface (as OBJ's p and l)
      if ((faces_ += 1) > kMaxColladaFaces)
        throw InputError(file_, "", "the scene places more than " + std::to_string(kMaxColladaFaces) +
                                        " faces (its nodes instance its meshes), more than this reader takes");
      for (unsigned i = 0; i < face.mNumIndices; ++i) {
        const unsigned v = face.mIndices[mirrored ? face.mNumIndices - 1 - i : i];
        if (v >= mesh.mNumVertices)
          throw InputError(file_, "face " + std::to_string(faces_ - 1), "references a vertex that does not exist");
        const aiVector3D& p = mesh.mVertices[v];
        PolygonSoup::Corner corner{.position = positions_.of(glm::dvec3(placed * glm::dvec4(p.x, p.y, p.z, 1.0)), soup_)};
        if (has_normals) {
          const aiVector3D& n = mesh.mNormals[v];
          corner.normal = static_cast<std::int64_t>(soup_.normals.size());
          soup_.normals.push_back(normal_matrix * glm::dvec3(n.x, n.y, n.z));
        }
        if (has_uvs) {
          const aiVector3D& uv = mesh.mTextureCoords[0][v];
          corner.uv = static_cast<std::int64_t>(soup_.uvs.size());
          soup_.uvs.emplace_back(uv.x, uv.y);
        }
        soup_.corners.push_back(corner);
      }
      soup_.end_face();
    }
  }

  const aiScene& scene_;
  const std::string& file_;
  PolygonSoup soup_;
  PositionIndex positions_;
  std::uint64_t faces_ = 0;
};

}  // namespace

PolygonSoup read_collada_soup(std::string_view bytes, const std::string& file) {
  ColladaDeclarations(bytes, file).check();
  Assimp::Importer importer;  // no DefaultLogger is created: Assimp's log goes nowhere
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  // A scene without meshes would otherwise get a stand-in: little pyramids at its nodes.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  const aiScene* scene = nullptr;
  try {
    // The hint "dae" is the only extension Assimp's Collada importer claims, so no other
    // importer looks at the bytes. No post-processing: the soup triangulates and welds.
    scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(), 0, "dae");
  } catch (const std::bad_alloc&) {  // what the checks above leave: Assimp's sizes are its own
    throw InputError(file, "", "Assimp cannot read it: it asks for more memory than there is");
  } catch (const std::length_error&) {
    throw InputError(file, "", "Assimp cannot read it: it asks for more memory than there is");
  }
  if (!scene) {
    const std::string why = importer.GetErrorString();
    throw InputError(file, "", "not a Collada file Assimp can read: " + (why.empty() ? std::string("no reason given") : why));
  }
  return SceneSoup(*scene, file).build();
}

}  // namespace nano::mesh
