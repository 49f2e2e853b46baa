#include "format/draco_mesh_sections.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <new>
#include <numeric>

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

namespace nano::format {
namespace {

// Directory of the section: u32 mesh count, u32 reserved (0), then per mesh a DirectoryEntry;
// the streams follow, contiguous and in mesh order, the last one ending the section.
struct DirectoryEntry {
  std::uint32_t offset;  // of the stream, from the start of the section
  std::uint32_t size;
  float position_step;   // positions are integers times this power of two
  float uv_step;         // UVs likewise
};
static_assert(sizeof(DirectoryEntry) == 16);
constexpr std::uint64_t kDirectoryHead = 8;
// Grid steps outside 2^±60 would be no honest mesh's and could overflow a float.
constexpr int kMaxStepExponent = 60;

double sign_of(double v) { return v < 0.0 ? -1.0 : 1.0; }

std::uint32_t bits(float f) { return std::bit_cast<std::uint32_t>(f); }

using VertexKey = std::array<std::uint32_t, 10>;
VertexKey key_of(const MeshArrays& m, std::size_t v) {
  const glm::vec4& p = m.positions[v];
  const glm::vec4& n = m.normals[v];
  const glm::vec2& t = m.uvs[v];
  return {bits(p.x), bits(p.y), bits(p.z), bits(p.w), bits(n.x), bits(n.y), bits(n.z), bits(n.w), bits(t.x), bits(t.y)};
}

bool is_power_of_two_step(float step) {
  if (!(step > 0.f) || !std::isfinite(step)) return false;
  int exponent = 0;
  return std::frexp(step, &exponent) == 0.5f && std::abs(exponent - 1) <= kMaxStepExponent;
}

// The integer of `value` on a grid `step` known to hold it exactly.
std::int32_t grid_integer(float value, float step) { return static_cast<std::int32_t>(double(value) / double(step)); }

float from_grid(std::int32_t q, float step) { return static_cast<float>(double(q) * double(step)); }

std::vector<float> position_components(const MeshArrays& m) {
  std::vector<float> v;
  v.reserve(m.positions.size() * 3);
  for (const glm::vec4& p : m.positions) v.insert(v.end(), {p.x, p.y, p.z});
  return v;
}

std::vector<float> uv_components(const MeshArrays& m) {
  std::vector<float> v;
  v.reserve(m.uvs.size() * 2);
  for (const glm::vec2& t : m.uvs) v.insert(v.end(), {t.x, t.y});
  return v;
}

template <std::size_t N>
int add_integer_attribute(draco::Mesh& mesh, draco::GeometryAttribute::Type type, const std::vector<std::array<std::int32_t, N>>& values) {
  draco::GeometryAttribute attribute;
  attribute.Init(type, nullptr, N, draco::DT_INT32, false, sizeof(std::int32_t) * N, 0);
  const int id = mesh.AddAttribute(attribute, true, static_cast<std::uint32_t>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i)
    mesh.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(static_cast<std::uint32_t>(i)), values[i].data());
  return id;
}

struct EncodedMesh {
  std::vector<std::byte> stream;
  float position_step = 1.f, uv_step = 1.f;
  std::string why;
};

EncodedMesh encode_mesh(const MeshArrays& m, int speed) {
  EncodedMesh out;
  if (m.triangles.empty()) return out.why = "it has no triangles", out;
  try {
    if (!same_bits(canonical_mesh_order(m), m)) return out.why = "it is not in canonical order", out;
  } catch (const std::invalid_argument& e) {
    return out.why = e.what(), out;
  }
  const std::optional<float> position_step = power_of_two_grid(position_components(m));
  if (!position_step) return out.why = "its positions lie on no power-of-two grid within 2^28 steps", out;
  const std::optional<float> uv_step = power_of_two_grid(uv_components(m));
  if (!uv_step) return out.why = "its UVs lie on no power-of-two grid within 2^28 steps", out;
  out.position_step = *position_step;
  out.uv_step = *uv_step;

  const std::size_t n = m.positions.size();
  std::vector<std::array<std::int32_t, 3>> positions(n);
  std::vector<std::array<std::int32_t, 2>> normals(n), uvs(n);
  for (std::size_t v = 0; v < n; ++v) {
    if (bits(m.positions[v].w) != 0 || bits(m.normals[v].w) != 0) return out.why = "a vertex has a non-zero w", out;
    const auto [a, b] = encode_octahedral(m.normals[v]);
    if (std::bit_cast<std::array<std::uint32_t, 4>>(decode_octahedral(a, b)) !=
        std::bit_cast<std::array<std::uint32_t, 4>>(m.normals[v]))
      return out.why = "normal " + std::to_string(v) + " is not on the octahedral grid", out;
    normals[v] = {a, b};
    for (int c = 0; c < 3; ++c) positions[v][c] = grid_integer(m.positions[v][c], out.position_step);
    for (int c = 0; c < 2; ++c) uvs[v][c] = grid_integer(m.uvs[v][c], out.uv_step);
  }
  draco::Mesh mesh;
  mesh.set_num_points(static_cast<std::uint32_t>(n));
  add_integer_attribute(mesh, draco::GeometryAttribute::POSITION, positions);
  add_integer_attribute(mesh, draco::GeometryAttribute::GENERIC, normals);
  add_integer_attribute(mesh, draco::GeometryAttribute::TEX_COORD, uvs);
  for (const gpu::Triangle& t : m.triangles)
    mesh.AddFace({draco::PointIndex(t.v0), draco::PointIndex(t.v1), draco::PointIndex(t.v2)});
  // Positions shared by vertices split at UV or normal seams become one, so the connectivity runs
  // across seams; the points themselves stay distinct.
  mesh.DeduplicateAttributeValues();
  mesh.DeduplicatePointIds();
  draco::Encoder encoder;
  encoder.SetSpeedOptions(speed, speed);
  encoder.SetEncodingMethod(draco::MESH_EDGEBREAKER_ENCODING);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(mesh, &buffer);
  if (!status.ok()) return out.why = "Draco cannot encode it: " + status.error_msg_string(), out;
  out.stream.resize(buffer.size());
  std::memcpy(out.stream.data(), buffer.data(), buffer.size());
  return out;
}

template <class T> void store(std::vector<std::byte>& out, std::uint64_t at, const T& value) {
  std::memcpy(out.data() + at, &value, sizeof(T));
}
template <class T> T load(std::span<const std::byte> in, std::uint64_t at) {
  T value;
  std::memcpy(&value, in.data() + at, sizeof(T));
  return value;
}

// Reads attribute `type` (exactly one, N int32 components) of point p.
template <int N> class IntegerAttribute {
public:
  IntegerAttribute(const draco::Mesh& mesh, draco::GeometryAttribute::Type type, const char* name, std::uint64_t where) {
    const int id = mesh.GetNamedAttributeId(type);
    if (id < 0 || mesh.NumNamedAttributes(type) != 1)
      throw DracoSectionError(where, std::string("the stream has no single ") + name + " attribute");
    attribute_ = mesh.attribute(id);
    if (attribute_->data_type() != draco::DT_INT32 || attribute_->num_components() != N)
      throw DracoSectionError(where, std::string("the ") + name + " attribute is not " + std::to_string(N) + " 32-bit integers");
    if (!attribute_->is_mapping_identity() && attribute_->indices_map_size() < mesh.num_points())
      throw DracoSectionError(where, std::string("the ") + name + " attribute maps fewer points than the mesh has");
    name_ = name;
    where_ = where;
  }
  std::array<std::int32_t, N> at(draco::PointIndex p) const {
    std::array<std::int32_t, N> v{};
    if (!attribute_->GetValue<std::int32_t, N>(attribute_->mapped_index(p), &v))
      throw DracoSectionError(where_, std::string("a point's ") + name_ + " value lies outside the attribute");
    return v;
  }

private:
  const draco::PointAttribute* attribute_ = nullptr;
  const char* name_ = "";
  std::uint64_t where_ = 0;
};

MeshArrays decode_stream(std::span<const std::byte> stream, const DirectoryEntry& entry, std::uint64_t where,
                         std::uint64_t max_vertices, std::uint64_t max_triangles) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(stream.data()), stream.size());
  const auto geometry = draco::Decoder::GetEncodedGeometryType(&buffer);
  if (!geometry.ok()) throw DracoSectionError(where, "not a Draco stream: " + geometry.status().error_msg_string());
  if (geometry.value() != draco::TRIANGULAR_MESH) throw DracoSectionError(where, "a Draco point cloud, not a triangle mesh");
  std::unique_ptr<draco::Mesh> decoded;
  try {
    draco::Decoder decoder;
    auto result = decoder.DecodeMeshFromBuffer(&buffer);
    if (!result.ok()) throw DracoSectionError(where, "Draco cannot decode the stream: " + result.status().error_msg_string());
    decoded = std::move(result).value();
  } catch (const std::bad_alloc&) {
    throw DracoSectionError(where, "the stream asks for more memory than there is");
  } catch (const std::length_error&) {
    throw DracoSectionError(where, "the stream asks for more memory than there is");
  }
  const draco::Mesh& mesh = *decoded;
  if (mesh.num_points() > max_vertices || mesh.num_faces() > max_triangles)
    throw DracoSectionError(where, "the stream holds " + std::to_string(mesh.num_points()) + " points and " +
                                       std::to_string(mesh.num_faces()) + " triangles, more than the sections' raw sizes allow");
  if (mesh.num_attributes() != 3) throw DracoSectionError(where, "the stream has " + std::to_string(mesh.num_attributes()) + " attributes, not 3");
  const IntegerAttribute<3> positions(mesh, draco::GeometryAttribute::POSITION, "position", where);
  const IntegerAttribute<2> normals(mesh, draco::GeometryAttribute::GENERIC, "normal", where);
  const IntegerAttribute<2> uvs(mesh, draco::GeometryAttribute::TEX_COORD, "UV", where);
  MeshArrays m;
  m.positions.resize(mesh.num_points());
  m.normals.resize(mesh.num_points());
  m.uvs.resize(mesh.num_points());
  for (draco::PointIndex p(0); p < mesh.num_points(); ++p) {
    const auto q = positions.at(p);
    const auto o = normals.at(p);
    const auto t = uvs.at(p);
    for (const std::int32_t value : {q[0], q[1], q[2], t[0], t[1]})
      if (std::abs(std::int64_t{value}) > kMaxGridInteger) throw DracoSectionError(where, "a grid integer exceeds 2^28");
    if (std::abs(o[0]) > kOctahedralMax || std::abs(o[1]) > kOctahedralMax)
      throw DracoSectionError(where, "an octahedral normal exceeds its 16-bit range");
    m.positions[p.value()] = {from_grid(q[0], entry.position_step), from_grid(q[1], entry.position_step),
                              from_grid(q[2], entry.position_step), 0.f};
    m.normals[p.value()] = decode_octahedral(o[0], o[1]);
    m.uvs[p.value()] = {from_grid(t[0], entry.uv_step), from_grid(t[1], entry.uv_step)};
  }
  m.triangles.resize(mesh.num_faces());
  for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f) {
    const draco::Mesh::Face& face = mesh.face(f);
    for (int c = 0; c < 3; ++c)
      if (face[c].value() >= mesh.num_points()) throw DracoSectionError(where, "a triangle names a point the stream lacks");
    m.triangles[f.value()] = {face[0].value(), face[1].value(), face[2].value()};
  }
  return canonical_mesh_order(m);
}

}  // namespace

bool same_bits(const MeshArrays& a, const MeshArrays& b) {
  const auto equal = [](const auto& x, const auto& y) {
    return x.size() == y.size() && (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0);
  };
  return equal(a.positions, b.positions) && equal(a.normals, b.normals) && equal(a.uvs, b.uvs) && equal(a.triangles, b.triangles);
}

glm::vec4 decode_octahedral(std::int32_t a, std::int32_t b) {
  double u = double(a) / kOctahedralMax, v = double(b) / kOctahedralMax;
  const double z = 1.0 - std::abs(u) - std::abs(v);
  if (z < 0.0) {
    const double folded_u = (1.0 - std::abs(v)) * sign_of(u);
    v = (1.0 - std::abs(u)) * sign_of(v);
    u = folded_u;
  }
  const double length = std::sqrt(u * u + v * v + z * z);  // >= 1/sqrt(3): the L1 norm is 1
  return {float(u / length), float(v / length), float(z / length), 0.f};
}

std::pair<std::int32_t, std::int32_t> encode_octahedral(const glm::vec4& normal) {
  const double x = normal.x, y = normal.y, z = normal.z;
  const double l1 = std::abs(x) + std::abs(y) + std::abs(z);
  if (!(l1 > 0.0) || !std::isfinite(l1)) return {0, 0};  // no direction: never on the grid
  double u = x / l1, v = y / l1;
  if (z < 0.0) {
    const double folded_u = (1.0 - std::abs(v)) * sign_of(u);
    v = (1.0 - std::abs(u)) * sign_of(v);
    u = folded_u;
  }
  const auto quantise = [](double w) {
    return static_cast<std::int32_t>(std::clamp<long long>(std::llround(w * kOctahedralMax), -kOctahedralMax, kOctahedralMax));
  };
  return {quantise(u), quantise(v)};
}

glm::vec4 snap_normal_to_grid(const glm::vec4& normal) {
  glm::vec4 n = normal;
  for (int round = 0; round < 4; ++round) {
    const auto [a, b] = encode_octahedral(n);
    const glm::vec4 next = decode_octahedral(a, b);
    if (std::bit_cast<std::array<std::uint32_t, 4>>(next) == std::bit_cast<std::array<std::uint32_t, 4>>(n)) break;
    n = next;
  }
  return n;
}

std::optional<float> power_of_two_grid(std::span<const float> values) {
  // The finest power of two dividing a float is its last set mantissa bit; the grid is the
  // coarsest step dividing all of them, i.e. the smallest of those.
  int lowest = std::numeric_limits<int>::max();
  double largest = 0.0;
  for (const float f : values) {
    if (!std::isfinite(f) || std::bit_cast<std::uint32_t>(f) == 0x80000000u) return std::nullopt;
    if (f == 0.f) continue;
    int exponent = 0;
    double mantissa = std::frexp(double(f), &exponent);  // f = mantissa * 2^exponent, 0.5 <= |m| < 1
    int last_bit = exponent;
    while (mantissa != std::trunc(mantissa)) mantissa *= 2.0, --last_bit;
    lowest = std::min(lowest, last_bit);
    largest = std::max(largest, std::abs(double(f)));
  }
  if (lowest == std::numeric_limits<int>::max()) return 1.f;
  if (std::abs(lowest) > kMaxStepExponent) return std::nullopt;
  const double step = std::ldexp(1.0, lowest);
  if (largest / step > double(kMaxGridInteger)) return std::nullopt;
  return static_cast<float>(step);
}

float storage_position_step(double largest_magnitude) {
  int exponent = -5;
  while (largest_magnitude / std::ldexp(1.0, exponent) > double(kMaxGridInteger) / 2) ++exponent;
  return static_cast<float>(std::ldexp(1.0, exponent));
}

float snap_to_step(double value, float step) {
  const double q = std::nearbyint(value / double(step));
  return static_cast<float>((q == 0.0 ? 0.0 : q) * double(step));
}

MeshArrays canonical_mesh_order(const MeshArrays& mesh) {
  const std::size_t n = mesh.positions.size();
  if (mesh.normals.size() != n || mesh.uvs.size() != n)
    throw std::invalid_argument("canonical_mesh_order: positions, normals and UVs differ in count");
  std::vector<std::uint8_t> used(n, 0);
  for (const gpu::Triangle& t : mesh.triangles)
    for (const std::uint32_t v : {t.v0, t.v1, t.v2}) {
      if (v >= n) throw std::invalid_argument("canonical_mesh_order: a triangle names vertex " + std::to_string(v) + " of " + std::to_string(n));
      used[v] = 1;
    }
  std::vector<std::pair<VertexKey, std::uint32_t>> keyed;
  for (std::uint32_t v = 0; v < n; ++v)
    if (used[v]) keyed.emplace_back(key_of(mesh, v), v);
  std::sort(keyed.begin(), keyed.end());
  MeshArrays out;
  std::vector<std::uint32_t> rank(n, 0);
  for (std::size_t i = 0; i < keyed.size(); ++i) {
    if (i == 0 || keyed[i].first != keyed[i - 1].first) {
      const std::uint32_t v = keyed[i].second;
      out.positions.push_back(mesh.positions[v]);
      out.normals.push_back(mesh.normals[v]);
      out.uvs.push_back(mesh.uvs[v]);
    }
    rank[keyed[i].second] = static_cast<std::uint32_t>(out.positions.size() - 1);
  }
  out.triangles.reserve(mesh.triangles.size());
  for (const gpu::Triangle& t : mesh.triangles) {
    std::array<std::uint32_t, 3> r{rank[t.v0], rank[t.v1], rank[t.v2]};
    std::rotate(r.begin(), std::min_element(r.begin(), r.end()), r.end());
    out.triangles.push_back({r[0], r[1], r[2]});
  }
  std::sort(out.triangles.begin(), out.triangles.end(), [](const gpu::Triangle& a, const gpu::Triangle& b) {
    return std::tie(a.v0, a.v1, a.v2) < std::tie(b.v0, b.v1, b.v2);
  });
  return out;
}

MeshArrays mesh_arrays(std::span<const gpu::Mesh> meshes, std::size_t index, std::span<const glm::vec4> positions,
                       std::span<const glm::vec4> normals, std::span<const glm::vec2> uvs,
                       std::span<const gpu::Triangle> triangles) {
  const gpu::Mesh& m = meshes[index];
  const auto within = [](std::uint64_t first, std::uint64_t count, std::size_t size) { return first + count <= size; };
  if (!within(m.first_vertex, m.vertex_count, positions.size()) || !within(m.first_vertex, m.vertex_count, normals.size()) ||
      !within(m.first_vertex, m.vertex_count, uvs.size()) || !within(m.first_triangle, m.triangle_count, triangles.size()))
    throw std::out_of_range("mesh " + std::to_string(index) + "'s ranges exceed the sections");
  MeshArrays out;
  out.positions.assign(positions.begin() + m.first_vertex, positions.begin() + m.first_vertex + m.vertex_count);
  out.normals.assign(normals.begin() + m.first_vertex, normals.begin() + m.first_vertex + m.vertex_count);
  out.uvs.assign(uvs.begin() + m.first_vertex, uvs.begin() + m.first_vertex + m.vertex_count);
  out.triangles.assign(triangles.begin() + m.first_triangle, triangles.begin() + m.first_triangle + m.triangle_count);
  return out;
}

DracoEncoding encode_draco_meshes(std::span<const gpu::Mesh> meshes, std::span<const glm::vec4> positions,
                                  std::span<const glm::vec4> normals, std::span<const glm::vec2> uvs,
                                  std::span<const gpu::Triangle> triangles, int speed) {
  DracoEncoding result;
  if (meshes.empty()) return result.why = "there are no meshes", result;
  std::uint64_t vertices = 0, triangle_total = 0;
  for (const gpu::Mesh& m : meshes) {
    if (m.first_vertex != vertices || m.first_triangle != triangle_total)
      return result.why = "the meshes do not follow each other in the sections", result;
    vertices += m.vertex_count;
    triangle_total += m.triangle_count;
  }
  if (vertices != positions.size() || vertices != normals.size() || vertices != uvs.size() || triangle_total != triangles.size())
    return result.why = "the meshes do not cover the sections exactly", result;

  std::vector<EncodedMesh> encoded;
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    encoded.push_back(encode_mesh(mesh_arrays(meshes, i, positions, normals, uvs, triangles), speed));
    if (!encoded.back().why.empty()) return result.why = "mesh " + std::to_string(i) + ": " + encoded.back().why, result;
  }
  std::uint64_t size = kDirectoryHead + sizeof(DirectoryEntry) * meshes.size();
  for (const EncodedMesh& e : encoded) size += e.stream.size();
  if (size > std::numeric_limits<std::uint32_t>::max()) return result.why = "the streams exceed 4 GiB", result;
  std::vector<std::byte> section(size);
  store(section, 0, static_cast<std::uint32_t>(meshes.size()));
  store(section, 4, std::uint32_t{0});
  std::uint64_t cursor = kDirectoryHead + sizeof(DirectoryEntry) * meshes.size();
  for (std::size_t i = 0; i < encoded.size(); ++i) {
    const DirectoryEntry entry{static_cast<std::uint32_t>(cursor), static_cast<std::uint32_t>(encoded[i].stream.size()),
                               encoded[i].position_step, encoded[i].uv_step};
    store(section, kDirectoryHead + sizeof(DirectoryEntry) * i, entry);
    std::memcpy(section.data() + cursor, encoded[i].stream.data(), encoded[i].stream.size());
    cursor += encoded[i].stream.size();
  }
  // Proof, not hope: the section must decode to exactly the input.
  MeshArrays input;
  input.positions.assign(positions.begin(), positions.end());
  input.normals.assign(normals.begin(), normals.end());
  input.uvs.assign(uvs.begin(), uvs.end());
  input.triangles.assign(triangles.begin(), triangles.end());
  try {
    if (!same_bits(decode_draco_meshes(section, meshes, vertices, triangle_total), input))
      return result.why = "Draco did not reproduce the meshes bit for bit", result;
  } catch (const DracoSectionError& e) {
    return result.why = std::string("Draco's stream does not decode: ") + e.what(), result;
  }
  result.section = std::move(section);
  return result;
}

MeshArrays decode_draco_meshes(std::span<const std::byte> section, std::span<const gpu::Mesh> meshes,
                               std::uint64_t max_vertices, std::uint64_t max_triangles) {
  if (section.size() < kDirectoryHead) throw DracoSectionError(0, "the section is shorter than its 8-byte directory head");
  const std::uint32_t count = load<std::uint32_t>(section, 0);
  if (count != meshes.size())
    throw DracoSectionError(0, "the directory lists " + std::to_string(count) + " streams for " + std::to_string(meshes.size()) + " meshes");
  if (load<std::uint32_t>(section, 4) != 0) throw DracoSectionError(4, "the reserved word of the directory is not zero");
  const std::uint64_t streams_begin = kDirectoryHead + sizeof(DirectoryEntry) * std::uint64_t{count};
  if (streams_begin > section.size()) throw DracoSectionError(0, "the directory runs past the end of the section");
  MeshArrays out;
  std::uint64_t cursor = streams_begin;
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint64_t at = kDirectoryHead + sizeof(DirectoryEntry) * i;
    const DirectoryEntry entry = load<DirectoryEntry>(section, at);
    const std::string mesh = "mesh " + std::to_string(i) + ": ";
    if (entry.offset != cursor || entry.size == 0 || entry.size > section.size() - cursor)
      throw DracoSectionError(at, mesh + "its stream [" + std::to_string(entry.offset) + ", +" + std::to_string(entry.size) +
                                      ") does not follow the previous one inside the section");
    if (!is_power_of_two_step(entry.position_step) || !is_power_of_two_step(entry.uv_step))
      throw DracoSectionError(at + 8, mesh + "a grid step is not a power of two within 2^±60");
    const MeshArrays m = decode_stream(section.subspan(entry.offset, entry.size), entry, entry.offset,
                                       max_vertices - out.positions.size(), max_triangles - out.triangles.size());
    const gpu::Mesh& record = meshes[i];
    if (record.first_vertex != out.positions.size() || record.vertex_count != m.positions.size() ||
        record.first_triangle != out.triangles.size() || record.triangle_count != m.triangles.size())
      throw DracoSectionError(entry.offset, mesh + "the stream decodes to vertices [" + std::to_string(out.positions.size()) + ", +" +
                                                std::to_string(m.positions.size()) + ") and triangles [" +
                                                std::to_string(out.triangles.size()) + ", +" + std::to_string(m.triangles.size()) +
                                                "), the meshes section says [" + std::to_string(record.first_vertex) + ", +" +
                                                std::to_string(record.vertex_count) + ") and [" + std::to_string(record.first_triangle) +
                                                ", +" + std::to_string(record.triangle_count) + ")");
    out.positions.insert(out.positions.end(), m.positions.begin(), m.positions.end());
    out.normals.insert(out.normals.end(), m.normals.begin(), m.normals.end());
    out.uvs.insert(out.uvs.end(), m.uvs.begin(), m.uvs.end());
    out.triangles.insert(out.triangles.end(), m.triangles.begin(), m.triangles.end());
    cursor += entry.size;
  }
  if (cursor != section.size())
    throw DracoSectionError(cursor, std::to_string(section.size() - cursor) + " bytes follow the last stream");
  return out;
}

}  // namespace nano::format
