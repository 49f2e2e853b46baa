#include "bake/scene_bake/tile_set_cache.hpp"

#include <cmath>
#include <string_view>

#include "bake/scene_bake/stage_bytes.hpp"

namespace nano::scene_bake {

namespace {

// A kind tag first, so a membrane request and a cube request never share a key.
enum class TileSetKind : std::uint32_t { membrane_squares = 1, soluble_cubes = 2 };

// Every field but `threads`, which the set does not depend on.
void add_budget(ShellStageKey& key, const tiles::GenerationBudget& b) {
  key.add(b.clearance);
  key.add(b.attempts_per_copy);
  key.add(b.max_consecutive_failures);
  key.add(b.relaxation_rounds);
}

void add_patch(ShellStageKey& key, const tiles::LipidPatch& patch) {
  key.add_instances(patch.lipids);
  key.add(patch.period_x);
  key.add(patch.period_y);
  key.add(patch.clearance);
  key.add(std::uint64_t(patch.mix.size()));
  for (const tiles::LipidSpecies& s : patch.mix) {
    key.add_instances(s.conformers);
    key.add(s.outer);
    key.add(s.inner);
  }
}

// What both kinds of request begin with; `budget` and `seed` close every key.
ShellStageKey start_key(TileSetKind kind, const std::vector<tiles::MoleculeType>& types, float edge, int colours) {
  ShellStageKey key;
  key.add(kind);
  key.add(baker_build_hash());
  key.add_types(types);
  key.add(edge);
  key.add(colours);
  return key;
}

void end_key(ShellStageKey& key, std::uint64_t seed, const tiles::GenerationBudget& budget) {
  key.add(seed);
  add_budget(key, budget);
}

}  // namespace

ShellStageKey tile_set_key(const tiles::MembraneTileRequest& r) {
  ShellStageKey key = start_key(TileSetKind::membrane_squares, r.types, r.edge, r.colours);
  key.add(std::uint64_t(r.molecules.size()));
  for (const tiles::MembraneMolecule& m : r.molecules) {
    key.add(m.type);
    key.add(m.copies_per_um2);
    key.add(m.depth);
    key.add(std::uint8_t(m.lipids_displaced_on_surface));
  }
  key.add(std::uint8_t(r.lipids.has_value()));
  if (r.lipids) {
    key.add(r.lipids->type);
    key.add(r.lipids->area_per_lipid);
    key.add(r.lipids->leaflet_offset);
  }
  key.add(std::uint8_t(r.lipid_patch.has_value()));
  if (r.lipid_patch) add_patch(key, *r.lipid_patch);
  key.add(r.surface.lateral_stretch);
  key.add(r.surface.curvature);
  key.add(r.surface.tilt);
  key.add(r.surface.max_rise);
  end_key(key, r.seed, r.budget);
  return key;
}

ShellStageKey tile_set_key(const tiles::SolubleCubeRequest& r) {
  ShellStageKey key = start_key(TileSetKind::soluble_cubes, r.types, r.edge, r.colours);
  key.add(r.variants);
  key.add(std::uint64_t(r.molecules.size()));
  for (const tiles::SolubleMolecule& m : r.molecules) {
    key.add(m.type);
    key.add(m.copies_per_um3);
  }
  end_key(key, r.seed, r.budget);
  return key;
}

std::vector<std::byte> encode_wang_set(const tiles::WangSet& set) {
  StageWriter w;
  w.put(std::int32_t(set.dims));
  w.put(set.edge);
  w.put(std::int32_t(set.colouring.dims));
  w.put(std::int32_t(set.colouring.colours));
  w.put(std::int32_t(set.colouring.variants));
  w.put(std::uint64_t(set.colouring.tiles.size()));
  w.put_all(set.colouring.tiles);
  w.put(std::uint64_t(set.tiles.size()));
  for (const tiles::WangTile& t : set.tiles) {
    w.put(t.colours);
    w.put(t.atoms_min);
    w.put(t.atoms_max);
    w.put(std::uint64_t(t.instances.size()));
    for (const tiles::Instance& i : t.instances) {
      w.put(i.type);
      w.put(i.position);
      w.put(i.rotation);
      w.put(std::uint8_t(i.alternate));
      w.put(std::uint8_t(i.has_alternate));
    }
  }
  w.put(std::uint64_t(set.densities.size()));
  for (const tiles::MoleculeDensity& d : set.densities) {
    w.put(std::uint64_t(d.name.size()));
    w.put_all(std::vector<char>(d.name.begin(), d.name.end()));
    w.put(d.type);
    w.put(d.requested);
    w.put(d.achieved);
    w.put(std::uint64_t(d.copies_in_set));
  }
  return w.bytes;
}

namespace {

std::string get_instance(StageReader& r, std::size_t types, tiles::Instance& i) {
  std::uint8_t alternate = 0, has_alternate = 0;
  if (!r.get(i.type) || !r.get(i.position) || !r.get(i.rotation) || !r.get(alternate) || !r.get(has_alternate))
    return "it ends inside a tile's copies";
  if (i.type >= types) return "a copy names molecule type " + std::to_string(i.type) + " of " + std::to_string(types);
  if (alternate > 1 || has_alternate > 1) return "a copy's flags are neither 0 nor 1";
  if (!std::isfinite(i.position.x) || !std::isfinite(i.position.y) || !std::isfinite(i.position.z)) return "a copy stands at a non-finite place";
  i.alternate = alternate == 1, i.has_alternate = has_alternate == 1;
  return "";
}

// A colouring a set can have: colours 1..255, its tile count what the colours and variants make,
// every side colour one of them (the recipe indexes tiles by these).
std::string check_colouring(const tiles::WangColouring& c) {
  if (c.colours < 1 || c.colours > 255 || c.variants < 0) return "its colours or variants are not a set's";
  std::uint64_t combinations = 1;
  for (int side = 0; side < (c.complete() ? 2 : 1) * c.dims; ++side) combinations *= std::uint64_t(c.colours);
  const std::uint64_t expected = c.complete() ? combinations : combinations * std::uint64_t(c.variants);
  if (c.tiles.size() != expected) return "its colouring holds " + std::to_string(c.tiles.size()) + " tiles, not " + std::to_string(expected);
  for (const tiles::SideColours& t : c.tiles)
    for (int axis = 0; axis < c.dims; ++axis)
      if (t[axis][0] >= c.colours || t[axis][1] >= c.colours) return "a tile side has a colour the set does not";
  return "";
}

std::string get_tiles(StageReader& r, std::size_t types, tiles::WangSet& set) {
  std::uint64_t count = 0;
  if (!r.get(count) || count != set.colouring.tiles.size()) return "its tiles are not one per colouring";
  set.tiles.resize(count);
  for (tiles::WangTile& t : set.tiles) {
    std::uint64_t copies = 0;
    if (!r.get(t.colours) || !r.get(t.atoms_min) || !r.get(t.atoms_max) || !r.get(copies)) return "it ends inside a tile";
    if (copies > (std::uint64_t{1} << 32)) return "a tile holds more copies than any set";
    t.instances.resize(copies);
    for (tiles::Instance& i : t.instances)
      if (std::string wrong = get_instance(r, types, i); !wrong.empty()) return wrong;
  }
  return "";
}

std::string get_densities(StageReader& r, std::size_t types, tiles::WangSet& set) {
  std::uint64_t count = 0;
  if (!r.get(count) || count > types) return "its densities are not one per molecule";
  set.densities.resize(count);
  for (tiles::MoleculeDensity& d : set.densities) {
    std::uint64_t length = 0, copies = 0;
    std::vector<char> name;
    if (!r.get(length) || !r.get_all(name, length) || !r.get(d.type) || !r.get(d.requested) || !r.get(d.achieved) ||
        !r.get(copies))
      return "it ends inside the densities";
    d.name.assign(name.begin(), name.end());
    d.copies_in_set = copies;
  }
  return "";
}

}  // namespace

std::optional<tiles::WangSet> decode_wang_set(std::span<const std::byte> bytes, std::size_t types, std::string& why) {
  StageReader r(bytes);
  tiles::WangSet set;
  std::int32_t dims = 0, colouring_dims = 0, colours = 0, variants = 0;
  std::uint64_t colourings = 0;
  if (!r.get(dims) || !r.get(set.edge) || !r.get(colouring_dims) || !r.get(colours) || !r.get(variants) ||
      !r.get(colourings) || !r.get_all(set.colouring.tiles, colourings)) {
    why = "it ends before its tiles";
    return std::nullopt;
  }
  if ((dims != 2 && dims != 3) || colouring_dims != dims || !(set.edge > 0.f) || !std::isfinite(set.edge)) {
    why = "its dimensions or tile edge are not a set's";
    return std::nullopt;
  }
  set.dims = dims, set.colouring.dims = colouring_dims, set.colouring.colours = colours, set.colouring.variants = variants;
  why = check_colouring(set.colouring);
  if (why.empty()) why = get_tiles(r, types, set);
  if (why.empty()) why = get_densities(r, types, set);
  if (why.empty() && !r.done()) why = "bytes follow the set";
  if (!why.empty()) return std::nullopt;
  return set;
}

namespace {

constexpr std::string_view kTileSetMagic = "NUTILES ";

template <typename Request, typename Make>
tiles::WangSet cached_set(const Request& request, const std::optional<std::filesystem::path>& cache, bool& from_cache,
                          Make make) {
  from_cache = false;
  if (!cache || baker_build_hash() == 0) return make(request);
  const ShellStageKey key = tile_set_key(request);
  if (std::optional<tiles::WangSet> kept = load_wang_set(*cache, key, request.types.size())) {
    from_cache = true;
    return std::move(*kept);
  }
  tiles::WangSet set = make(request);
  store_wang_set(*cache, key, set);
  return set;
}

}  // namespace

std::filesystem::path tile_set_cache_file(const std::filesystem::path& directory, const ShellStageKey& key) {
  return directory / ("tiles-" + key.hex() + ".bin");
}

std::optional<tiles::WangSet> load_wang_set(const std::filesystem::path& directory, const ShellStageKey& key, std::size_t types) {
  const std::filesystem::path file = tile_set_cache_file(directory, key);
  const std::optional<std::vector<std::byte>> bytes = read_cached_file(file);
  if (!bytes) return std::nullopt;
  std::string why;
  std::optional<tiles::WangSet> set;
  if (const auto payload = unwrap_cached_stage(*bytes, kTileSetMagic, key, why)) set = decode_wang_set(*payload, types, why);
  if (!set) cached_file_unusable(file, why);
  else cached_file_used(file);
  return set;
}

void store_wang_set(const std::filesystem::path& directory, const ShellStageKey& key, const tiles::WangSet& set) {
  write_cached_file(directory, tile_set_cache_file(directory, key), wrap_cached_stage(kTileSetMagic, key, encode_wang_set(set)));
}

tiles::WangSet cached_membrane_tiles(const tiles::MembraneTileRequest& request,
                                     const std::optional<std::filesystem::path>& cache, bool& from_cache) {
  return cached_set(request, cache, from_cache, [](const tiles::MembraneTileRequest& r) { return tiles::make_membrane_tiles(r); });
}

tiles::WangSet cached_soluble_cubes(const tiles::SolubleCubeRequest& request,
                                    const std::optional<std::filesystem::path>& cache, bool& from_cache) {
  return cached_set(request, cache, from_cache, [](const tiles::SolubleCubeRequest& r) { return tiles::make_soluble_cubes(r); });
}

}  // namespace nano::scene_bake
