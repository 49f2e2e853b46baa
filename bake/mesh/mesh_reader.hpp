#pragma once
// Loads a proxy mesh from OBJ, PLY, OFF, STL, Draco .drc or Collada .dae. The four text-or-binary
// formats have readers of our own (one file each, sharing polygon_soup.hpp), written to accept what
// the formats allow (comments anywhere, every PLY encoding and type, n-gons, negative OBJ indices)
// and to keep the face list as written: check-mesh then sees every defect (non-manifold edges,
// degenerate triangles) at the face index of the file, where a half-edge builder would quietly
// repair it. Draco goes through libdraco (draco_codec.hpp), Collada through Assimp
// (collada_reader.cpp), whose scene becomes a polygon soup checked by the same rules.
//
// Collada (cellPACK's geometry format): every mesh every node of the <visual_scene> places, with
// the nodes' transforms applied (a mirroring one reverses the faces' corners, so what faced out
// still does; a mesh two nodes instance comes twice); faces in that order, depth first through
// the nodes. Lines and points are skipped. Coordinates are Assimp's single-precision floats
// (the nearest float to what is written), transformed in double. <unit meter="..."> and <up_axis>
// are ignored: coordinates are taken as written, in the scene's "units" (Å by default), never
// rescaled or rotated. The cellPACK database files looked at (HIV envelope and capsid, an Env
// ingredient, a pycollada-written surface) declare <unit meter="0.01" name="centimeter"/> and
// <up_axis>Y_UP</up_axis> (Cinema 4D's and pycollada's defaults) while their coordinates are Å (HIV1_envelope_Pack_145_0_2_0.dae: a radius of 725, the 145 nm
// envelope), and cellPACK itself reads them with pycollada, which applies neither.
// Assimp never prints (no logger); its error message goes into the InputError. A .dae is refused
// before Assimp reads it when it is not XML text (a zipped .zae included), has more than 512 MiB,
// declares a count, offset or stride that is not a decimal whole number or exceeds the file's
// size, an <input> offset above 31, a <p> or <vcount> holding other than digits, signs and blanks
// (Assimp 5.2 loops on any other character in <p>), a <triangles>, <polylist> or <polygons> whose
// count disagrees with its <p> elements (Debian's Assimp aborts on an assertion), or primitives of
// more than 12,582,912 corners; and after it, when the nodes place more than 4,194,304 faces.
// Assimp reads a negative index in <p> as 0. What gets past these checks and still crashes Assimp
// (a misspelt <float_array> count: a null dereference, found by fuzzing, docs/tests.md) cannot
// crash the reader's process: Assimp runs in a process of its own (this executable started again),
// and a crash there, an import running over 60 s (then stopped) or needing more than 4 GiB of
// address space (16 times the file's size if more) is an InputError naming the file (and the
// signal). Only the polygons come back, checked like a file's; Collada is fuzzed like the rest.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <string>

#include "bake/mesh/proxy_mesh.hpp"

namespace nano::mesh {

enum class MeshFormat { obj, off, ply, stl, draco, collada };

// The format a file name's extension names (.obj, .off, .ply, .stl, .drc, .dae, in any case), or nullopt.
std::optional<MeshFormat> mesh_format_of(const std::filesystem::path& path);

// Faces are triangulated in file order, so triangle i of an all-triangle file is face i (0-based).
// A quad is cut along its shorter diagonal (a tie: the 0–2 one); a larger polygon becomes a fan
// from its first corner; a corner repeated in a row ("4 a b c c") counts once. Coordinates are read
// as doubles, exactly as written. Bit-identical positions are welded. Normals are taken from the
// file when every corner has one, otherwise computed (angle-weighted); UVs are kept per corner when
// every corner has one. Throws nano::InputError naming the file and, where one helps, the line and
// the face or vertex (0-based) on: a missing or unreadable file, an unknown extension, a parse
// failure, a truncated file or counts larger than it could hold, a face that references a missing
// vertex, UV or normal, a face with fewer than 3 distinct vertices or through one vertex twice,
// non-finite coordinates or UVs, or a file with no faces (Draco: draco_codec.hpp). A mesh without
// UVs loads (has_uvs() is false) so that check-mesh can report it as a problem.
ProxyMesh read_proxy_mesh(const std::filesystem::path& path);

// The same from the file's bytes in memory, in the format given (what read_proxy_mesh does once it
// has read the file): every rule above, each error naming `file` (which is only a label here).
ProxyMesh parse_proxy_mesh(std::span<const std::byte> bytes, MeshFormat format, const std::string& file);

}  // namespace nano::mesh
