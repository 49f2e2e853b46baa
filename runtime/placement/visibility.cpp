#include "runtime/placement/visibility.hpp"

#include <algorithm>

#include "common/error.hpp"
#include "format/package_view.hpp"

namespace nano::placement {

namespace {

bool any_set(const std::vector<std::uint8_t>& flags) {
  return std::any_of(flags.begin(), flags.end(), [](std::uint8_t f) { return f != 0; });
}

// (0, 0) is "no name"; a reference past the section too (the validator refuses one).
std::string name_at(std::span<const char> strings, std::uint32_t offset, std::uint32_t length) {
  if (length == 0 || std::uint64_t(offset) + length > strings.size()) return {};
  return std::string(strings.data() + offset, length);
}

void add_name(std::vector<HideableName>& names, HideableName::Kind kind, std::string name, std::uint32_t index) {
  if (name.empty()) return;
  for (HideableName& n : names)
    if (n.kind == kind && n.name == name) {
      n.indices.push_back(index);
      return;
    }
  names.push_back({kind, std::move(name), {index}});
}

const char* prefix(HideableName::Kind kind) {
  return kind == HideableName::Kind::compartment ? "compartment:" : kind == HideableName::Kind::molecule_type ? "molecule:" : "";
}

bool matches(const HideableName& n, const std::string& text) { return text == n.name || text == prefix(n.kind) + n.name; }

}  // namespace

std::string hideable_listing(std::span<const HideableName> names) {
  std::string text;
  for (const HideableName& n : names) text += (text.empty() ? "" : ", ") + std::string(prefix(n.kind)) + n.name;
  return text.empty() ? "nothing named" : text;
}

std::size_t hideable_matches(std::span<const HideableName> names, const std::string& text) {
  return std::size_t(std::count_if(names.begin(), names.end(), [&](const HideableName& n) { return matches(n, text); }));
}

bool Visibility::hides_compartments() const { return any_set(hidden_compartments); }
bool Visibility::hides_molecule_types() const { return any_set(hidden_molecule_types); }

std::vector<HideableName> hideable_names(const format::Package& package) {
  const format::PackageView view(package);
  const auto strings = package.records<format::SectionKind::strings>();
  std::vector<HideableName> names;
  if (!view.medium.empty()) names.push_back({HideableName::Kind::medium, "medium", {}});
  for (std::uint32_t c = 0; c < view.compartments.size(); ++c)
    add_name(names, HideableName::Kind::compartment, name_at(strings, view.compartments[c].name_offset, view.compartments[c].name_length), c);
  for (std::uint32_t t = 0; t < view.molecules.size(); ++t)
    add_name(names, HideableName::Kind::molecule_type, name_at(strings, view.molecules[t].name_offset, view.molecules[t].name_length), t);
  return names;
}

Visibility resolve_hidden(const format::Package& package, std::span<const std::string> requested, const std::string& option) {
  const std::vector<HideableName> names = hideable_names(package);
  const format::PackageView view(package);
  Visibility v;
  for (const std::string& text : requested) {
    if (text == "medium") continue;
    std::vector<const HideableName*> found;
    for (const HideableName& n : names)
      if (n.kind != HideableName::Kind::medium && matches(n, text)) found.push_back(&n);
    if (found.empty())
      throw InputError(option, "", package.name() + " has no compartment or molecule type named '" + text + "'; it has: " +
                                       hideable_listing(names));
    if (found.size() > 1)
      throw InputError(option, "", "'" + text + "' names both a compartment and a molecule type of " + package.name() +
                                       ": write compartment:" + text + " or molecule:" + text);
    const HideableName& n = *found.front();
    std::vector<std::uint8_t>& flags =
        n.kind == HideableName::Kind::compartment ? v.hidden_compartments : v.hidden_molecule_types;
    flags.resize(n.kind == HideableName::Kind::compartment ? view.compartments.size() : view.molecules.size(), 0);
    for (const std::uint32_t index : n.indices) flags[index] = 1;
  }
  return v;
}

}  // namespace nano::placement
