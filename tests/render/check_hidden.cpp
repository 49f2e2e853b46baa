// Checks what `render --hide` leaves out against the same view rendered without it (two --ids
// files): the shown frame has pixels of every hidden name (the check is not vacuous), the hidden
// frame has none; a pixel whose shown hit was not hidden keeps exactly that hit (hiding removes
// occluders, never adds any); a pixel whose shown hit was hidden now hits something no nearer, or
// nothing. Compartments come from the hit's compartment instance, molecule types from the hit atom's
// range in section molecules: the package's records, not the renderer's levels or masks.
// Usage: check_hidden PKG SHOWN.ids HIDDEN.ids NAME...
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "format/package_view.hpp"
#include "format/validator.hpp"
#include "runtime/placement/visibility.hpp"
#include "runtime/render/image_io.hpp"
#include "shared/medium.h"

namespace {

using nano::gpu::PixelHit;

struct Classifier {
  const nano::format::PackageView& view;
  const nano::placement::Visibility& hidden;

  std::uint32_t type_of_atom(std::uint32_t atom) const {
    for (std::uint32_t t = 0; t < view.molecules.size(); ++t)
      if (atom >= view.molecules[t].first_atom && atom - view.molecules[t].first_atom < view.molecules[t].atom_count) return t;
    return ~0u;
  }
  bool is_hidden(const PixelHit& h) const {
    if (h.atom == nano::gpu::kNoHit) return false;
    if (h.compartment_instance != nano::gpu::NANO_MEDIUM_OWNER && h.compartment_instance < view.compartment_instances.size() &&
        hidden.compartment_hidden(view.compartment_instances[h.compartment_instance].compartment))
      return true;
    return hidden.molecule_type_hidden(type_of_atom(h.atom));
  }
};

bool same_hit(const PixelHit& a, const PixelHit& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) return std::fprintf(stderr, "usage: check_hidden PKG SHOWN.ids HIDDEN.ids NAME...\n"), 2;
  try {
    const nano::format::Package package = nano::format::open_validated(argv[1]);
    const nano::format::PackageView view(package);
    const std::vector<std::string> names(argv + 4, argv + argc);
    const nano::placement::Visibility hidden = nano::placement::resolve_hidden(package, names);
    const Classifier classify{view, hidden};
    std::uint32_t w = 0, h = 0, hw = 0, hh = 0;
    const std::vector<PixelHit> shown = nano::render::read_ids(argv[2], w, h);
    const std::vector<PixelHit> without = nano::render::read_ids(argv[3], hw, hh);
    if (w != hw || h != hh) return std::fprintf(stderr, "the two ids files differ in size\n"), 1;
    std::size_t shown_hidden = 0, still_hidden = 0, changed = 0, nearer = 0, revealed = 0;
    for (std::size_t p = 0; p < shown.size(); ++p) {
      still_hidden += classify.is_hidden(without[p]);
      if (!classify.is_hidden(shown[p])) {
        changed += !same_hit(shown[p], without[p]);
        continue;
      }
      ++shown_hidden;
      if (without[p].atom != nano::gpu::kNoHit) {
        ++revealed;
        nearer += without[p].depth < shown[p].depth;
      }
    }
    // Each name on its own must have been in the picture, or hiding it proves nothing.
    std::size_t vacuous = 0;
    for (const std::string& name : names) {
      const nano::placement::Visibility one = nano::placement::resolve_hidden(package, std::vector<std::string>{name});
      const Classifier by_name{view, one};
      std::size_t pixels = 0;
      for (const PixelHit& hit : shown) pixels += by_name.is_hidden(hit);
      std::printf("%s: %zu pixels in the shown frame\n", name.c_str(), pixels);
      vacuous += pixels == 0;
    }
    std::printf("%ux%u: %zu pixels showed what is hidden (%zu now show what was behind it); hidden still shown: %zu; "
                "other pixels changed: %zu; revealed nearer than the hidden hit: %zu\n",
                w, h, shown_hidden, revealed, still_hidden, changed, nearer);
    return vacuous == 0 && still_hidden == 0 && changed == 0 && nearer == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "check_hidden: %s\n", e.what());
    return 1;
  }
}
