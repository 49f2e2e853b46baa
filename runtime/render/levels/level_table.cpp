#include "runtime/render/levels/level_table.hpp"

#include "runtime/render/levels/atoms.hpp"
#include "runtime/render/levels/beads.hpp"
#include "runtime/render/levels/core.hpp"
#include "runtime/render/levels/flat.hpp"
#include "runtime/render/levels/medium.hpp"
#include "runtime/render/levels/membrane.hpp"
#include "runtime/render/levels/sections.hpp"
#include "runtime/render/levels/ulas.hpp"

namespace nano::levels {
namespace {

// Build order is table order, and it fixes the layout of the orders buffer; the flat level comes
// before the µLAS, whose instance records name each instance's first triangle bit.
constexpr LevelEntry kLevels[] = {
    {LevelId::sections, "sections", "the package's sections as storage buffers, in place where the device reads mapped pages",
     &render::LoadReport::upload_seconds, nullptr, build_sections, write_section_descriptors, nullptr},
    {LevelId::atoms, "atoms", "nLAS: per molecule type its atoms' boxes in molecule space",
     &render::LoadReport::nlas_seconds, nullptr, build_atoms, nullptr, nullptr},
    {LevelId::beads, "beads", "per molecule type its coarse beads (level of detail, format ≥ 2.5)",
     &render::LoadReport::nlas_seconds, nullptr, build_beads, nullptr, nullptr},
    {LevelId::membrane, "membrane", "shell prisms, Wang-square mLAS per distortion class, repLAS per compartment (+ atom squares for --levels 2)",
     &render::LoadReport::mlas_seconds, plan_membrane, build_membrane, write_membrane_descriptors, nullptr},
    {LevelId::core, "core", "Wang-cube mLAS and the kept boxes of the core grids' boundary boxes",
     &render::LoadReport::mlas_seconds, plan_core, build_core, write_core_descriptors, nullptr},
    {LevelId::flat, "flat", "the membrane copies nearest the eye as TLAS instances, within the flatten budget",
     &render::LoadReport::ulas_seconds, nullptr, build_flat, write_flat_descriptors, set_flat_eye},
    {LevelId::ulas, "µLAS", "per compartment its prisms and core box; the instance TLAS relative to the eye",
     &render::LoadReport::ulas_seconds, nullptr, build_ulas, write_ulas_descriptors, set_ulas_eye},
    {LevelId::medium, "medium", "the periodic region between the cells and the exclusion fields that keep it clear of them",
     &render::LoadReport::ulas_seconds, nullptr, build_medium, write_medium_descriptors, set_medium_eye},
};

static_assert(std::size(kLevels) == kLevelCount, "one row per LevelId");

constexpr bool rows_in_id_order() {
  for (std::size_t i = 0; i < std::size(kLevels); ++i)
    if (static_cast<std::size_t>(kLevels[i].id) != i) return false;
  return true;
}
static_assert(rows_in_id_order(), "row i declares LevelId i");

}  // namespace

std::span<const LevelEntry> level_table() { return kLevels; }

}  // namespace nano::levels
