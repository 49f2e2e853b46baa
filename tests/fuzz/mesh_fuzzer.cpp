// libFuzzer target: arbitrary bytes through one mesh reader (parse_proxy_mesh, the path
// read_proxy_mesh takes once it has the file's bytes). Built once per format, NANO_FUZZ_MESH_FORMAT
// naming it (obj, off, ply, stl or draco: targets obj_fuzzer ... draco_fuzzer), so that each format
// gets a campaign and a report of its own. Rejection as an InputError is the expected outcome;
// anything else (another exception, a crash, a sanitizer report, a leak, an allocation over
// -rss_limit_mb, a hang) is a finding, and so is an accepted mesh that breaks what
// bake/mesh/proxy_mesh.hpp and mesh_reader.hpp promise: faces, indices in range, finite welded
// positions, UVs per corner of every triangle or none, unit normals per corner of every triangle.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <span>
#include <string>
#include <unordered_set>
#include <vector>

#include "bake/mesh/mesh_reader.hpp"
#include "common/error.hpp"

#ifndef NANO_FUZZ_MESH_FORMAT
#error "NANO_FUZZ_MESH_FORMAT must name the format (obj, off, ply, stl or draco)"
#endif

namespace {

using namespace nano::mesh;

constexpr MeshFormat kFormat = MeshFormat::NANO_FUZZ_MESH_FORMAT;

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

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    check(parse_proxy_mesh(std::as_bytes(std::span(data, size)), kFormat, "fuzz/mesh"));
  } catch (const nano::InputError&) {
  }
  return 0;
}
