#include "bake/mesh/draco_codec.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>

#include <draco/compression/config/compression_shared.h>
#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/core/draco_types.h>
#include <draco/core/varint_decoding.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>

#include "bake/mesh/vertex_normals.hpp"
#include "common/error.hpp"

namespace nano::mesh {
namespace {

template <int N> std::array<float, N> as_floats(const glm::vec<N, double>& v) {
  std::array<float, N> out{};
  for (int i = 0; i < N; ++i) out[i] = float(v[i]);
  return out;
}

// What read_corners found of an attribute.
struct CornerRead {
  enum Status { read, absent, corrupt, non_finite } status = read;
  std::size_t face = 0;  // the first face with a value that is corrupt or not finite
};

// The attribute's value at corner c of face f as N floats. libdraco leaves it to the caller to check
// that the value is there: a point index past the mesh's points or the attribute's mapping, or a
// value past its buffer, would be read from whatever memory follows (a hostile file can say so).
template <int N>
CornerRead::Status value_at(const draco::Mesh& m, const draco::PointAttribute& attribute, draco::FaceIndex f, int c,
                            std::array<float, N>& value) {
  const draco::PointIndex point = m.face(f)[c];
  if (point.value() >= m.num_points()) return CornerRead::corrupt;
  if (!attribute.is_mapping_identity() && point.value() >= attribute.indices_map_size()) return CornerRead::corrupt;
  const draco::AttributeValueIndex index = attribute.mapped_index(point);
  const draco::DataBuffer* buffer = attribute.buffer();
  if (index.value() >= attribute.size() || !buffer || attribute.byte_offset() < 0 || attribute.byte_stride() < 0)
    return CornerRead::corrupt;
  const std::int64_t end = attribute.byte_offset() + attribute.byte_stride() * std::int64_t(index.value()) +
                           std::int64_t(attribute.num_components()) * draco::DataTypeLength(attribute.data_type());
  if (end > std::int64_t(buffer->data_size())) return CornerRead::corrupt;
  if (!attribute.ConvertValue<float>(index, N, value.data())) return CornerRead::absent;
  for (const float x : value)
    if (!std::isfinite(x)) return CornerRead::non_finite;
  return CornerRead::read;
}

// Per-corner values of a Draco attribute, deduplicated into (values, per-triangle indices). Stops at
// the first value that is corrupt or not finite (before it reaches the map, whose order NaN breaks).
template <int N>
CornerRead read_corners(const draco::Mesh& m, draco::GeometryAttribute::Type type, std::vector<glm::vec<N, double>>& values,
                        std::vector<Triangle>& corners) {
  const draco::PointAttribute* attribute = m.GetNamedAttribute(type);
  if (!attribute || attribute->num_components() < N) return {CornerRead::absent};
  // Numbers only: a file may declare an attribute of bools, whose bytes libdraco would load as bool
  // whatever they hold (undefined unless 0 or 1).
  if (attribute->data_type() < draco::DT_INT8 || attribute->data_type() > draco::DT_FLOAT64) return {CornerRead::absent};
  std::map<std::array<float, N>, std::uint32_t> index;
  for (draco::FaceIndex f(0); f < m.num_faces(); ++f) {
    Triangle t{};
    for (int c = 0; c < 3; ++c) {
      std::array<float, N> v{};
      if (const CornerRead::Status status = value_at<N>(m, *attribute, f, c, v); status != CornerRead::read)
        return {status, f.value()};
      const auto [it, added] = index.try_emplace(v, std::uint32_t(values.size()));
      if (added) {
        glm::vec<N, double> d;
        for (int i = 0; i < N; ++i) d[i] = v[i];
        values.push_back(d);
      }
      t[c] = it->second;
    }
    corners.push_back(t);
  }
  return {};
}

// ---- what a Draco file declares before libdraco allocates for it ----
//
// libdraco sizes its tables by the counts a file declares, before reading anything they count: a
// 60-byte file declaring a billion faces makes it allocate some 30 GB (zero-filled, so really
// used), and a metadata entry declaring 4 GB of value gets a 4 GB buffer. The header, the metadata
// and the connectivity counts are therefore read here first, as libdraco 1.5 reads them
// (docs/spec in the Draco repository), and a file declaring more than the limits below, or
// metadata that runs past its end, is refused before libdraco sees it.

// As many faces as any proxy mesh has (the baker takes at most 4 million triangles:
// scene_feasibility.hpp, mesh_check.hpp), three points a face at most; libdraco allocates some 32
// bytes per declared face and some 40 per declared point.
constexpr std::uint64_t kMaxDracoFaces = std::uint64_t{1} << 22;
constexpr std::uint64_t kMaxDracoPoints = 3 * kMaxDracoFaces;
constexpr int kMaxMetadataDepth = 32;

// Reads as libdraco reads (its own buffer and varint decoder: a varint of more than 32 bits wraps
// there, and must wrap here too, or the counts here would not be libdraco's).
class DracoHeaderReader {
public:
  explicit DracoHeaderReader(std::span<const std::byte> bytes) {
    buffer_.Init(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  }
  bool u8(std::uint32_t& out) {
    std::uint8_t v = 0;
    return buffer_.Decode(&v) ? (out = v, true) : false;
  }
  bool u16(std::uint32_t& out) {
    std::uint16_t v = 0;
    return buffer_.Decode(&v) ? (out = v, true) : false;
  }
  bool u32(std::uint32_t& out) { return buffer_.Decode(&out); }
  bool varint(std::uint32_t& out) { return draco::DecodeVarint(&out, &buffer_); }
  bool skip(std::uint64_t n) {
    if (n > left()) return false;
    buffer_.Advance(std::int64_t(n));
    return true;
  }
  std::uint64_t left() const { return std::uint64_t(buffer_.remaining_size()); }

private:
  draco::DecoderBuffer buffer_;
};

// One metadata element (entries, then named sub-elements), each count within the bytes left.
bool skip_metadata(DracoHeaderReader& in, int depth) {
  std::uint32_t entries = 0, subs = 0, length = 0;
  if (depth > kMaxMetadataDepth || !in.varint(entries) || entries > in.left()) return false;
  for (std::uint32_t e = 0; e < entries; ++e)
    if (!in.u8(length) || !in.skip(length) || !in.varint(length) || length == 0 || !in.skip(length)) return false;
  if (!in.varint(subs) || subs > in.left()) return false;
  for (std::uint32_t k = 0; k < subs; ++k)
    if (!in.u8(length) || !in.skip(length) || !skip_metadata(in, depth + 1)) return false;
  return true;
}

// Refuses a Draco mesh that declares more faces or points than kMaxDraco*, or whose metadata does
// not fit in it. A file that ends or has a version or method libdraco does not know is left to
// libdraco, which refuses it.
void check_draco_declarations(std::span<const std::byte> bytes, const std::string& file) {
  DracoHeaderReader in(bytes);
  std::uint32_t major = 0, minor = 0, type = 0, method = 0, flags = 0;
  if (!in.skip(5) || !in.u8(major) || !in.u8(minor) || !in.u8(type) || !in.u8(method) || !in.u16(flags)) return;
  if (type != draco::TRIANGULAR_MESH || major < 1 || major > 2 || (major == 2 && minor > 2)) return;
  const std::uint32_t version = major << 8 | minor;
  if (version >= 0x0103 && (flags & METADATA_FLAG_MASK)) {
    std::uint32_t attribute_metadata = 0, id = 0;
    bool fits = in.varint(attribute_metadata) && attribute_metadata <= in.left();
    for (std::uint32_t a = 0; fits && a < attribute_metadata; ++a) fits = in.varint(id) && skip_metadata(in, 0);
    if (!fits || !skip_metadata(in, 0)) throw InputError(file, "", "the Draco metadata runs past the end of the file (corrupt file)");
  }
  // Counts are 32-bit words before bitstream 2.0 (2.2 for sequential meshes), varints since.
  const auto count = [&](std::uint32_t& out, std::uint32_t varint_since) { return version >= varint_since ? in.varint(out) : in.u32(out); };
  std::uint32_t faces = 0, points = 0;
  if (method == draco::MESH_SEQUENTIAL_ENCODING) {
    if (!count(faces, 0x0202) || !count(points, 0x0202)) return;
  } else if (method == draco::MESH_EDGEBREAKER_ENCODING) {
    std::uint32_t traversal = 0, new_vertices = 0, attribute_data = 0, symbols = 0, split_symbols = 0;
    if (!in.u8(traversal) || (version < 0x0202 && !count(new_vertices, 0x0200)) || !count(points, 0x0200) ||
        !count(faces, 0x0200) || !in.u8(attribute_data) || !count(symbols, 0x0200) || !count(split_symbols, 0x0200))
      return;
    points = std::uint32_t(std::min<std::uint64_t>(std::uint64_t{points} + split_symbols, 0xffffffffu));
  } else {
    return;
  }
  if (faces > kMaxDracoFaces || points > kMaxDracoPoints)
    throw InputError(file, "", "the Draco file declares " + std::to_string(faces) + " faces and " + std::to_string(points) +
                                   " points, more than this reader decodes (" + std::to_string(kMaxDracoFaces) + " and " +
                                   std::to_string(kMaxDracoPoints) + "; libdraco would allocate for them all first)");
}

void refuse_corrupt(const CornerRead& read, const char* what, const std::string& file) {
  if (read.status == CornerRead::corrupt)
    throw InputError(file, "face " + std::to_string(read.face),
                     std::string("refers to a ") + what + " the Draco buffer does not hold (corrupt file)");
}

}  // namespace

std::vector<std::byte> encode_draco_mesh(const ProxyMesh& mesh, const DracoQuantisation& q) {
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(int(mesh.triangles.size()));
  const int position = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int uv = mesh.has_uvs() ? builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32) : -1;
  const int normal = mesh.has_normals() ? builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32) : -1;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const draco::FaceIndex f(static_cast<std::uint32_t>(t));
    const auto p0 = as_floats(mesh.corner_position(t, 0)), p1 = as_floats(mesh.corner_position(t, 1)),
               p2 = as_floats(mesh.corner_position(t, 2));
    builder.SetAttributeValuesForFace(position, f, p0.data(), p1.data(), p2.data());
    if (uv >= 0) {
      const auto a = as_floats(mesh.corner_uv(t, 0)), b = as_floats(mesh.corner_uv(t, 1)), c = as_floats(mesh.corner_uv(t, 2));
      builder.SetAttributeValuesForFace(uv, f, a.data(), b.data(), c.data());
    }
    if (normal >= 0) {
      const auto a = as_floats(mesh.corner_normal(t, 0)), b = as_floats(mesh.corner_normal(t, 1)),
                 c = as_floats(mesh.corner_normal(t, 2));
      builder.SetAttributeValuesForFace(normal, f, a.data(), b.data(), c.data());
    }
  }
  const std::unique_ptr<draco::Mesh> built = builder.Finalize();
  if (!built) throw std::runtime_error("Draco could not build the mesh");
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, q.position_bits);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, q.uv_bits);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, q.normal_bits);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(*built, &buffer);
  if (!status.ok()) throw std::runtime_error("Draco could not encode the mesh: " + status.error_msg_string());
  std::vector<std::byte> out(buffer.size());
  std::memcpy(out.data(), buffer.data(), buffer.size());
  return out;
}

ProxyMesh decode_draco_mesh(std::span<const std::byte> bytes, const std::string& file) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  const auto geometry = draco::Decoder::GetEncodedGeometryType(&buffer);
  if (!geometry.ok()) throw InputError(file, "", "not a Draco file: " + geometry.status().error_msg_string());
  if (geometry.value() != draco::TRIANGULAR_MESH) throw InputError(file, "", "a Draco point cloud, not a triangle mesh");
  check_draco_declarations(bytes, file);
  std::unique_ptr<draco::Mesh> decoded;
  try {
    draco::Decoder decoder;
    auto result = decoder.DecodeMeshFromBuffer(&buffer);
    if (!result.ok()) throw InputError(file, "", "Draco cannot decode it: " + result.status().error_msg_string());
    decoded = std::move(result).value();
  } catch (const std::bad_alloc&) {  // what the limits above leave: libdraco's sizes are its own
    throw InputError(file, "", "Draco cannot decode it: it asks for more memory than there is");
  } catch (const std::length_error&) {
    throw InputError(file, "", "Draco cannot decode it: it asks for more memory than there is");
  }
  const draco::Mesh& m = *decoded;
  if (m.num_faces() == 0) throw InputError(file, "", "mesh has no faces");
  ProxyMesh mesh;
  const CornerRead positions = read_corners<3>(m, draco::GeometryAttribute::POSITION, mesh.positions, mesh.triangles);
  if (positions.status == CornerRead::absent) throw InputError(file, "", "the Draco mesh has no readable positions");
  refuse_corrupt(positions, "position", file);
  if (positions.status == CornerRead::non_finite)
    throw InputError(file, "face " + std::to_string(positions.face), "coordinate is not a finite number");
  const CornerRead uvs = read_corners<2>(m, draco::GeometryAttribute::TEX_COORD, mesh.uvs, mesh.uv_triangles);
  refuse_corrupt(uvs, "texture coordinate", file);
  if (uvs.status == CornerRead::non_finite)
    throw InputError(file, "face " + std::to_string(uvs.face), "texture coordinate is not a finite number");
  if (uvs.status != CornerRead::read) mesh.uvs.clear(), mesh.uv_triangles.clear();
  const CornerRead file_normals = read_corners<3>(m, draco::GeometryAttribute::NORMAL, mesh.normals, mesh.normal_triangles);
  refuse_corrupt(file_normals, "normal", file);
  bool normals = file_normals.status == CornerRead::read;  // not finite: computed instead, as when absent
  for (glm::dvec3& n : mesh.normals) {
    if (const std::optional<glm::dvec3> unit = unit_direction(n)) n = *unit;
    else normals = false;
  }
  if (!normals) {
    mesh.normals.clear(), mesh.normal_triangles.clear();
    compute_angle_weighted_normals(mesh);
  }
  return mesh;
}

}  // namespace nano::mesh
