// box_clashes PKG xmin ymin zmin xmax ymax zmax [min_copies]: every atom that virtual instancing
// places in the box, instantiated explicitly, must keep 0.6 × (r1 + r2) from every atom of another
// copy. Exit 0 when clash-free and at least `min_copies` copies were found (so an empty box cannot
// pass), 1 otherwise.
#include <cstdio>
#include <cstdlib>
#include <set>
#include <vector>

#include "format/validator.hpp"
#include "runtime/explicit/clash_check.hpp"
#include "runtime/explicit/explicit_scene.hpp"

int main(int argc, char** argv) {
  if (argc < 8) {
    std::fprintf(stderr, "usage: box_clashes PKG xmin ymin zmin xmax ymax zmax [min_copies]\n");
    return 2;
  }
  const nano::format::Package package = nano::format::open_validated(argv[1]);
  const nano::oracle::ExplicitScene scene(package);
  nano::oracle::WorldBox box;
  box.min = {std::atof(argv[2]), std::atof(argv[3]), std::atof(argv[4])};
  box.max = {std::atof(argv[5]), std::atof(argv[6]), std::atof(argv[7])};
  const std::size_t min_copies = argc > 8 ? std::strtoull(argv[8], nullptr, 10) : 1;

  std::vector<nano::oracle::ClashAtom> atoms;
  std::set<std::uint64_t> copies;
  scene.for_each_atom(box, [&](const nano::oracle::AtomSample& a) {
    atoms.push_back({a.copy->number, a.position, a.radius});
    copies.insert(a.copy->number);
  });
  const nano::oracle::ClashReport report = nano::oracle::find_clashes(atoms);
  std::printf("%s: %zu copies, %zu atoms, %llu clashing pairs\n", argv[1], copies.size(), atoms.size(),
              static_cast<unsigned long long>(report.count));
  for (std::size_t i = 0; i < report.pairs.size() && i < 10; ++i) {
    const auto& c = report.pairs[i];
    std::printf("  copies %llu and %llu: %.3f Å < %.3f Å\n", static_cast<unsigned long long>(atoms[c.a].copy),
                static_cast<unsigned long long>(atoms[c.b].copy), c.distance, c.limit);
  }
  return report.count == 0 && copies.size() >= min_copies ? 0 : 1;
}
