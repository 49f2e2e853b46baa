#include "bake/structure/inspect_report.hpp"

#include <gtest/gtest.h>

namespace nano::structure {
namespace {

Molecule three_atoms() {
  Molecule m;
  m.source = "m.pdb";
  m.model_count = 2;
  m.warnings = {"something odd"};
  const char* chains[] = {"B", "A", "B"};
  const char* elements[] = {"C", "N", "C"};
  for (int i = 0; i < 3; ++i) {
    Atom a;
    a.chain = chains[i];
    a.element = elements[i];
    a.position = glm::dvec3(i, 2 * i, -i);
    a.radius = 1.0;
    a.hetatm = i == 2;
    m.atoms.push_back(a);
  }
  return m;
}

TEST(InspectReport, JsonCarriesTheAgreedKeys) {
  const Molecule m = three_atoms();
  const nlohmann::json j = inspect_report_json(m, compute_molecule_properties(m.atoms));
  EXPECT_EQ(j["file"], "m.pdb");
  EXPECT_EQ(j["format"], "pdb");
  EXPECT_EQ(j["atoms"], 3);
  EXPECT_EQ(j["hetatm_atoms"], 1);
  EXPECT_EQ(j["models"], 2);
  EXPECT_EQ(j["chains"], nlohmann::json::array({"B", "A"}));  // first appearance, not sorted
  EXPECT_EQ(j["elements"], nlohmann::json({{"C", 2}, {"N", 1}}));
  EXPECT_EQ(j["aabb"], nlohmann::json::parse("[[0,0,-2],[2,4,0]]"));
  EXPECT_EQ(j["aabb_inflated"], nlohmann::json::parse("[[-1,-1,-3],[3,5,1]]"));
  EXPECT_EQ(j["centroid"], nlohmann::json::parse("[1,2,-1]"));
  EXPECT_DOUBLE_EQ(j["radius"].get<double>(), std::sqrt(6.0) + 1.0);
  EXPECT_EQ(j["principal_axes"].size(), 3u);
  EXPECT_EQ(j["principal_variances"].size(), 3u);
  EXPECT_EQ(j["up"].size(), 3u);
  EXPECT_EQ(j["warnings"], nlohmann::json::array({"something odd"}));
}

TEST(InspectReport, TextSummarisesTheSameFacts) {
  const Molecule m = three_atoms();
  const std::string text = inspect_report_text(m, compute_molecule_properties(m.atoms));
  EXPECT_NE(text.find("atoms:      3 (1 HETATM)\n"), std::string::npos) << text;
  EXPECT_NE(text.find("chains:     B A\n"), std::string::npos) << text;
  EXPECT_NE(text.find("elements:   C:2 N:1\n"), std::string::npos) << text;
  EXPECT_NE(text.find("centroid:   (1.000, 2.000, -1.000)\n"), std::string::npos) << text;
  EXPECT_NE(text.find("warning:    something odd\n"), std::string::npos) << text;
}

}  // namespace
}  // namespace nano::structure
