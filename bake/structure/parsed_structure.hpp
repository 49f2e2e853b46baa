#pragma once
// What a format parser hands over: every atom record of every model, nothing filtered yet.
#include <string>
#include <vector>

#include "bake/structure/atom.hpp"

namespace nano::structure {

struct ParsedStructure {
  std::vector<Atom> atoms;  // file order
  int model_count = 0;      // models that hold at least one atom record
};

}  // namespace nano::structure
