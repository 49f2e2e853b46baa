// Picks the reader by extension, then parses the bytes (parse_proxy_mesh). Each format's reader
// (obj_reader.cpp, off_reader.cpp, ply_reader.cpp, stl_reader.cpp, and collada_reader.cpp through
// Assimp) turns the whole file into a polygon soup; one assembly (polygon_soup.cpp) checks and triangulates every soup alike.
#include "bake/mesh/mesh_reader.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <span>
#include <string>

#include "bake/mesh/draco_codec.hpp"
#include "bake/mesh/polygon_soup.hpp"
#include "common/error.hpp"

namespace nano::mesh {

std::optional<MeshFormat> mesh_format_of(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  if (extension == ".obj") return MeshFormat::obj;
  if (extension == ".off") return MeshFormat::off;
  if (extension == ".ply") return MeshFormat::ply;
  if (extension == ".stl") return MeshFormat::stl;
  if (extension == ".drc") return MeshFormat::draco;
  if (extension == ".dae") return MeshFormat::collada;
  return std::nullopt;
}

ProxyMesh parse_proxy_mesh(std::span<const std::byte> bytes, MeshFormat format, const std::string& file) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  switch (format) {
    case MeshFormat::obj: return assemble_proxy_mesh(read_obj_soup(text, file), file);
    case MeshFormat::off: return assemble_proxy_mesh(read_off_soup(text, file), file);
    case MeshFormat::ply: return assemble_proxy_mesh(read_ply_soup(text, file), file);
    case MeshFormat::stl: return assemble_proxy_mesh(read_stl_soup(text, file), file);
    case MeshFormat::draco: return decode_draco_mesh(bytes, file);
    case MeshFormat::collada: return assemble_proxy_mesh(read_collada_soup(text, file), file);
  }
  throw InputError(file, "", "unknown mesh format");
}

ProxyMesh read_proxy_mesh(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(file, "", "no such file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(file, "", "cannot open the file for reading");
  const std::optional<MeshFormat> format = mesh_format_of(path);
  if (!format)
    throw InputError(file, "", "unsupported mesh format '" + path.extension().string() +
                                   "' (use .obj, .ply, .off, .stl, .drc or .dae)");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(file, "", "cannot read the file");
  return parse_proxy_mesh(std::as_bytes(std::span(bytes.data(), bytes.size())), *format, file);
}

}  // namespace nano::mesh
