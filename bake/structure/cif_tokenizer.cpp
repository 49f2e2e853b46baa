#include "bake/structure/cif_tokenizer.hpp"

#include <cstring>
#include <strings.h>

#include "common/error.hpp"

namespace nano::structure {
namespace {

bool is_cif_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

bool starts_with_nocase(std::string_view s, std::string_view prefix) {
  return s.size() >= prefix.size() && strncasecmp(s.data(), prefix.data(), prefix.size()) == 0;
}

}  // namespace

CifTokenizer::CifTokenizer(std::string_view text, std::string file_name) : text_(text), file_(std::move(file_name)) {}

void CifTokenizer::skip_whitespace_and_comments() {
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (c == '\n') {
      ++line_;
      ++pos_;
    } else if (is_cif_space(c)) {
      ++pos_;
    } else if (c == '#') {
      const void* newline = std::memchr(text_.data() + pos_, '\n', text_.size() - pos_);
      pos_ = newline ? static_cast<std::size_t>(static_cast<const char*>(newline) - text_.data()) : text_.size();
    } else {
      return;
    }
  }
}

// A quote closes only when followed by whitespace or the end, so 'O5'' is the value O5'.
CifToken CifTokenizer::quoted(char quote) {
  const std::size_t start_line = line_;
  const std::size_t start = pos_ + 1;
  for (std::size_t i = start; i < text_.size(); ++i) {
    const char c = text_[i];
    if (c == '\n' || c == '\r') break;
    if (c == quote && (i + 1 == text_.size() || is_cif_space(text_[i + 1]))) {
      pos_ = i + 1;
      return {CifTokenKind::Value, text_.substr(start, i - start), start_line};
    }
  }
  throw InputError(file_, "line " + std::to_string(start_line),
                   std::string("unterminated ") + (quote == '\'' ? "single" : "double") +
                       "-quoted value: the closing quote must come before the end of the line");
}

// A text field runs from ';' at the start of a line to the next line starting with ';'.
CifToken CifTokenizer::text_field() {
  const std::size_t start_line = line_;
  const std::size_t start = pos_ + 1;
  std::size_t i = start;
  while (true) {
    const void* newline = std::memchr(text_.data() + i, '\n', text_.size() - i);
    if (!newline) break;
    const std::size_t at = static_cast<const char*>(newline) - text_.data();
    ++line_;
    if (at + 1 < text_.size() && text_[at + 1] == ';') {
      std::size_t end = at;
      if (end > start && text_[end - 1] == '\r') --end;
      pos_ = at + 2;
      return {CifTokenKind::Value, text_.substr(start, end - start), start_line};
    }
    i = at + 1;
  }
  throw InputError(file_, "line " + std::to_string(start_line),
                   "unterminated ';' text field: no line starting with ';' closes it");
}

CifToken CifTokenizer::next() {
  skip_whitespace_and_comments();
  if (pos_ >= text_.size()) return {CifTokenKind::End, {}, line_};
  const char c = text_[pos_];
  const bool at_line_start = pos_ == 0 || text_[pos_ - 1] == '\n';
  if (c == ';' && at_line_start) return text_field();
  if (c == '\'' || c == '"') return quoted(c);
  const std::size_t start = pos_;
  while (pos_ < text_.size() && !is_cif_space(text_[pos_])) ++pos_;
  const std::string_view word = text_.substr(start, pos_ - start);
  if (c == '_') return {CifTokenKind::Tag, word, line_};
  if (word == ".") return {CifTokenKind::Inapplicable, word, line_};
  if (word == "?") return {CifTokenKind::Unknown, word, line_};
  if (starts_with_nocase(word, "data_")) return {CifTokenKind::DataBlock, word.substr(5), line_};
  if (word.size() == 5 && starts_with_nocase(word, "loop_")) return {CifTokenKind::Loop, word, line_};
  if (starts_with_nocase(word, "save_")) return {CifTokenKind::Save, word.substr(5), line_};
  if ((word.size() == 7 && starts_with_nocase(word, "global_")) || (word.size() == 5 && starts_with_nocase(word, "stop_")))
    throw InputError(file_, "line " + std::to_string(line_), "reserved CIF word '" + std::string(word) + "' is not allowed");
  return {CifTokenKind::Value, word, line_};
}

}  // namespace nano::structure
