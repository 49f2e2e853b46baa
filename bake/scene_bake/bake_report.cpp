#include "bake/scene_bake/bake_report.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "bake/scene_bake/molecule_library.hpp"
#include "format/draco_mesh_sections.hpp"
#include "format/section_kind.hpp"
#include "format/writer.hpp"

namespace nano::scene_bake {
namespace {

nlohmann::ordered_json vec(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

std::uint64_t total(const std::vector<std::pair<std::string, std::uint64_t>>& list) {
  std::uint64_t n = 0;
  for (const auto& e : list) n += e.second;
  return n;
}

// The package's stand-in molecule types (name → source), by their source (molecule_library.hpp).
std::map<std::string, std::string> stand_ins(const format::Package& package) {
  std::map<std::string, std::string> found;
  const auto strings = package.records<format::SectionKind::strings>();
  for (const gpu::MoleculeType& m : package.records<format::SectionKind::molecules>()) {
    const std::string source(strings.data() + m.source_offset, m.source_length);
    if (is_stand_in_source(source)) found[std::string(strings.data() + m.name_offset, m.name_length)] = source;
  }
  return found;
}

void write_stand_ins(std::ostream& out, const format::Package& package) {
  for (const auto& [name, source] : stand_ins(package))
    out << "  " << name << " is a STAND-IN, no structure: " << source.substr(kStandInSourcePrefix.size() - 1) << "\n";
}

nlohmann::ordered_json mol_percent_json(const scene::LeafletCounts& kinds) {
  nlohmann::ordered_json shares = nlohmann::ordered_json::object();
  double all = 0.0;
  for (const auto& [name, n] : kinds) all += static_cast<double>(n);
  for (const auto& [name, n] : kinds) shares[name] = all > 0.0 ? 100.0 * static_cast<double>(n) / all : 0.0;
  return shares;
}

// "cholesterol 43.1 %, POPC 26.9 %" of one leaflet's kept copies.
std::string mol_percent_text(const scene::LeafletCounts& kinds) {
  double all = 0.0;
  for (const auto& [name, n] : kinds) all += static_cast<double>(n);
  std::string text;
  char share[64];
  for (const auto& [name, n] : kinds) {
    std::snprintf(share, sizeof share, "%.1f %%", all > 0.0 ? 100.0 * static_cast<double>(n) / all : 0.0);
    text += (text.empty() ? "" : ", ") + name + " " + share;
  }
  return text;
}

nlohmann::ordered_json membrane_json(const MembraneSummary& m) {
  nlohmann::ordered_json per_species = nlohmann::ordered_json::object(), dropped = nlohmann::ordered_json::object();
  for (const auto& [name, n] : m.lipids) per_species[name] = n / m.area_um2;
  for (const auto& [name, n] : m.dropped) dropped[name] = n;
  nlohmann::ordered_json alternates = nlohmann::ordered_json::object();
  for (const auto& [name, n] : m.alternates) alternates[name] = n;
  nlohmann::ordered_json unfit = nlohmann::ordered_json::object();
  for (const auto& [name, n] : m.unfit) unfit[name] = n;
  const double lipids = total(m.lipids) / m.area_um2;
  const MembraneSummary::ByLeaflet leaflets = m.fraction_of_real_leaflets_beside_proteins();
  const MembraneSummary::ByLeaflet areas = m.leaflet_areas();
  return {{"area_um2", m.area_um2},
          {"lipids_per_um2", per_species},
          {"lipids_per_um2_total", lipids},
          {"real_bilayer_lipids_per_um2", m.real_lipids_per_um2()},
          {"fraction_of_real_bilayer", lipids / m.real_lipids_per_um2()},
          {"lipids_by_leaflet", {{"outer", m.outer_lipids}, {"inner", m.inner_lipids}}},
          {"mol_percent_by_leaflet", {{"outer", mol_percent_json(m.outer_kinds)}, {"inner", mol_percent_json(m.inner_kinds)}}},
          {"leaflet_area_um2", {{"outer", areas.outer}, {"inner", areas.inner}}},
          {"protein_area_um2", {{"outer", m.outer_protein_um2}, {"inner", m.inner_protein_um2}}},
          {"fraction_of_real_bilayer_beside_proteins", m.fraction_of_real_bilayer_beside_proteins()},
          {"fraction_of_real_leaflet_beside_proteins", {{"outer", leaflets.outer}, {"inner", leaflets.inner}}},
          {"dropped", dropped},
          {"dropped_where_no_prism_fits", unfit},
          {"alternates_shown", alternates},
          {"pruned", m.pruned_everywhere ? "everywhere" : "along UV seams and on checked triangles"},
          {"pruning_checked_triangles", m.checked_triangles},
          {"pruning_checked_copies", m.checked_copies},
          {"pruning_atom_pairs", m.atom_pairs},
          {"pruning_copy_pairs_tested", m.copy_pairs_tested}};
}

// What the package's mesh data takes in the file: the four mesh sections plus any Draco streams.
std::uint64_t mesh_stored_bytes(const format::Package& package) {
  std::uint64_t stored = 0;
  for (format::SectionKind k : format::kDracoCodedKinds)
    if (const format::SectionEntry* e = package.entry(k)) stored += e->stored_size;
  if (const format::SectionEntry* e = package.entry(format::SectionKind::draco_meshes)) stored += e->stored_size;
  return stored;
}

// The mesh sections both ways, measured on this package: as zstd stores them (each section zstd
// where that is smaller) and as Draco streams (format/draco_mesh_sections.hpp), and which one the
// file holds. Draco is measured even when zstd won, unless the meshes are off Draco's grids.
nlohmann::ordered_json mesh_section_sizes(const format::Package& package) {
  using format::SectionKind;
  std::uint64_t zstd = 0, raw = 0;
  for (SectionKind k : format::kDracoCodedKinds) {
    zstd += format::zstd_stored_size(package.raw_bytes(k));
    raw += package.raw_bytes(k).size();
  }
  nlohmann::ordered_json j;
  const format::SectionEntry* streams = package.entry(SectionKind::draco_meshes);
  j["codec"] = streams ? "draco" : "zstd";  // the reader accepts the streams only with all four sections Draco-coded
  if (streams) {
    j["draco_bytes"] = streams->stored_size;
  } else {
    const format::DracoEncoding draco = format::encode_draco_meshes(
        package.records<SectionKind::meshes>(), package.records<SectionKind::vertex_positions>(),
        package.records<SectionKind::vertex_normals>(), package.records<SectionKind::vertex_uvs>(),
        package.records<SectionKind::triangles>(), format::kDefaultDracoSpeed);
    if (draco.why.empty()) j["draco_bytes"] = draco.section.size();
    else j["draco_unavailable"] = draco.why;
  }
  j["zstd_bytes"] = zstd;
  j["stored_bytes"] = mesh_stored_bytes(package);
  j["raw_bytes"] = raw;
  return j;
}

// The medium as the report gives it (its copies estimated, medium_bake.hpp).
nlohmann::ordered_json medium_json(const MediumSummary& m) {
  nlohmann::ordered_json counts = nlohmann::ordered_json::object();
  for (const MediumMoleculeCount& n : m.counts) counts[n.name] = {{"copies", n.copies}, {"atoms", n.atoms}};
  nlohmann::ordered_json fields = nlohmann::ordered_json::array();
  for (const MediumSummary::Field& f : m.fields)
    fields.push_back({{"compartment", f.compartment}, {"spacing_A", f.spacing}, {"margin_A", f.margin}, {"reach_A", {f.least_reach, f.largest_reach}},
                      {"measured_excess_A", f.measured_excess}, {"bytes", f.bytes}});
  return {{"soluble", m.soluble},
          {"region", {vec(m.region_min), vec(m.region_max)}},
          {"boxes", {m.boxes.x, m.boxes.y, m.boxes.z}},
          {"copies_in_region", m.copies_in_region},
          {"estimated", counts},
          {"exclusion_fields", fields}};
}

// The medium's lines of the summary.
void write_medium_summary(std::ostringstream& out, const MediumSummary& m) {
  char line[512];
  std::snprintf(line, sizeof line, "  medium %s: %u x %u x %u boxes over [%.0f, %.0f, %.0f]-[%.0f, %.0f, %.0f] Å, about",
                m.soluble.c_str(), m.boxes.x, m.boxes.y, m.boxes.z, m.region_min.x, m.region_min.y, m.region_min.z,
                m.region_max.x, m.region_max.y, m.region_max.z);
  out << line;
  double atoms = 0;
  for (const MediumMoleculeCount& n : m.counts) {
    std::snprintf(line, sizeof line, " %.3g %s,", n.copies, n.name.c_str());
    out << line;
    atoms += n.atoms;
  }
  std::snprintf(line, sizeof line, " %.3g atoms (estimated from the excluded volumes)\n", atoms);
  out << line;
  for (const MediumSummary::Field& f : m.fields) {
    std::snprintf(line, sizeof line,
                  "  medium keeps clear of %s's membrane (%.0f-%.0f Å from its triangles) by a field of %.0f Å spacing, margin %.1f Å, %.2f MB\n",
                  f.compartment.c_str(), f.least_reach, f.largest_reach, f.spacing, f.margin, f.bytes / 1e6);
    out << line;
  }
}

nlohmann::ordered_json estimate_json(const BakeEstimate& e) {
  nlohmann::ordered_json estimate;
  estimate["cpu_seconds"] = e.cpu_seconds;
  estimate["wall_seconds"] = e.wall_seconds;
  estimate["peak_memory_bytes"] = e.peak_bytes;
  for (const StageEstimate& s : e.stages) estimate["stages"][s.stage] = {{"work", s.work}, {"cpu_seconds", s.cpu_seconds}};
  for (const MemoryTerm& t : e.memory) estimate["memory"][t.what] = t.bytes;
  for (const CompartmentEstimate& c : e.compartments)
    for (const auto& [name, copies] : c.copies) estimate["copies"][c.name][name] = copies;
  return estimate;
}

}  // namespace

nlohmann::ordered_json bake_report(const BakedScene& scene, const format::Package& package) {
  nlohmann::ordered_json j;
  j["represented_atoms"] = scene.represented_atoms;
  j["hydrogens"] = "counted when the structure files hold them (see each molecule's reader flags)";
  auto& compartments = j["compartments"] = nlohmann::ordered_json::array();
  for (const CompartmentSummary& c : scene.compartments) {
    nlohmann::ordered_json copies = nlohmann::ordered_json::object();
    for (const auto& [name, n] : c.copies) copies[name] = n;
    compartments.push_back({{"name", c.name},
                            {"mesh", c.mesh_origin},
                            {"triangles", c.triangles},
                            {"represented_atoms", c.represented_atoms},
                            {"copies", copies},
                            {"core_boxes", {{"inside", c.core_boxes_inside}, {"boundary", c.core_boxes_boundary}}},
                            {"replication_area", {c.replication_width, c.replication_height}}});
    compartments.back()["mesh_scale"] = c.mesh_scale;
    compartments.back()["uvs"] = c.uv_origin;
    compartments.back()["mesh_storage"] = c.mesh_storage;
    if (c.membrane) compartments.back()["shells_from_cache"] = c.shells_from_cache;
    if (c.bilayer_thickness > 0.0)
      compartments.back()["membrane_fit"] = {{"bilayer_thickness_A", c.bilayer_thickness},
                                             {"thinnest_wall_A", std::isfinite(c.thinnest_wall) ? nlohmann::ordered_json(c.thinnest_wall) : nlohmann::ordered_json(nullptr)}};
    if (c.charts) compartments.back()["charts"] = mesh::to_json(*c.charts);
    if (c.repair) compartments.back()["repair"] = mesh::to_json(*c.repair);
    if (c.remesh) compartments.back()["remesh"] = mesh::to_json(*c.remesh);
    if (c.membrane) compartments.back()["membrane"] = membrane_json(*c.membrane);
  }
  if (scene.medium) j["medium"] = medium_json(*scene.medium);
  auto& instances = j["instances"] = nlohmann::ordered_json::array();
  for (const InstanceSummary& i : scene.instances)
    instances.push_back({{"compartment", i.compartment}, {"aabb", {vec(i.aabb_min), vec(i.aabb_max)}}});
  auto& densities = j["densities"] = nlohmann::ordered_json::array();
  for (const WangSetSummary& s : scene.wang_sets)
    for (const tiles::MoleculeDensity& d : s.densities)
      densities.push_back({{"set", s.name}, {"molecule", d.name}, {"requested", d.requested}, {"achieved", d.achieved},
                           {"set_from_cache", s.from_cache}});
  auto& surfaces = j["membrane_surfaces"] = nlohmann::ordered_json::object();
  for (const WangSetSummary& s : scene.wang_sets)
    if (s.surface)
      surfaces[s.name] = {{"chart_stretch", 1.0 + s.surface->lateral_stretch},
                          {"curvature", s.surface->curvature},
                          {"normal_tilt", s.surface->tilt},
                          {"facet_sag", s.surface->max_rise}};
  // The level of detail per molecule type: how many beads stand for how many atoms.
  auto& lod = j["level_of_detail"] = nlohmann::ordered_json::object();
  const auto molecules = package.records<format::SectionKind::molecules>();
  const auto ranges = package.records<format::SectionKind::bead_ranges>();
  const auto strings = package.records<format::SectionKind::strings>();
  // Lipid conformers share their species' name: one entry per name, its types summed.
  for (std::size_t t = 0; t < molecules.size() && t < ranges.size(); ++t) {
    const gpu::MoleculeType& m = molecules[t];
    auto& entry = lod[std::string(strings.data() + m.name_offset, m.name_length)];
    if (entry.is_null()) entry = {{"types", 0}, {"atoms", 0}, {"beads", 0}};
    entry["types"] = entry["types"].get<std::uint64_t>() + 1;
    entry["atoms"] = entry["atoms"].get<std::uint64_t>() + m.atom_count;
    entry["beads"] = entry["beads"].get<std::uint64_t>() + ranges[t].count;
  }
  j["stand_ins"] = stand_ins(package);
  j["mesh_sections"] = mesh_section_sizes(package);
  auto& sections = j["sections"] = nlohmann::ordered_json::object();
  for (const format::SectionEntry& e : package.entries())
    sections[format::section_kind_name(e.kind)] = e.stored_size;
  j["package_bytes"] = package.file_size();
  auto& stages = j["stages"] = nlohmann::ordered_json::object();
  for (const auto& [name, seconds] : scene.stage_seconds) stages[name] = seconds;
  auto& stages_cpu = j["stages_cpu"] = nlohmann::ordered_json::object();
  for (const auto& [name, seconds] : scene.stage_cpu_seconds) stages_cpu[name] = seconds;
  auto& stages_peak = j["stages_peak_memory_bytes"] = nlohmann::ordered_json::object();
  for (const auto& [name, bytes] : scene.stage_peak_bytes) stages_peak[name] = bytes;
  // The estimate made before the heavy stages beside what they then took (bake_estimate.hpp).
  j["estimate"] = estimate_json(scene.estimate);
  j["warnings"] = scene.warnings;
  if (const auto& cached = scene.estimate_with_cache)
    j["estimate_with_cache"] = {{"cpu_seconds", cached->cpu_seconds},
                                {"peak_memory_bytes", cached->peak_bytes},
                                {"why", "the same estimate with the shells and tile sets the bake cache served left out"}};
  j["measured"] = {{"cpu_seconds_after_estimate", process_cpu_seconds() - scene.cpu_seconds_at_estimate},
                   {"peak_memory_bytes", peak_resident_bytes()}};
  return j;
}

namespace {

// Each Wang set: read from the bake cache or what it was packed to survive, and its densities.
void describe_wang_sets(std::ostringstream& out, const BakedScene& scene) {
  char line[512];
  for (const WangSetSummary& s : scene.wang_sets) {
    if (s.from_cache) out << "  " << s.name << ": tile set read from the bake cache (the same request was packed before; --no-cache packs it)\n";
    if (s.surface) {
      std::snprintf(line, sizeof line,
                    "  %s: packed to stay clash-free under chart stretches up to %.3g, normals turning %.3g rad/Å "
                    "and tilting %.3g from their faces (facets sag %.3g Å)\n",
                    s.name.c_str(), 1.0 + s.surface->lateral_stretch, s.surface->curvature, s.surface->tilt,
                    s.surface->max_rise);
      out << line;
    }
    for (const tiles::MoleculeDensity& d : s.densities) {
      std::snprintf(line, sizeof line, "  %s/%s: density %.4g of %.4g requested\n", s.name.c_str(), d.name.c_str(),
                    d.achieved, d.requested);
      out << line;
    }
  }
}

}  // namespace

std::string bake_summary(const BakedScene& scene, const format::Package& package) {
  std::ostringstream out;
  char line[512];
  std::snprintf(line, sizeof line, "%s: %zu compartment(s), %zu instance(s), %.3g represented atoms, %.2f MB\n",
                package.name().c_str(), scene.compartments.size(), scene.instances.size(),
                static_cast<double>(scene.represented_atoms), package.file_size() / 1e6);
  out << line;
  write_stand_ins(out, package);
  for (const CompartmentSummary& c : scene.compartments) {
    std::snprintf(line, sizeof line, "  %s: %.3g atoms per copy", c.name.c_str(), static_cast<double>(c.represented_atoms));
    out << line;
    for (const auto& [name, n] : c.copies) {
      std::snprintf(line, sizeof line, ", %s %.3g", name.c_str(), static_cast<double>(n));
      out << line;
    }
    out << "\n";
    if (c.repair) out << "  " << c.name << " mesh " << mesh::describe(*c.repair) << "\n";
    if (c.remesh) out << "  " << c.name << " mesh " << mesh::describe(*c.remesh) << "\n";
    if (c.charts) {
      std::snprintf(line, sizeof line,
                    "  %s UVs %s: %zu charts, seam %.4g Å, stretch max %.3f (mean %.3f), %.0f%% of the UV square used, %.2f s\n",
                    c.name.c_str(), c.uv_origin.c_str(), c.charts->charts.size(), c.charts->seam_length, c.charts->max_stretch,
                    c.charts->mean_stretch, 100.0 * c.charts->packing_efficiency, c.charts->seconds);
      out << line;
    }
    if (c.membrane) {
      const MembraneSummary& m = *c.membrane;
      const double lipids = total(m.lipids) / m.area_um2;
      const MembraneSummary::ByLeaflet leaflets = m.fraction_of_real_leaflets_beside_proteins();
      const MembraneSummary::ByLeaflet areas = m.leaflet_areas();
      std::snprintf(line, sizeof line,
                    "  %s membrane: %.4g µm², %.3g lipids/µm² (%.0f%% of a real bilayer's %.3g; %.0f%% beside the proteins, "
                    "%.0f%% / %.0f%% in the outer / inner leaflet, which they take %.0f%% / %.0f%% of)",
                    c.name.c_str(), m.area_um2, lipids, 100.0 * lipids / m.real_lipids_per_um2(), m.real_lipids_per_um2(),
                    100.0 * m.fraction_of_real_bilayer_beside_proteins(), 100.0 * leaflets.outer,
                    100.0 * leaflets.inner, 100.0 * m.outer_protein_um2 / areas.outer,
                    100.0 * m.inner_protein_um2 / areas.inner);
      out << line;
      for (const auto& [name, n] : m.lipids) {
        std::snprintf(line, sizeof line, ", %s %.3g", name.c_str(), n / m.area_um2);
        out << line;
      }
      const std::string checked = m.pruned_everywhere ? std::string("everywhere")
                                                       : "along UV seams and on " + std::to_string(m.checked_triangles) + " of " +
                                                             std::to_string(m.triangles) + " triangles";
      std::snprintf(line, sizeof line, "; %.3g copies dropped (clashing, checked %s, or beyond a count), %.3g alternates shown in their place\n",
                    static_cast<double>(total(m.dropped)), checked.c_str(), static_cast<double>(total(m.alternates)));
      out << line;
      if (m.outer_kinds.size() > 1 || m.inner_kinds.size() > 1)
        out << "    mol % outer leaflet: " << mol_percent_text(m.outer_kinds)
            << "; inner leaflet: " << mol_percent_text(m.inner_kinds) << "\n";
      for (const auto& [name, n] : m.unfit) {
        std::snprintf(line, sizeof line, "    %.3g %s left out where the surface folds too tightly for it (placed elsewhere if counted per compartment)\n",
                      static_cast<double>(n), name.c_str());
        out << line;
      }      if (c.shells_from_cache) out << "    shells and pruning read from the bake cache (the same inputs were baked before; --no-cache bakes them)\n";
    }
  }
  if (scene.medium) write_medium_summary(out, *scene.medium);
  std::snprintf(line, sizeof line, "  meshes: %s, %.1f kB\n",
                package.has(format::SectionKind::draco_meshes) ? "Draco streams (on Draco's exact grids)" : "zstd",
                mesh_stored_bytes(package) / 1e3);
  out << line;
  describe_wang_sets(out, scene);
  out << "  stages:";
  for (const auto& [name, seconds] : scene.stage_seconds) {
    std::snprintf(line, sizeof line, " %s %.2fs;", name.c_str(), seconds);
    out << line;
  }
  out << "\n";
  return out.str();
}

}  // namespace nano::scene_bake
