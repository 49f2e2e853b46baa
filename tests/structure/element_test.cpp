#include "bake/structure/element.hpp"
#include "bake/structure/field_parsing.hpp"

#include <gtest/gtest.h>

namespace nano::structure {
namespace {

TEST(Element, NormalisesSymbolsAndFoldsDeuteriumIntoHydrogen) {
  EXPECT_EQ(normalize_element_symbol("FE"), "Fe");
  EXPECT_EQ(normalize_element_symbol(" c"), "C");
  EXPECT_EQ(normalize_element_symbol("D"), "H");
  EXPECT_EQ(normalize_element_symbol("  "), "");
}

TEST(Element, KnowsElementSymbols) {
  EXPECT_TRUE(is_element_symbol("Se"));
  EXPECT_TRUE(is_element_symbol("CL"));
  EXPECT_FALSE(is_element_symbol("Xx"));
  EXPECT_FALSE(is_element_symbol("C1"));
  EXPECT_FALSE(is_element_symbol(""));
}

TEST(Element, InfersFromThePdbNameFieldByColumnConvention) {
  EXPECT_EQ(infer_element_from_pdb_atom_name(" CA "), "C");
  EXPECT_EQ(infer_element_from_pdb_atom_name("CA  "), "Ca");
  EXPECT_EQ(infer_element_from_pdb_atom_name("1HB "), "H");
  EXPECT_EQ(infer_element_from_pdb_atom_name("2HD1"), "H");
  EXPECT_EQ(infer_element_from_pdb_atom_name("HG21"), "H");
  EXPECT_EQ(infer_element_from_pdb_atom_name("HG  "), "Hg");
  EXPECT_EQ(infer_element_from_pdb_atom_name("C210"), "C");  // MD-style left-justified carbon
  EXPECT_EQ(infer_element_from_pdb_atom_name("    "), "");
}

TEST(Element, InfersFromBareMmcifNames) {
  EXPECT_EQ(infer_element_from_atom_name("CA", "ALA"), "C");
  EXPECT_EQ(infer_element_from_atom_name("CA", "CA"), "Ca");
  EXPECT_EQ(infer_element_from_atom_name("FE", "FE"), "Fe");
  EXPECT_EQ(infer_element_from_atom_name("1HB", "ALA"), "H");
  EXPECT_EQ(infer_element_from_atom_name("", "ALA"), "");
}

TEST(Element, UsesTheMantinaTableFromBiologyMd) {
  EXPECT_EQ(van_der_waals_radius("H"), 1.10);
  EXPECT_EQ(van_der_waals_radius("C"), 1.70);
  EXPECT_EQ(van_der_waals_radius("N"), 1.55);
  EXPECT_EQ(van_der_waals_radius("O"), 1.52);
  EXPECT_EQ(van_der_waals_radius("S"), 1.80);
  EXPECT_EQ(van_der_waals_radius("P"), 1.80);
  EXPECT_EQ(van_der_waals_radius("Fe"), 2.05);
  EXPECT_EQ(van_der_waals_radius("Ca"), 2.31);
  EXPECT_EQ(van_der_waals_radius("Zn"), 2.10);
  EXPECT_EQ(van_der_waals_radius("Se"), 1.90);
  EXPECT_EQ(van_der_waals_radius("Xe"), std::nullopt);
  EXPECT_EQ(kFallbackVdwRadius, 1.7);
}

TEST(FieldParsing, ParsesStrictReals) {
  EXPECT_EQ(parse_real("  -12.345"), -12.345);
  EXPECT_EQ(parse_real("+4"), 4.0);
  EXPECT_EQ(parse_real("1e3 "), 1000.0);
  EXPECT_EQ(parse_real("1.2.3"), std::nullopt);
  EXPECT_EQ(parse_real("abc"), std::nullopt);
  EXPECT_EQ(parse_real("   "), std::nullopt);
}

TEST(FieldParsing, ParsesStrictIntegers) {
  EXPECT_EQ(parse_integer(" 42"), 42);
  EXPECT_EQ(parse_integer("-7"), -7);
  EXPECT_EQ(parse_integer("4.5"), std::nullopt);
  EXPECT_EQ(parse_integer(""), std::nullopt);
  EXPECT_EQ(trim_blanks("  ab \r"), "ab");
}

TEST(FieldParsing, DecodesHybrid36) {
  EXPECT_EQ(parse_hybrid36("9999", 4), 9999);
  EXPECT_EQ(parse_hybrid36(" -99", 4), -99);
  EXPECT_EQ(parse_hybrid36("A000", 4), 10000);
  EXPECT_EQ(parse_hybrid36("ZZZZ", 4), 1223055);  // 36^4 - 1 - 10*36^3 + 10^4
  EXPECT_EQ(parse_hybrid36("a000", 4), 1223056);  // continues right after ZZZZ
  EXPECT_EQ(parse_hybrid36("A0", 4), std::nullopt);
  EXPECT_EQ(parse_hybrid36("Aa00", 4), std::nullopt);
}

}  // namespace
}  // namespace nano::structure
