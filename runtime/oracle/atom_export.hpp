#pragma once
// Writes the atoms of an ExplicitScene inside a world box as CSV, PDB or mmCIF, atomically.
//  CSV:   copy,type,chain,residue,atom,element,x,y,z,radius (copy = Copy::number, type = molecule
//         type index, residue = residue name; text fields quoted when they hold ',' '"' or spaces;
//         empty without atom_info). Coordinates in Å with 6 decimals.
//  PDB:   ATOM/HETATM fixed columns; B-factor = atom radius. Every (copy, source chain) group gets
//         its own chain id, cycling through A-Z a-z 0-9 (62 ids, then wrapping), the source chain
//         goes to segID (cols 73-76); residue numbers outside -999..9999 wrap modulo 10000.
//         Refused (nothing written) beyond 99,999 atoms or outside the 8.3 coordinate columns:
//         use mmCIF for those.
//  mmCIF: one _atom_site loop (readable by gemmi); asym id "<chain>_<copy number>", B = radius.
// Without atom_info, PDB and mmCIF name every atom X of residue UNK 1 in chain A.
#include <cstdint>
#include <filesystem>

#include "runtime/oracle/explicit_scene.hpp"

namespace nano::oracle {

enum class AtomFormat { csv, pdb, mmcif };

// By extension: .csv, .pdb, .cif or .mmcif (any case). Throws InputError naming the path otherwise.
AtomFormat atom_format_of(const std::filesystem::path& path);

struct ExportCounts {
  std::uint64_t copies = 0;  // copies with at least one atom written
  std::uint64_t atoms = 0;
};

inline constexpr std::uint64_t kPdbMaxAtoms = 99999;

// Streams every atom of `scene` inside `box` to `path` through nano::write_file_atomically: on any
// error (I/O, PDB limits, placement) the target is left untouched.
ExportCounts export_atoms(const ExplicitScene& scene, const WorldBox& box, const std::filesystem::path& path,
                          AtomFormat format);

}  // namespace nano::oracle
