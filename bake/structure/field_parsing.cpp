#include "bake/structure/field_parsing.hpp"

#include <cctype>
#include <charconv>

namespace nano::structure {

std::string_view trim_blanks(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) text.remove_suffix(1);
  return text;
}

std::optional<double> parse_real(std::string_view field) {
  field = trim_blanks(field);
  if (!field.empty() && field.front() == '+') field.remove_prefix(1);
  if (field.empty()) return std::nullopt;
  double value = 0.0;
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (ec != std::errc() || end != field.data() + field.size()) return std::nullopt;
  return value;
}

std::optional<int> parse_integer(std::string_view field) {
  field = trim_blanks(field);
  if (!field.empty() && field.front() == '+') field.remove_prefix(1);
  if (field.empty()) return std::nullopt;
  int value = 0;
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (ec != std::errc() || end != field.data() + field.size()) return std::nullopt;
  return value;
}

std::optional<int> parse_hybrid36(std::string_view field, int width) {
  const std::string_view trimmed = trim_blanks(field);
  if (trimmed.empty()) return std::nullopt;
  const char first = trimmed.front();
  if (!std::isalpha(static_cast<unsigned char>(first))) return parse_integer(trimmed);
  // Hybrid-36 always fills the whole field.
  if (static_cast<int>(trimmed.size()) != width) return std::nullopt;
  const bool upper = std::isupper(static_cast<unsigned char>(first)) != 0;
  long long value = 0;
  for (char c : trimmed) {
    int digit;
    if (c >= '0' && c <= '9') digit = c - '0';
    else if (upper && c >= 'A' && c <= 'Z') digit = c - 'A' + 10;
    else if (!upper && c >= 'a' && c <= 'z') digit = c - 'a' + 10;
    else return std::nullopt;
    value = value * 36 + digit;
  }
  long long power36 = 1, power10 = 1;
  for (int i = 0; i < width - 1; ++i) power36 *= 36;
  for (int i = 0; i < width; ++i) power10 *= 10;
  // Upper case continues after the decimal range; lower case continues after upper case.
  value = upper ? value - 10 * power36 + power10 : value + 16 * power36 + power10;
  return static_cast<int>(value);
}

}  // namespace nano::structure
