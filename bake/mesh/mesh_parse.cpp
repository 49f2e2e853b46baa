#include "bake/mesh/mesh_parse.hpp"

#include <charconv>
#include <cstdlib>

namespace nano::mesh::parse {

namespace {

constexpr std::string_view kWhitespace = " \t\r\v\f";

std::string_view without_comment(std::string_view line, char comment) {
  if (comment == '\0') return line;
  return line.substr(0, line.find(comment));
}

std::string_view trimmed_right(std::string_view line) {
  const std::size_t end = line.find_last_not_of(kWhitespace);
  return end == std::string_view::npos ? std::string_view() : line.substr(0, end + 1);
}

void split(std::string_view line, std::vector<std::string_view>& tokens) {
  for (std::size_t pos = line.find_first_not_of(kWhitespace); pos != std::string_view::npos;) {
    const std::size_t end = std::min(line.find_first_of(kWhitespace, pos), line.size());
    tokens.push_back(line.substr(pos, end - pos));
    pos = line.find_first_not_of(kWhitespace, end);
  }
}

// from_chars refuses a leading '+', which C's strtod and many writers allow.
std::string_view without_plus(std::string_view token) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') token.remove_prefix(1);
  return token;
}

}  // namespace

LineReader::LineReader(std::string_view text, Options options)
    : text_(text), options_(options), physical_(options.first_line - 1) {
  if (text_.starts_with("\xEF\xBB\xBF")) pos_ = 3;  // a UTF-8 byte order mark some editors write
}

std::string_view LineReader::physical_line() {
  const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
  const std::string_view line = text_.substr(pos_, end - pos_);
  pos_ = end < text_.size() ? end + 1 : end;
  ++physical_;
  return line;
}

bool LineReader::next(std::vector<std::string_view>& tokens) {
  tokens.clear();
  while (pos_ < text_.size()) {
    std::string_view line = without_comment(physical_line(), options_.comment);
    line_ = physical_;
    if (options_.continuation && trimmed_right(line).ends_with('\\')) {
      joined_.clear();
      for (bool more = true; more;) {
        line = trimmed_right(line);
        more = line.ends_with('\\');
        joined_ += line.substr(0, line.size() - (more ? 1 : 0));
        joined_ += ' ';
        if (more && pos_ >= text_.size()) break;
        if (more) line = without_comment(physical_line(), options_.comment);
      }
      line = joined_;
    }
    split(line, tokens);
    if (!tokens.empty()) return true;
  }
  return false;
}

std::optional<std::string_view> TokenReader::next() {
  while (index_ == tokens_.size()) {
    if (!lines_.next(tokens_)) return std::nullopt;
    index_ = 0;
  }
  return tokens_[index_++];
}

std::vector<std::string_view> TokenReader::rest_of_line() {
  std::vector<std::string_view> rest(tokens_.begin() + static_cast<std::ptrdiff_t>(index_), tokens_.end());
  index_ = tokens_.size();
  return rest;
}

std::string TokenReader::where() const { return line() > 0 ? at_line(line()) : std::string(); }

std::optional<double> to_double(std::string_view token) {
  token = without_plus(token);
  double value = 0.0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (end != token.data() + token.size() || token.empty()) return std::nullopt;
  if (error == std::errc::result_out_of_range) {
    // 1e-400 is a number (zero, as a double), 1e400 one that is not finite: strtod says which.
    return std::strtod(std::string(token).c_str(), nullptr);
  }
  if (error != std::errc()) return std::nullopt;
  return value;
}

std::optional<std::int64_t> to_int(std::string_view token) {
  token = without_plus(token);
  std::int64_t value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc() || end != token.data() + token.size() || token.empty()) return std::nullopt;
  return value;
}

std::string at_line(std::size_t line) { return "line " + std::to_string(line); }

}  // namespace nano::mesh::parse
