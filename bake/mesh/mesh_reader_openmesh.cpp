// The only translation unit that includes OpenMesh. OpenMesh's own ImporterT would build a
// half-edge mesh and quietly split non-manifold faces or drop faces with repeated vertices; the
// RawImporter below records exactly what the file says instead, so every defect keeps its face
// index for check-mesh.
#include "bake/mesh/mesh_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <span>
#include <map>
#include <optional>
#include <sstream>
#include <cstdio>
#include <string>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>

#include "bake/mesh/draco_codec.hpp"
#include "bake/mesh/vertex_normals.hpp"
#include "common/error.hpp"

namespace nano::mesh {

namespace {

using OpenMesh::FaceHandle;
using OpenMesh::VertexHandle;

struct RawPolygon {
  std::vector<int> vertices;
  std::vector<glm::dvec2> corner_uvs;      // from per-face texcoords, if the file has them
  std::vector<std::optional<glm::dvec3>> corner_normals;
};

class RawImporter final : public OpenMesh::IO::BaseImporter {
public:
  std::vector<glm::dvec3> points;
  std::vector<std::optional<glm::dvec2>> vertex_uvs;
  std::vector<std::optional<glm::dvec3>> vertex_normals;
  std::vector<RawPolygon> polygons;
  std::optional<std::pair<std::string, std::string>> error;  // where, rule

  VertexHandle add_vertex(const OpenMesh::Vec3f& p) override { return push_vertex({p[0], p[1], p[2]}); }
  VertexHandle add_vertex(const OpenMesh::Vec3d& p) override { return push_vertex({p[0], p[1], p[2]}); }
  VertexHandle add_vertex() override { return push_vertex(glm::dvec3(0.0)); }
  void set_point(VertexHandle vh, const OpenMesh::Vec3f& p) override {
    if (valid(vh)) points[vh.idx()] = {p[0], p[1], p[2]};
  }

  FaceHandle add_face(const VHandles& handles) override {
    RawPolygon polygon;
    for (const VertexHandle& vh : handles) {
      if (!valid(vh)) {
        if (!error) error = {"face " + std::to_string(polygons.size()), "references a vertex that does not exist"};
        return FaceHandle();
      }
      polygon.vertices.push_back(vh.idx());
      // OBJ gives per-corner normals by setting the vertex normal just before the face.
      auto pending = pending_normals_.find(vh.idx());
      polygon.corner_normals.push_back(pending != pending_normals_.end() ? std::optional(pending->second)
                                                                         : vertex_normals[vh.idx()]);
    }
    pending_normals_.clear();
    polygons.push_back(std::move(polygon));
    return FaceHandle(static_cast<int>(polygons.size()) - 1);
  }
  FaceHandle add_face(OpenMesh::HalfedgeHandle) override {
    if (!error) error = {"", "half-edge connectivity records are not supported"};
    return FaceHandle();
  }

  void add_face_texcoords(FaceHandle fh, VertexHandle, const std::vector<OpenMesh::Vec2f>& uvs) override {
    // The OBJ reader calls this twice per face, the second time with its (usually empty) 3D list.
    if (uvs.empty() || !fh.is_valid() || fh.idx() >= static_cast<int>(polygons.size())) return;
    auto& corner_uvs = polygons[fh.idx()].corner_uvs;
    corner_uvs.clear();
    for (const auto& uv : uvs) corner_uvs.push_back({uv[0], uv[1]});
  }
  void add_face_texcoords(FaceHandle fh, VertexHandle vh, const std::vector<OpenMesh::Vec3f>& uvw) override {
    std::vector<OpenMesh::Vec2f> uvs;
    for (const auto& t : uvw) uvs.push_back({t[0], t[1]});
    add_face_texcoords(fh, vh, uvs);
  }
  void set_texcoord(VertexHandle vh, const OpenMesh::Vec2f& uv) override {
    if (valid(vh)) vertex_uvs[vh.idx()] = glm::dvec2(uv[0], uv[1]);
  }
  void set_texcoord(VertexHandle vh, const OpenMesh::Vec3f& uv) override {
    if (valid(vh)) vertex_uvs[vh.idx()] = glm::dvec2(uv[0], uv[1]);
  }
  void set_normal(VertexHandle vh, const OpenMesh::Vec3f& n) override { record_normal(vh, {n[0], n[1], n[2]}); }
  void set_normal(VertexHandle vh, const OpenMesh::Vec3d& n) override { record_normal(vh, {n[0], n[1], n[2]}); }

  // Attributes a proxy mesh does not carry.
  OpenMesh::HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return OpenMesh::HalfedgeHandle(); }
  void set_face_texindex(FaceHandle, int) override {}
  void set_halfedge(VertexHandle, OpenMesh::HalfedgeHandle) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4f&) override {}
  void set_status(VertexHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_next(OpenMesh::HalfedgeHandle, OpenMesh::HalfedgeHandle) override {}
  void set_face(OpenMesh::HalfedgeHandle, FaceHandle) override {}
  void request_face_texcoords2D() override {}
  void set_texcoord(OpenMesh::HalfedgeHandle, const OpenMesh::Vec2f&) override {}
  void set_texcoord(OpenMesh::HalfedgeHandle, const OpenMesh::Vec3f&) override {}
  void set_status(OpenMesh::HalfedgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec3f&) override {}
  void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec4f&) override {}
  void set_status(OpenMesh::EdgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3d&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec4f&) override {}
  void set_status(FaceHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void add_texture_information(int, std::string) override {}

  size_t n_vertices() const override { return points.size(); }
  size_t n_faces() const override { return polygons.size(); }
  size_t n_edges() const override { return 0; }

private:
  VertexHandle push_vertex(const glm::dvec3& p) {
    points.push_back(p);
    vertex_uvs.emplace_back();
    vertex_normals.emplace_back();
    return VertexHandle(static_cast<int>(points.size()) - 1);
  }
  bool valid(VertexHandle vh) const { return vh.is_valid() && vh.idx() < static_cast<int>(points.size()); }
  void record_normal(VertexHandle vh, const glm::dvec3& n) {
    if (!valid(vh)) return;
    vertex_normals[vh.idx()] = n;
    pending_normals_[vh.idx()] = n;
  }
  std::map<int, glm::dvec3> pending_normals_;
};

// Assigns one index per distinct value (bit-exact), in order of first appearance.
template <typename Value>
class Deduplicator {
public:
  std::uint32_t index_of(const Value& v) {
    auto [it, inserted] = index_.try_emplace(key(v), static_cast<std::uint32_t>(values.size()));
    if (inserted) values.push_back(v);
    return it->second;
  }
  std::vector<Value> values;

private:
  static std::string key(const Value& v) {
    std::string bytes(sizeof(Value), '\0');
    std::memcpy(bytes.data(), &v, sizeof(Value));
    return bytes;
  }
  std::map<std::string, std::uint32_t> index_;
};

ProxyMesh assemble(const RawImporter& in, const std::string& file) {
  for (std::size_t v = 0; v < in.points.size(); ++v) {
    const glm::dvec3& p = in.points[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw InputError(file, "vertex " + std::to_string(v), "coordinate is not a finite number");
  }
  Deduplicator<glm::dvec3> welded_positions;
  Deduplicator<glm::dvec2> uvs;
  Deduplicator<glm::dvec3> normals;
  ProxyMesh mesh;
  bool every_corner_has_uv = true;
  bool every_corner_has_normal = true;
  for (std::size_t f = 0; f < in.polygons.size(); ++f) {
    const RawPolygon& polygon = in.polygons[f];
    const std::size_t n = polygon.vertices.size();
    if (n < 3) throw InputError(file, "face " + std::to_string(f), "face has fewer than 3 vertices");
    const bool face_uvs = polygon.corner_uvs.size() == n;
    auto corner_uv = [&](std::size_t c) -> std::optional<glm::dvec2> {
      if (face_uvs) return polygon.corner_uvs[c];
      return in.vertex_uvs[polygon.vertices[c]];
    };
    for (std::size_t c = 2; c < n; ++c) {  // fan: (0, c-1, c)
      const std::size_t corners[3] = {0, c - 1, c};
      Triangle t{}, uv_t{}, normal_t{};
      for (int k = 0; k < 3; ++k) {
        t[k] = welded_positions.index_of(in.points[polygon.vertices[corners[k]]]);
        if (auto uv = corner_uv(corners[k])) {
          uv_t[k] = uvs.index_of(*uv);
        } else {
          every_corner_has_uv = false;
        }
        if (auto normal = polygon.corner_normals[corners[k]]) {
          normal_t[k] = normals.index_of(*normal);
        } else {
          every_corner_has_normal = false;
        }
      }
      mesh.triangles.push_back(t);
      mesh.uv_triangles.push_back(uv_t);
      mesh.normal_triangles.push_back(normal_t);
    }
  }
  if (mesh.triangles.empty()) throw InputError(file, "", "mesh has no faces");
  mesh.positions = std::move(welded_positions.values);
  if (every_corner_has_uv) {
    mesh.uvs = std::move(uvs.values);
  } else {
    mesh.uv_triangles.clear();
  }
  bool normals_usable = every_corner_has_normal;
  for (glm::dvec3& normal : normals.values) {
    const double length = std::sqrt(normal.x * normal.x + normal.y * normal.y + normal.z * normal.z);
    if (!(length > 0.0) || !std::isfinite(length)) normals_usable = false;
    else normal /= length;
  }
  if (normals_usable) {
    mesh.normals = std::move(normals.values);
  } else {
    compute_angle_weighted_normals(mesh);
  }
  return mesh;
}

// OpenMesh's OBJ reader silently drops a face left with fewer than 3 distinct vertices, which
// would shift every later face index; find such a face first and name it.
void reject_obj_faces_with_repeated_vertices(const std::filesystem::path& path, const std::string& file) {
  std::ifstream in(path);
  std::string line;
  long positions = 0, face = 0;
  while (std::getline(in, line)) {
    std::istringstream tokens(line);
    std::string keyword;
    tokens >> keyword;
    if (keyword == "v") ++positions;
    if (keyword != "f") continue;
    std::vector<long> corners;
    for (std::string corner; tokens >> corner;) {
      long index = 0;
      if (std::sscanf(corner.c_str(), "%ld", &index) != 1) break;
      corners.push_back(index < 0 ? positions + index + 1 : index);  // OBJ counts back from the end
    }
    std::sort(corners.begin(), corners.end());
    const auto distinct = std::unique(corners.begin(), corners.end()) - corners.begin();
    if (distinct < 3)
      throw InputError(file, "face " + std::to_string(face),
                       "degenerate face: fewer than 3 distinct vertices (repeated vertex index)");
    ++face;
  }
}

}  // namespace

ProxyMesh read_proxy_mesh(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(file, "", "no such file");
  if (!std::ifstream(path, std::ios::binary))
    throw InputError(file, "", "cannot open the file for reading");
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  if (extension == ".drc") {
    std::ifstream in(path, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return decode_draco_mesh(std::as_bytes(std::span(text.data(), text.size())), file);
  }
  if (extension != ".obj" && extension != ".ply" && extension != ".off" && extension != ".stl")
    throw InputError(file, "", "unsupported mesh format '" + extension + "' (use .obj, .ply, .off, .stl or .drc)");

  if (extension == ".obj") reject_obj_faces_with_repeated_vertices(path, file);
  RawImporter importer;
  OpenMesh::IO::Options options;
  options += OpenMesh::IO::Options::VertexTexCoord;
  options += OpenMesh::IO::Options::FaceTexCoord;
  options += OpenMesh::IO::Options::VertexNormal;
  // OpenMesh reports parse trouble on its own stream; our InputError says it once, with the file.
  omerr().disable();
  const bool parsed = OpenMesh::IO::IOManager().read(file, importer, options);
  omerr().enable();
  if (importer.error) throw InputError(file, importer.error->first, importer.error->second);
  if (!parsed) throw InputError(file, "", "not a readable " + extension.substr(1) + " mesh");
  return assemble(importer, file);
}

}  // namespace nano::mesh
