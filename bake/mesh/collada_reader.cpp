// Collada (.dae), the geometry format of cellPACK's database, read through Assimp: the only
// translation unit of bake/ that includes Assimp. Assimp parses the XML and resolves sources,
// accessors and node instances; what it hands back becomes a polygon soup like every other
// format's, so polygon_soup.cpp checks, triangulates and welds it by mesh_reader.hpp's rules.
//
// What Assimp is allowed to do is kept narrow:
// - it runs in a process of its own (this executable started again, see "the import process and
//   the reader" below), with a time limit and a bounded address space; what it hands back crosses
//   a pipe as one record the reader checks, and a crash, a hang or a runaway allocation there is
//   an InputError here;
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
#include <cerrno>
#include <charconv>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <unordered_map>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

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

// ---- the scene Assimp builds, as a polygon soup (in the import process) ----

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
  explicit SceneSoup(const aiScene& scene) : scene_(scene) {}

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
  // The file is named by the reader, which passes on `where` and `rule` (this runs in the import process).
  [[noreturn]] static void fail(const std::string& where, const std::string& rule) { throw InputError("", where, rule); }

  void add_meshes(const aiNode& node, const glm::dmat4& placed) {
    for (unsigned k = 0; k < node.mNumMeshes; ++k) {
      if (node.mMeshes[k] >= scene_.mNumMeshes) fail("", "a node places a mesh that does not exist");
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
        fail("", "the scene places more than " + std::to_string(kMaxColladaFaces) +
                     " faces (its nodes instance its meshes), more than this reader takes");
      // Instancing multiplies corners as well as faces: bounded as the file's own are.
      if (soup_.corners.size() + face.mNumIndices > kMaxColladaCorners)
        fail("", "the scene places more than " + std::to_string(kMaxColladaCorners) +
                     " face corners (its nodes instance its meshes), more than this reader takes");
      for (unsigned i = 0; i < face.mNumIndices; ++i) {
        const unsigned v = face.mIndices[mirrored ? face.mNumIndices - 1 - i : i];
        if (v >= mesh.mNumVertices) fail("face " + std::to_string(faces_ - 1), "references a vertex that does not exist");
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
  PolygonSoup soup_;
  PositionIndex positions_;
  std::uint64_t faces_ = 0;
};

// ---- the import process and the reader: who runs Assimp, and why apart ----
//
// Fuzzing showed that Assimp itself does not survive every malformed file: a misspelt <float_array>
// count makes it dereference null, Debian builds it with assertions that abort, and it leaks when
// it throws. Bad input must end as an error naming the file, never as a crash, so Assimp runs in a
// process of its own, with a time limit and a bounded address space, and only its result comes
// back: one record through a pipe, which the reader checks as it would a file.
//
// That process is this same executable, started afresh (posix_spawn of /proc/self/exe), not a
// fork() of the reader. Meshes are read while another thread may run: on a terminal, nanobake's
// progress display (bake_progress.cpp) redraws from a thread of its own during the "meshes" stage,
// holding its mutex and stdio's locks as it prints. A forked child of a threaded process may only
// call async-signal-safe functions until it execs, since a lock another thread held at fork()
// stays held in the child for good; Assimp allocates and builds strings throughout. A process that
// execs starts with one thread and no held locks, whatever the reader's process was doing, and
// glibc's posix_spawn (vfork-like, nothing run between the clone and the exec but dup2 and open)
// is safe to call from a threaded process. The switch into the import role is kImportProcessRole
// below, run while the executable's static objects are constructed, before main(): so every
// program linking this reader (nanobake, the tests, the fuzzers) is its own import helper, without
// a subcommand or a helper binary to find.
//
// The import process gets the file's bytes on standard input (a memfd: the reader never writes to
// a pipe the child could close, so SIGPIPE cannot reach it), writes its record to descriptor
// kRecordFd, and its standard output goes to /dev/null (Assimp has no logger and prints nothing;
// standard error is kept, where a sanitizer build would report). The protocol's variable holds
// the address space it may add to what it has on starting.
constexpr const char* kImportProcessVariable = "NANO_COLLADA_IMPORT_PROCESS";
constexpr int kRecordFd = 3;
// The import process's exit statuses other than 0 (its record written).
constexpr int kExitCannotReadInput = 120;
constexpr int kExitCannotWriteRecord = 121;

// The record, in this machine's byte order (both ends are one executable):
//   u32 kRecordStart, u8 RecordKind
//   refusal: u32 length and the text of `where`, the same for the rule (each at most kMaxMessageBytes)
//   soup: u64 counts of positions, normals, UVs, corners and faces; then the positions and normals
//         (3 doubles each), UVs (2 doubles), corners (3 int32 each: position, UV, normal, -1 for
//         none) and faces (u32 each: the end of its corners)
//   u32 kRecordEnd
// The reader trusts none of it: every count is bounded (by the limits check() and SceneSoup
// enforce) before anything is sized by it, the faces' ends must rise to the corner count, and
// polygon_soup.cpp checks every index as for any file.
enum class RecordKind : std::uint8_t { soup = 1, refusal = 2 };
constexpr std::uint32_t kRecordStart = 0x41444e4e;  // "NNDA"
constexpr std::uint32_t kRecordEnd = 0x444e4521;    // "!END"
constexpr std::uint32_t kMaxMessageBytes = 1 << 16;
static_assert(sizeof(glm::dvec3) == 3 * sizeof(double) && sizeof(glm::dvec2) == 2 * sizeof(double));

// ---- in the import process ----

class RecordWriter {
public:
  explicit RecordWriter(int fd) : fd_(fd) {}
  bool ok() const { return ok_; }

  template <typename Value> void value(const Value& v) { bytes(&v, sizeof v); }
  template <typename Value> void values(const std::vector<Value>& vs) { bytes(vs.data(), vs.size() * sizeof(Value)); }
  void text(std::string_view s) {
    s = s.substr(0, kMaxMessageBytes);
    value(static_cast<std::uint32_t>(s.size()));
    bytes(s.data(), s.size());
  }

private:
  // A failed write (the reader gone) stops the record; the exit status says so.
  void bytes(const void* data, std::size_t size) {
    const char* at = static_cast<const char*>(data);
    while (ok_ && size > 0) {
      const ssize_t written = ::write(fd_, at, std::min<std::size_t>(size, std::size_t{1} << 20));
      if (written < 0 && errno == EINTR) continue;
      if (written <= 0) ok_ = false;
      if (written <= 0) break;
      at += written;
      size -= static_cast<std::size_t>(written);
    }
  }

  int fd_;
  bool ok_ = true;
};

void write_refusal(RecordWriter& out, std::string_view where, std::string_view rule) {
  out.value(kRecordStart);
  out.value(RecordKind::refusal);
  out.text(where);
  out.text(rule);
  out.value(kRecordEnd);
}

void write_soup(RecordWriter& out, const PolygonSoup& soup) {
  // Converted before the first byte goes out, so that memory running out here still leaves a
  // refusal, not half a record. SceneSoup bounds every index below 2^31.
  std::vector<std::int32_t> corners;
  corners.reserve(3 * soup.corners.size());
  for (const PolygonSoup::Corner& c : soup.corners)
    for (const std::int64_t index : {c.position, c.uv, c.normal}) corners.push_back(static_cast<std::int32_t>(index));
  const std::vector<std::uint32_t> face_ends(soup.face_ends.begin(), soup.face_ends.end());
  out.value(kRecordStart);
  out.value(RecordKind::soup);
  for (const std::size_t count : {soup.positions.size(), soup.normals.size(), soup.uvs.size(), soup.corners.size(), face_ends.size()})
    out.value(static_cast<std::uint64_t>(count));
  out.values(soup.positions);
  out.values(soup.normals);
  out.values(soup.uvs);
  out.values(corners);
  out.values(face_ends);
  out.value(kRecordEnd);
}

// The most address space this process has had, in bytes (0 if /proc cannot say).
std::uint64_t peak_address_space() {
  const int fd = ::open("/proc/self/status", O_RDONLY | O_CLOEXEC);
  if (fd < 0) return 0;
  std::array<char, 4096> text{};
  ssize_t got = -1;
  do got = ::read(fd, text.data(), text.size() - 1); while (got < 0 && errno == EINTR);
  ::close(fd);
  const std::string_view status(text.data(), static_cast<std::size_t>(std::max<ssize_t>(got, 0)));
  const std::size_t at = status.find("VmPeak:");
  if (at == std::string_view::npos) return 0;
  const std::size_t digits = status.find_first_of("0123456789", at);
  std::uint64_t kib = 0;
  if (digits != std::string_view::npos) std::from_chars(status.data() + digits, status.data() + status.size(), kib);
  return kib << 10;
}

// The address space the import may use: what the process had on starting, and what it may add.
struct AddressSpaceAllowance {
  std::uint64_t at_start = 0;
  std::uint64_t budget = 0;
};

// Assimp reports an allocation that failed as whatever it was doing (pugixml's out-of-memory
// becomes "malformed XML"), so a refusal says when the process had used much of its allowance.
std::string with_memory_note(std::string rule, const AddressSpaceAllowance& allowance) {
  const std::uint64_t peak = peak_address_space();
  if (peak > allowance.at_start && peak - allowance.at_start > allowance.budget / 2)
    rule += " (its process had used " + std::to_string((peak - allowance.at_start) >> 20) + " MiB of the " +
            std::to_string(allowance.budget >> 20) + " MiB of address space it may add: the failure may be an allocation that did not fit)";
  return rule;
}

void import_and_write(std::string_view bytes, RecordWriter& out, const AddressSpaceAllowance& allowance) {
  const auto refuse = [&](std::string_view where, const std::string& rule) {
    write_refusal(out, where, with_memory_note(rule, allowance));
  };
  try {
    Assimp::Importer importer;  // no DefaultLogger is created: Assimp's log goes nowhere
    importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
    // A scene without meshes would otherwise get a stand-in: little pyramids at its nodes.
    importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
    // The hint "dae" is the only extension Assimp's Collada importer claims, so no other
    // importer looks at the bytes. No post-processing: the soup triangulates and welds.
    const aiScene* scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(), 0, "dae");
    if (!scene) {
      const std::string why = importer.GetErrorString();
      return refuse("", "not a Collada file Assimp can read: " + (why.empty() ? std::string("no reason given") : why));
    }
    write_soup(out, SceneSoup(*scene).build());
  } catch (const InputError& e) {
    write_refusal(out, e.where(), e.rule());  // our own limits, not memory
  } catch (const std::bad_alloc&) {
    refuse("", "Assimp cannot read it: it asks for more memory than it may have");
  } catch (const std::length_error&) {
    refuse("", "Assimp cannot read it: it asks for more memory than it may have");
  } catch (const std::exception& e) {
    refuse("", std::string("Assimp cannot read it: ") + e.what());
  }
}

// The address space this process has now, in bytes (0 if /proc cannot say).
std::uint64_t current_address_space() {
  const int fd = ::open("/proc/self/statm", O_RDONLY | O_CLOEXEC);
  if (fd < 0) return 0;
  char text[64] = {};
  ssize_t got = -1;
  do got = ::read(fd, text, sizeof text - 1); while (got < 0 && errno == EINTR);
  ::close(fd);
  std::uint64_t pages = 0;
  std::from_chars(text, text + std::max<ssize_t>(got, 0), pages);
  return pages * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
}

std::string read_all_input() {
  std::string bytes;
  struct stat input {};
  if (::fstat(STDIN_FILENO, &input) != 0) ::_exit(kExitCannotReadInput);
  bytes.resize(static_cast<std::size_t>(input.st_size));
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t got = ::read(STDIN_FILENO, bytes.data() + done, bytes.size() - done);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) ::_exit(kExitCannotReadInput);
    done += static_cast<std::size_t>(got);
  }
  return bytes;
}

// The import process, from its start to its _exit (which also skips LeakSanitizer's check at exit:
// what Assimp leaks on a throw goes with the process).
[[noreturn]] void serve_as_import_process(const char* address_space_budget) {
  // A crash must end this process by its signal, for the reader to name it; a sanitizer's handler
  // (the fuzz build) would print a report and exit 1 instead. No core file either.
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  for (const int crash : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) ::sigaction(crash, &default_action, nullptr);
  const rlimit no_core{0, 0};
  ::setrlimit(RLIMIT_CORE, &no_core);
  // A runaway allocation then fails (bad_alloc, or a crash) instead of swapping the machine. Added
  // to what the process has: a sanitizer build reserves terabytes of shadow before main.
  AddressSpaceAllowance allowance{.at_start = current_address_space()};
  std::from_chars(address_space_budget, address_space_budget + std::strlen(address_space_budget), allowance.budget);
  const rlimit address_space{allowance.at_start + allowance.budget, allowance.at_start + allowance.budget};
  ::setrlimit(RLIMIT_AS, &address_space);
  const std::string bytes = read_all_input();
  RecordWriter out(kRecordFd);
  import_and_write(bytes, out, allowance);
  ::_exit(out.ok() ? 0 : kExitCannotWriteRecord);
}

// In the import process (kImportProcessVariable set by the reader that started it) this never
// returns; in every other process it does nothing. See "the import process and the reader".
[[maybe_unused]] const bool kImportProcessRole = [] {
  if (const char* budget = std::getenv(kImportProcessVariable)) serve_as_import_process(budget);
  return false;
}();

// ---- in the reader ----

using Clock = std::chrono::steady_clock;

class FileDescriptor {
public:
  FileDescriptor() = default;
  explicit FileDescriptor(int fd) : fd_(fd) {}
  FileDescriptor(FileDescriptor&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  FileDescriptor& operator=(FileDescriptor&& other) noexcept {
    reset(std::exchange(other.fd_, -1));
    return *this;
  }
  ~FileDescriptor() { reset(); }
  int get() const { return fd_; }
  void reset(int fd = -1) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = fd;
  }

private:
  int fd_ = -1;
};

[[noreturn]] void system_failure(const std::string& file, const std::string& what) {
  throw std::runtime_error(file + ": cannot start the process that reads Collada (" + what + ": " + std::strerror(errno) + ")");
}

// `fd` moved to a number of 10 or more, close-on-exec: the spawn's dup2s onto 0, 1 and 3 then
// cannot overwrite one another's sources, whatever the reader's process has open.
FileDescriptor high_descriptor(FileDescriptor original, const std::string& file) {
  if (original.get() < 0) system_failure(file, "memfd_create or pipe2");
  const int high = ::fcntl(original.get(), F_DUPFD_CLOEXEC, 10);
  if (high < 0) system_failure(file, "fcntl");
  return FileDescriptor(high);
}

FileDescriptor input_holding(std::string_view bytes, const std::string& file) {
  FileDescriptor input = high_descriptor(FileDescriptor(::memfd_create("nano-collada-input", MFD_CLOEXEC)), file);
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t written = ::write(input.get(), bytes.data() + done, bytes.size() - done);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) system_failure(file, "writing the file's bytes to a memfd");
    done += static_cast<std::size_t>(written);
  }
  if (::lseek(input.get(), 0, SEEK_SET) != 0) system_failure(file, "lseek");
  return input;
}

// The reader's environment with the import process's variable set.
std::vector<std::string> import_environment(std::uint64_t address_space_budget) {
  const std::string prefix = std::string(kImportProcessVariable) + "=";
  std::vector<std::string> environment;
  for (char** entry = environ; *entry; ++entry)
    if (!std::string_view(*entry).starts_with(prefix)) environment.emplace_back(*entry);
  environment.push_back(prefix + std::to_string(address_space_budget));
  return environment;
}

pid_t spawn_import_process(int input, int record, std::uint64_t address_space_budget, const std::string& file) {
  posix_spawn_file_actions_t actions;
  posix_spawnattr_t attributes;
  ::posix_spawn_file_actions_init(&actions);
  ::posix_spawn_file_actions_adddup2(&actions, input, STDIN_FILENO);
  ::posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  ::posix_spawn_file_actions_adddup2(&actions, record, kRecordFd);
  // No signal blocked, and SIGPIPE at its default even if the reader's process ignores it (an
  // ignored signal stays ignored across exec): a reader gone ends the import process.
  ::posix_spawnattr_init(&attributes);
  sigset_t signals;
  ::sigemptyset(&signals);
  ::posix_spawnattr_setsigmask(&attributes, &signals);
  ::sigaddset(&signals, SIGPIPE);
  ::posix_spawnattr_setsigdefault(&attributes, &signals);
  ::posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  std::vector<std::string> environment = import_environment(address_space_budget);
  std::vector<char*> environment_pointers;
  for (std::string& entry : environment) environment_pointers.push_back(entry.data());
  environment_pointers.push_back(nullptr);
  char name[] = "nano-collada-import";
  char* arguments[] = {name, nullptr};
  pid_t pid = -1;
  const int error = ::posix_spawn(&pid, "/proc/self/exe", &actions, &attributes, arguments, environment_pointers.data());
  ::posix_spawn_file_actions_destroy(&actions);
  ::posix_spawnattr_destroy(&attributes);
  if (error != 0) {
    errno = error;
    system_failure(file, "posix_spawn /proc/self/exe");
  }
  return pid;
}

// The import process, from its spawn to its end: killed and waited for by the destructor if it
// still runs, so it never outlives the reader and never stays a zombie.
class ImportProcess {
public:
  ImportProcess(std::string_view bytes, std::uint64_t address_space_budget, const std::string& file) {
    const FileDescriptor input = input_holding(bytes, file);
    // Both ends close-on-exec: the import process gets the write end as kRecordFd only, never the
    // read end; the reader closes its write end once the process has its own, so the record ends
    // (end of file) when the process's copy closes.
    int ends[2] = {-1, -1};
    if (::pipe2(ends, O_CLOEXEC) != 0) system_failure(file, "pipe2");
    FileDescriptor low_read_end(ends[0]), low_write_end(ends[1]);
    FileDescriptor read_end = high_descriptor(std::move(low_read_end), file);
    const FileDescriptor write_end = high_descriptor(std::move(low_write_end), file);
    pid_ = spawn_import_process(input.get(), write_end.get(), address_space_budget, file);
    record_ = std::move(read_end);
  }
  ImportProcess(const ImportProcess&) = delete;
  ImportProcess& operator=(const ImportProcess&) = delete;
  ~ImportProcess() {
    if (pid_ > 0) kill_and_wait();
  }

  int record() const { return record_.get(); }

  // Its wait status once it has ended, or nullopt if it still runs at `deadline`.
  std::optional<int> wait_until(Clock::time_point deadline) {
    for (auto pause = std::chrono::microseconds(100);; pause = std::min(2 * pause, std::chrono::microseconds(20'000))) {
      int status = 0;
      const pid_t ended = ::waitpid(pid_, &status, WNOHANG);
      if (ended == pid_ || (ended < 0 && errno == ECHILD)) {  // ECHILD: reaped already (SIGCHLD ignored)
        pid_ = -1;
        return ended > 0 ? status : 0;
      }
      if (ended < 0 && errno != EINTR) return std::nullopt;
      if (Clock::now() >= deadline) return std::nullopt;
      std::this_thread::sleep_for(pause);
    }
  }

  void kill_and_wait() {
    ::kill(pid_, SIGKILL);
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
  }

private:
  pid_t pid_ = -1;
  FileDescriptor record_;
};

// Why the record could not be read: cut short, malformed, or the time limit reached first.
struct BrokenRecord {
  std::string why;
};
struct TimeLimitReached {};

class RecordReader {
public:
  RecordReader(int fd, Clock::time_point deadline) : fd_(fd), deadline_(deadline) {}

  template <typename Value> Value value() {
    Value v;
    bytes(&v, sizeof v);
    return v;
  }
  template <typename Value> void values(std::vector<Value>& vs, std::uint64_t count) {
    vs.resize(count);
    bytes(vs.data(), count * sizeof(Value));
  }
  std::string text() {
    const auto size = value<std::uint32_t>();
    if (size > kMaxMessageBytes) throw BrokenRecord{"a message of " + std::to_string(size) + " bytes"};
    std::string s(size, '\0');
    bytes(s.data(), size);
    return s;
  }
  // Whether the process closed its end without writing more (within the time limit).
  bool at_end() {
    char extra = 0;
    return read_some(&extra, 1) == 0;
  }

private:
  void bytes(void* data, std::size_t size) {
    for (char* at = static_cast<char*>(data); size > 0;) {
      const std::size_t got = read_some(at, std::min<std::size_t>(size, std::size_t{1} << 20));
      if (got == 0) throw BrokenRecord{"it ends early"};
      at += got;
      size -= got;
    }
  }

  std::size_t read_some(char* at, std::size_t size) {
    for (;;) {
      const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline_ - Clock::now());
      if (left.count() <= 0) throw TimeLimitReached{};
      pollfd readable{.fd = fd_, .events = POLLIN, .revents = 0};
      const int ready = ::poll(&readable, 1, static_cast<int>(std::min<std::int64_t>(left.count(), 1'000'000)));
      if (ready == 0 || (ready < 0 && errno == EINTR)) continue;
      if (ready < 0) throw BrokenRecord{std::string("poll: ") + std::strerror(errno)};
      const ssize_t got = ::read(fd_, at, size);
      if (got < 0 && errno == EINTR) continue;
      if (got < 0) throw BrokenRecord{std::string("read: ") + std::strerror(errno)};
      return static_cast<std::size_t>(got);
    }
  }

  int fd_;
  Clock::time_point deadline_;
};

// What the import process answered: a soup, or why the file is refused.
struct ImportAnswer {
  std::optional<PolygonSoup> soup;
  std::string where, rule;
};

PolygonSoup read_soup(RecordReader& in) {
  std::array<std::uint64_t, 5> counts;  // positions, normals, UVs, corners, faces
  for (std::uint64_t& count : counts) count = in.value<std::uint64_t>();
  const auto [positions, normals, uvs, corners, faces] = counts;
  // Each corner adds at most one position (welded), one normal and one UV.
  if (faces > kMaxColladaFaces || corners > kMaxColladaCorners || positions > corners || normals > corners || uvs > corners)
    throw BrokenRecord{"counts beyond this reader's limits"};
  PolygonSoup soup;
  in.values(soup.positions, positions);
  soup.position_lines.assign(positions, 0);
  in.values(soup.normals, normals);
  in.values(soup.uvs, uvs);
  std::vector<std::int32_t> indices;
  in.values(indices, 3 * corners);
  soup.corners.reserve(corners);
  for (std::size_t c = 0; c < corners; ++c)
    soup.corners.push_back({.position = indices[3 * c], .uv = indices[3 * c + 1], .normal = indices[3 * c + 2]});
  std::vector<std::uint32_t> face_ends;
  in.values(face_ends, faces);
  std::uint64_t previous = 0;
  for (const std::uint32_t end : face_ends) {
    if (end < previous || end > corners) throw BrokenRecord{"a face's corners out of order"};
    previous = end;
  }
  if (previous != corners) throw BrokenRecord{"corners after the last face"};
  soup.face_ends.assign(face_ends.begin(), face_ends.end());
  soup.face_lines.assign(faces, 0);
  return soup;
}

ImportAnswer read_answer(RecordReader& in) {
  if (in.value<std::uint32_t>() != kRecordStart) throw BrokenRecord{"it does not start as a record"};
  ImportAnswer answer;
  const auto kind = in.value<RecordKind>();
  if (kind == RecordKind::soup) {
    answer.soup = read_soup(in);
  } else if (kind == RecordKind::refusal) {
    answer.where = in.text();
    answer.rule = in.text();
  } else {
    throw BrokenRecord{"an unknown kind of record"};
  }
  if (in.value<std::uint32_t>() != kRecordEnd || !in.at_end()) throw BrokenRecord{"it does not end as a record"};
  return answer;
}

std::string seconds_text(std::chrono::milliseconds time) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", static_cast<double>(time.count()) / 1000.0);
  return text;
}

// How the import process ended, when that is why there is no answer: nullopt for a clean exit.
std::optional<std::string> abnormal_end(int status) {
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    const char* abbreviation = ::sigabbrev_np(signal);
    const char* description = ::sigdescr_np(signal);
    return "Assimp stopped on this file (signal " + std::to_string(signal) + ": SIG" +
           (abbreviation ? abbreviation : "?") + ", " + (description ? description : "unknown signal") +
           ") while reading it in a process of its own: the file is malformed in a way Assimp does not survive";
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) != 0)
    return "the process that reads Collada through Assimp ended with exit status " + std::to_string(WEXITSTATUS(status)) +
           " without an answer";
  return std::nullopt;
}

}  // namespace

PolygonSoup read_collada_soup(std::string_view bytes, const std::string& file, const ColladaImportLimits& limits) {
  ColladaDeclarations(bytes, file).check();
  const std::uint64_t budget = std::max(limits.address_space, limits.address_space_per_byte * bytes.size());
  const Clock::time_point deadline = Clock::now() + limits.time;
  ImportProcess process(bytes, budget, file);
  const std::string out_of_time = "Assimp did not finish reading this file within " + seconds_text(limits.time) +
                                  " (the time limit); its process was stopped (SIGKILL)";
  ImportAnswer answer;
  std::optional<std::string> broken;
  try {
    RecordReader in(process.record(), deadline);
    answer = read_answer(in);
  } catch (const BrokenRecord& e) {
    broken = e.why;
  } catch (const TimeLimitReached&) {
    throw InputError(file, "", out_of_time);  // ~ImportProcess kills and waits
  }
  // How the process ended comes first: a record cut short by a crash is reported as the crash.
  const std::optional<int> status = process.wait_until(deadline);
  if (!status) throw InputError(file, "", out_of_time);
  if (std::optional<std::string> why = abnormal_end(*status)) throw InputError(file, "", *why);
  if (broken) throw InputError(file, "", "the process that reads Collada through Assimp gave a broken answer (" + *broken + ")");
  if (!answer.soup) throw InputError(file, answer.where, answer.rule);
  return std::move(*answer.soup);
}

}  // namespace nano::mesh
