// libFuzzer target: arbitrary bytes through one mesh reader (parse_proxy_mesh, the path
// read_proxy_mesh takes once it has the file's bytes). fuzz_mesh is nano_fuzzer's reader for all six
// formats (obj, off, ply, stl, draco, collada), the format an argument: NANO_FUZZ_READER picks one
// per process (fuzz_main.cpp), so that each format gets a campaign and a report of its own.
// Collada's Assimp runs in a process of its own (collada_reader.cpp): what it does not survive there
// is an InputError here, as it is in nanobake; its time and address space are held below
// libFuzzer's -timeout and -rss_limit_mb. Rejection as an InputError is the expected outcome;
// anything else (another exception, a crash, a sanitizer report, a leak, an allocation over
// -rss_limit_mb, a hang) is a finding, and so is an accepted mesh that breaks what
// bake/mesh/proxy_mesh.hpp and mesh_reader.hpp promise: faces, indices in range, finite welded
// positions, UVs per corner of every triangle or none, unit normals per corner of every triangle.
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

#include "bake/mesh/mesh_reader.hpp"
#include "bake/mesh/polygon_soup.hpp"
#include "common/error.hpp"

namespace {

using namespace nano::mesh;

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "mesh fuzzer: accepted mesh %s\n", what.c_str());
  std::abort();
}

template <int N> bool finite(const glm::vec<N, double>& v) {
  for (int i = 0; i < N; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

template <typename Value>
void check_indices(const std::vector<Triangle>& triangles, const std::vector<Value>& values, const char* what) {
  for (const Triangle& t : triangles)
    for (const std::uint32_t i : t)
      if (i >= values.size()) finding(std::string("has a triangle referencing a missing ") + what);
}

void check(const ProxyMesh& mesh) {
  if (mesh.triangles.empty()) finding("has no triangles");
  check_indices(mesh.triangles, mesh.positions, "position");
  std::unordered_set<std::string> seen;  // welded: no two positions bit-identical
  for (const glm::dvec3& p : mesh.positions) {
    if (!finite(p)) finding("holds a non-finite position");
    if (!seen.emplace(reinterpret_cast<const char*>(&p), sizeof p).second) finding("holds two bit-identical positions");
  }
  if (mesh.has_uvs()) {
    if (mesh.uv_triangles.size() != mesh.triangles.size()) finding("has UVs for some triangles only");
    check_indices(mesh.uv_triangles, mesh.uvs, "UV");
    for (const glm::dvec2& uv : mesh.uvs)
      if (!finite(uv)) finding("holds a non-finite UV");
  }
  if (mesh.normal_triangles.size() != mesh.triangles.size()) finding("has no normal at some corner");
  check_indices(mesh.normal_triangles, mesh.normals, "normal");
  for (const glm::dvec3& n : mesh.normals)
    if (!finite(n) || std::abs(std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z) - 1.0) > 1e-9)
      finding("holds a normal that is not a finite unit vector");
}

ProxyMesh parse(MeshFormat format, std::span<const std::byte> bytes) {
  if (format == MeshFormat::collada) {
    // 5 s under libFuzzer's -timeout of 10, 1 GiB under nanobake's 4 (a sanitizer build counts
    // only its large allocations against it: the small ones come from space reserved at its start).
    const ColladaImportLimits limits{.time = std::chrono::seconds(5), .address_space = std::uint64_t{1} << 30};
    const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    return assemble_proxy_mesh(read_collada_soup(text, "fuzz/mesh", limits), "fuzz/mesh");
  }
  return parse_proxy_mesh(bytes, format, "fuzz/mesh");
}

}  // namespace

namespace nano::fuzz {

void fuzz_mesh(mesh::MeshFormat format, std::span<const std::byte> bytes) {
  try {
    check(parse(format, bytes));
  } catch (const InputError&) {
  }
}

}  // namespace nano::fuzz
