// Picks the reader by extension. Each format's reader (obj_reader.cpp, off_reader.cpp,
// ply_reader.cpp, stl_reader.cpp) turns the whole file into a polygon soup; one assembly
// (polygon_soup.cpp) checks and triangulates every soup alike.
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

ProxyMesh read_proxy_mesh(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(file, "", "no such file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(file, "", "cannot open the file for reading");
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  using SoupReader = PolygonSoup (*)(std::string_view, const std::string&);
  SoupReader read_soup = nullptr;
  if (extension == ".obj") read_soup = read_obj_soup;
  else if (extension == ".off") read_soup = read_off_soup;
  else if (extension == ".ply") read_soup = read_ply_soup;
  else if (extension == ".stl") read_soup = read_stl_soup;
  else if (extension != ".drc")
    throw InputError(file, "", "unsupported mesh format '" + extension + "' (use .obj, .ply, .off, .stl or .drc)");

  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(file, "", "cannot read the file");
  if (!read_soup) return decode_draco_mesh(std::as_bytes(std::span(bytes.data(), bytes.size())), file);
  return assemble_proxy_mesh(read_soup(bytes, file), file);
}

}  // namespace nano::mesh
