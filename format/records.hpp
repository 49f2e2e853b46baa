#pragma once
// Package records: the GPU-visible ones come from shaders/shared/package_records.h; the CPU-only
// per-atom picking metadata is defined here.
#include <cstddef>
#include <cstdint>

#include "shaders/shared/medium.h"
#include "shaders/shared/package_records.h"

namespace nano::format {

// Section "atom_info", parallel to "atoms". Text fields are ASCII, NUL-padded (not NUL-terminated
// when full), as read from PDB/mmCIF.
struct AtomInfo {
  char chain[4];         // auth_asym_id / chain id
  char residue_name[8];  // comp id (3 letters in PDB, up to 5 in mmCIF)
  char atom_name[4];
  char element[2];
  char insertion_code;   // NUL if none
  char alt_location;     // NUL if none
  std::int32_t residue_number;
};
static_assert(sizeof(AtomInfo) == 24 && offsetof(AtomInfo, residue_number) == 20, "AtomInfo layout");

}  // namespace nano::format
