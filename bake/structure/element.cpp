#include "bake/structure/element.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <utility>

namespace nano::structure {
namespace {

constexpr std::array<std::string_view, 118> kSymbols = {
    "H",  "He", "Li", "Be", "B",  "C",  "N",  "O",  "F",  "Ne", "Na", "Mg", "Al", "Si", "P",  "S",
    "Cl", "Ar", "K",  "Ca", "Sc", "Ti", "V",  "Cr", "Mn", "Fe", "Co", "Ni", "Cu", "Zn", "Ga", "Ge",
    "As", "Se", "Br", "Kr", "Rb", "Sr", "Y",  "Zr", "Nb", "Mo", "Tc", "Ru", "Rh", "Pd", "Ag", "Cd",
    "In", "Sn", "Sb", "Te", "I",  "Xe", "Cs", "Ba", "La", "Ce", "Pr", "Nd", "Pm", "Sm", "Eu", "Gd",
    "Tb", "Dy", "Ho", "Er", "Tm", "Yb", "Lu", "Hf", "Ta", "W",  "Re", "Os", "Ir", "Pt", "Au", "Hg",
    "Tl", "Pb", "Bi", "Po", "At", "Rn", "Fr", "Ra", "Ac", "Th", "Pa", "U",  "Np", "Pu", "Am", "Cm",
    "Bk", "Cf", "Es", "Fm", "Md", "No", "Lr", "Rf", "Db", "Sg", "Bh", "Hs", "Mt", "Ds", "Rg", "Cn",
    "Nh", "Fl", "Mc", "Lv", "Ts", "Og"};

// Mantina et al. 2009 as tabulated by Mol* (ElementVdwRadii) and quoted in BIOLOGY.md §3.
constexpr std::array<std::pair<std::string_view, double>, 17> kVdwRadii = {{
    {"H", 1.10}, {"C", 1.70}, {"N", 1.55}, {"O", 1.52}, {"Na", 2.27}, {"Mg", 1.73},
    {"P", 1.80}, {"S", 1.80}, {"Cl", 1.75}, {"K", 2.75}, {"Ca", 2.31}, {"Mn", 2.05},
    {"Fe", 2.05}, {"Co", 2.00}, {"Cu", 2.00}, {"Zn", 2.10}, {"Se", 1.90},
}};

bool is_letter(char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; }
bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

std::string one_letter(char c) { return is_letter(c) ? normalize_element_symbol(std::string_view(&c, 1)) : ""; }

}  // namespace

std::string normalize_element_symbol(std::string_view text) {
  std::string s;
  for (char c : text)
    if (is_letter(c)) s += s.empty() ? static_cast<char>(std::toupper(static_cast<unsigned char>(c)))
                                      : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (s == "D") s = "H";
  return s;
}

bool is_element_symbol(std::string_view symbol) {
  const std::string s = normalize_element_symbol(symbol);
  if (s.empty() || s.size() != symbol.size()) return false;
  return std::find(kSymbols.begin(), kSymbols.end(), s) != kSymbols.end();
}

std::string infer_element_from_pdb_atom_name(std::string_view field) {
  const char c0 = field.size() > 0 ? field[0] : ' ';
  const char c1 = field.size() > 1 ? field[1] : ' ';
  if (c0 == ' ' || is_digit(c0)) return one_letter(c1);
  if (!is_letter(c0)) return one_letter(c1);
  const bool four_characters = field.size() >= 4 && field.find(' ') == std::string_view::npos;
  if ((c0 == 'H' || c0 == 'h') && four_characters) return "H";
  if (is_letter(c1) && is_element_symbol(field.substr(0, 2))) return normalize_element_symbol(field.substr(0, 2));
  return one_letter(c0);
}

std::string infer_element_from_atom_name(std::string_view atom_name, std::string_view residue_name) {
  if (atom_name.empty()) return "";
  if (atom_name == residue_name && is_element_symbol(atom_name)) return normalize_element_symbol(atom_name);
  for (char c : atom_name)
    if (is_letter(c)) return one_letter(c);
  return "";
}

std::optional<double> van_der_waals_radius(std::string_view symbol) {
  for (const auto& [element, radius] : kVdwRadii)
    if (element == symbol) return radius;
  return std::nullopt;
}

}  // namespace nano::structure
