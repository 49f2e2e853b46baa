#pragma once
// A streaming CIF 1.1 tokenizer: yields one token at a time (no token array, so a huge mmCIF
// costs no extra memory) with the line it starts on.
#include <cstddef>
#include <string>
#include <string_view>

namespace nano::structure {

enum class CifTokenKind {
  DataBlock,  // data_NAME; text holds NAME
  Loop,       // loop_
  Save,       // save_ or save_NAME (frames are not used by mmCIF files from the PDB)
  Tag,        // _category.item
  Value,      // unquoted, quoted or text-field value; text excludes quotes and ';' markers
  Inapplicable,  // unquoted '.'
  Unknown,       // unquoted '?'
  End,
};

struct CifToken {
  CifTokenKind kind = CifTokenKind::End;
  std::string_view text;
  std::size_t line = 0;  // 1-based
};

class CifTokenizer {
public:
  // `file_name` only labels error messages; `text` must outlive the tokenizer and its tokens.
  CifTokenizer(std::string_view text, std::string file_name);

  // Next token, or kind End at the end of the text. Throws InputError on an unterminated quoted
  // value or text field, or on reserved words (global_, stop_) that mmCIF never uses.
  CifToken next();

  const std::string& file_name() const { return file_; }

private:
  void skip_whitespace_and_comments();
  CifToken quoted(char quote);
  CifToken text_field();

  std::string_view text_;
  std::string file_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
};

}  // namespace nano::structure
