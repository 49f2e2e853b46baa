#pragma once
// The mesh sections (vertex_positions, vertex_normals, vertex_uvs, triangles) stored as Draco
// streams in section "draco_meshes", one stream per record of "meshes" (format 2.6; layout in
// docs/format.md). Draco serves here as a lossless codec of integers: the package defines exact grids
// (positions and UVs on power-of-two steps, normals as 16-bit octahedral pairs), so decoding gives
// back the baked floats bit for bit on any machine, whatever Draco's own float arithmetic. Draco
// renumbers vertices and triangles, so writer and reader agree on one canonical order that depends
// only on the values (canonical_mesh_order). The only translation unit of format/ with Draco.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "format/section_kind.hpp"
#include "shaders/shared/package_records.h"

namespace nano::format {

// The sections codec draco serves, always together: the rows of format/section_table.hpp whose codecs
// column says mesh.
namespace draco_detail {
constexpr std::size_t coded_kind_count() {
  std::size_t n = 0;
  for (const SectionInfo& row : kSectionTable) n += row.codecs == SectionCodecs::mesh;
  return n;
}
}  // namespace draco_detail
inline constexpr std::array<SectionKind, draco_detail::coded_kind_count()> kDracoCodedKinds = [] {
  std::array<SectionKind, draco_detail::coded_kind_count()> kinds{};
  std::size_t n = 0;
  for (const SectionInfo& row : kSectionTable)
    if (row.codecs == SectionCodecs::mesh) kinds[n++] = row.kind;
  return kinds;
}();
static_assert(kDracoCodedKinds == std::array{SectionKind::vertex_positions, SectionKind::vertex_normals,
                                             SectionKind::vertex_uvs, SectionKind::triangles},
              "the Draco streams (below) code exactly positions, normals, UVs and triangles");
// "vertex_positions, vertex_normals, vertex_uvs and triangles", for messages.
inline std::string draco_coded_kind_names() {
  std::string names;
  for (std::size_t i = 0; i < kDracoCodedKinds.size(); ++i)
    names += (i == 0 ? "" : i + 1 == kDracoCodedKinds.size() ? " and " : ", ") + section_kind_name(kDracoCodedKinds[i]);
  return names;
}

// One mesh's arrays as the package stores them; triangle indices are local to the mesh.
struct MeshArrays {
  std::vector<glm::vec4> positions;  // xyz, w = 0
  std::vector<glm::vec4> normals;    // unit xyz, w = 0
  std::vector<glm::vec2> uvs;
  std::vector<gpu::Triangle> triangles;
};

// Bit-for-bit equality (so -0 differs from +0 and NaN equals itself): what "decodes exactly" means.
bool same_bits(const MeshArrays& a, const MeshArrays& b);

// The octahedral normal grid: a pair of integers in [-kOctahedralMax, kOctahedralMax].
inline constexpr int kOctahedralMax = 32767;
// A unit normal of the grid (w = 0), computed in double and rounded: the same floats everywhere.
glm::vec4 decode_octahedral(std::int32_t a, std::int32_t b);
// The grid pair nearest to `normal` (need not be unit; must be non-zero and finite).
std::pair<std::int32_t, std::int32_t> encode_octahedral(const glm::vec4& normal);
// decode(encode(n)) repeated until it stops changing (at most a few rounds): a normal on the grid,
// or the last round's if none is reached (then Draco storage refuses the mesh, zstd keeps it).
glm::vec4 snap_normal_to_grid(const glm::vec4& normal);

// Integers of a grid step are bounded so Draco's parallelogram predictions (a + b - c) fit in 32 bits.
inline constexpr std::int64_t kMaxGridInteger = std::int64_t{1} << 28;
// The coarsest power of two `step` such that every value is an exact multiple of it with
// |value / step| <= kMaxGridInteger; nullopt if there is none or a value is not finite or is -0.
// All-zero values give step 1.
std::optional<float> power_of_two_grid(std::span<const float> values);
// The position step a baker snaps to so that Draco pays: 2^-5 Å (0.03 Å, far below an atom), or
// coarser for meshes so large that 2^-5 Å would need integers beyond kMaxGridInteger.
float storage_position_step(double largest_magnitude);
// Nearest multiple of `step` (a power of two), with -0 made +0.
float snap_to_step(double value, float step);

// Vertices deduplicated and sorted by their bits, each triangle rotated (orientation kept) to start
// at its smallest vertex, triangles sorted. The same output for any renumbering of the same mesh.
// Throws std::invalid_argument if array sizes disagree or an index is out of range.
MeshArrays canonical_mesh_order(const MeshArrays& mesh);

// Why a mesh cannot be stored as Draco (empty if it can): off its grids, not canonical, or Draco
// failed to reproduce it.
struct DracoEncoding {
  std::vector<std::byte> section;  // the whole "draco_meshes" section, empty when `why` is set
  std::string why;
};
// Draco's speed setting (0 smallest in general ... 10 fastest): 2 is smallest on these integer
// attributes (red blood cell 68.3 kB at 2, 72.7 at 0, 71.0 at 5, 98.1 at 10; its mesh decodes in 4 ms).
inline constexpr int kDefaultDracoSpeed = 2;

// Encodes every mesh of the four sections (ranges from `meshes`, which must tile them in order) and
// decodes the result again to prove it exact.
DracoEncoding encode_draco_meshes(std::span<const gpu::Mesh> meshes, std::span<const glm::vec4> positions,
                                  std::span<const glm::vec4> normals, std::span<const glm::vec2> uvs,
                                  std::span<const gpu::Triangle> triangles, int speed = kDefaultDracoSpeed);

// A defect of a "draco_meshes" section: where (byte offset in its raw bytes) and what.
class DracoSectionError : public std::runtime_error {
public:
  DracoSectionError(std::uint64_t offset, const std::string& what) : std::runtime_error(what), offset_(offset) {}
  std::uint64_t offset() const { return offset_; }

private:
  std::uint64_t offset_;
};

// The four sections' records decoded from a "draco_meshes" section. Trusts nothing: the directory,
// every stream, and that mesh i decodes to exactly the counts and ranges `meshes[i]` claims (meshes
// tile the sections in order). `max_vertices` / `max_triangles` stop it before it allocates more.
// Throws DracoSectionError.
MeshArrays decode_draco_meshes(std::span<const std::byte> section, std::span<const gpu::Mesh> meshes,
                               std::uint64_t max_vertices, std::uint64_t max_triangles);

// The mesh of `meshes[index]` copied out of the four sections (index checked; throws std::out_of_range).
MeshArrays mesh_arrays(std::span<const gpu::Mesh> meshes, std::size_t index, std::span<const glm::vec4> positions,
                       std::span<const glm::vec4> normals, std::span<const glm::vec2> uvs,
                       std::span<const gpu::Triangle> triangles);

}  // namespace nano::format
