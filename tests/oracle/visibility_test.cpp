// What --hide names (runtime/placement/visibility.hpp) and what the CPU enumerator then leaves out:
// names against the format tests' sample package (molecules "haemoglobin" and "band3", compartment
// "membrane", a medium), copies against the hand scene (every copy of a hidden compartment and of a
// hidden type gone, every other copy still there, the same).
#include "runtime/placement/visibility.hpp"

#include <map>

#include <gtest/gtest.h>

#include "common/error.hpp"
#include "format/package.hpp"
#include "runtime/placement/copy_enumerator.hpp"
#include "tests/format/sample_scene.hpp"
#include "tests/oracle/hand_scene.hpp"

namespace nano::placement {
namespace {

format::Package sample_package() { return format::Package::from_bytes(format::test::build(format::test::make_sample_scene())); }

TEST(Visibility, NamesAreThePackagesMediumCompartmentsAndMolecules) {
  const format::Package package = sample_package();
  const std::vector<HideableName> names = hideable_names(package);
  ASSERT_EQ(names.size(), 4u);
  EXPECT_EQ(names[0].kind, HideableName::Kind::medium);
  EXPECT_EQ(names[1].name, "membrane");
  EXPECT_EQ(names[1].kind, HideableName::Kind::compartment);
  EXPECT_EQ(names[2].name, "haemoglobin");
  EXPECT_EQ(names[3].name, "band3");
  EXPECT_EQ(hideable_listing(names), "medium, compartment:membrane, molecule:haemoglobin, molecule:band3");
  EXPECT_EQ(hideable_matches(names, "band3"), 1u);
  EXPECT_EQ(hideable_matches(names, "molecule:band3"), 1u);
  EXPECT_EQ(hideable_matches(names, "compartment:band3"), 0u);
}

TEST(Visibility, ResolvesNamesToFlags) {
  const format::Package package = sample_package();
  const std::vector<std::string> nothing;
  EXPECT_FALSE(resolve_hidden(package, nothing).hides_anything());
  EXPECT_FALSE(resolve_hidden(package, std::vector<std::string>{"medium"}).hides_anything());  // the caller's switch
  const Visibility v = resolve_hidden(package, std::vector<std::string>{"band3", "compartment:membrane"});
  EXPECT_TRUE(v.compartment_hidden(0));
  EXPECT_FALSE(v.molecule_type_hidden(0));
  EXPECT_TRUE(v.molecule_type_hidden(1));
  EXPECT_FALSE(v.molecule_type_hidden(7));  // beyond the package: nothing to hide
}

TEST(Visibility, AnUnknownNameListsTheNamesThereAre) {
  const format::Package package = sample_package();
  try {
    (void)resolve_hidden(package, std::vector<std::string>{"haemoglobin", "band 3"});
    FAIL() << "'band 3' resolved";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "--hide");
    EXPECT_NE(e.rule().find("no compartment or molecule type named 'band 3'"), std::string::npos) << e.rule();
    EXPECT_NE(e.rule().find("molecule:band3"), std::string::npos) << e.rule();
  }
}

TEST(Visibility, ANameSharedByACompartmentAndAMoleculeMustBeQualified) {
  format::test::SampleScene scene = format::test::make_sample_scene();
  scene.compartments[0].name_offset = 15;  // "band3", as molecule 1
  scene.compartments[0].name_length = 5;
  const format::Package package = format::Package::from_bytes(format::test::build(scene));
  EXPECT_THROW((void)resolve_hidden(package, std::vector<std::string>{"band3"}), InputError);
  EXPECT_TRUE(resolve_hidden(package, std::vector<std::string>{"compartment:band3"}).compartment_hidden(0));
  EXPECT_TRUE(resolve_hidden(package, std::vector<std::string>{"molecule:band3"}).molecule_type_hidden(1));
}

using Copies = std::map<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>>;  // number → (instance, type)

Copies enumerate(const format::Package& package, const Visibility& v) {
  CopyOptions options;
  options.visibility = v;
  Copies copies;
  CopyEnumerator(package, options).for_each_copy(WorldBox::everything(), [&](const Copy& c) {
    copies[c.number] = {c.id.compartment_instance, c.molecule_type};
  });
  return copies;
}

TEST(Visibility, TheEnumeratorLeavesOutHiddenCompartmentsAndTypesAndNothingElse) {
  const std::vector<explicit_test::Placement> placements = explicit_test::default_placements();
  const format::Package package = format::Package::from_bytes(format::test::build(explicit_test::hand_scene(placements)));
  const Copies all = enumerate(package, {});
  Visibility v;
  v.hidden_compartments = {0, 0, 1};  // the core grid
  v.hidden_molecule_types = {0, 1};   // type 1
  const Copies shown = enumerate(package, v);
  std::size_t expected = 0, hidden_types = 0, hidden_core = 0;
  for (const auto& [number, what] : all) {
    const bool core = placements[what.first].compartment == 2;
    hidden_core += core;
    hidden_types += what.second == 1;
    if (core || what.second == 1) {
      EXPECT_EQ(shown.count(number), 0u) << number;
      continue;
    }
    ++expected;
    ASSERT_EQ(shown.count(number), 1u) << number;
    EXPECT_EQ(shown.at(number), what);
  }
  EXPECT_EQ(shown.size(), expected);
  EXPECT_GT(hidden_core, 0u);  // both switches had copies to remove
  EXPECT_GT(hidden_types, 0u);
}

}  // namespace
}  // namespace nano::placement
