#pragma once
// What the OBJ, OFF, PLY and STL readers share: lines and tokens of a text that keep their line
// numbers (every error names one), numbers that must be the whole token, and endian-aware loads
// from a byte buffer.
#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace nano::mesh::parse {

class LineReader {
public:
  struct Options {
    char comment = '\0';        // cuts the rest of a line ('\0': no comments)
    bool continuation = false;  // a line ending in '\' goes on on the next one (OBJ)
    std::size_t first_line = 1; // the number of the text's first line (a PLY body's follows its header)
  };
  explicit LineReader(std::string_view text, Options options);
  explicit LineReader(std::string_view text) : LineReader(text, Options{}) {}

  // The next line that has a token once its comment is cut, split at whitespace. The tokens stay
  // valid until the next call. False at the end of the text.
  bool next(std::vector<std::string_view>& tokens);
  // 1-based number of the line last returned (of its first physical line, when continued).
  std::size_t line() const { return line_; }
  // Where the line after the one last returned starts (a binary PLY body begins there).
  std::size_t offset() const { return pos_; }

private:
  std::string_view physical_line();
  std::string_view text_;
  Options options_;
  std::size_t pos_ = 0;
  std::size_t physical_ = 0;  // the number of the last physical line consumed
  std::size_t line_ = 0;
  std::string joined_;        // a continued line, glued together
};

// Whitespace-separated tokens across lines, for formats where line breaks mean little (OFF, ASCII
// PLY and STL) but where "the rest of this line" still matters now and then (OFF's colours).
class TokenReader {
public:
  explicit TokenReader(std::string_view text, LineReader::Options options = {}) : lines_(text, options) {}

  std::optional<std::string_view> next();
  // Drops and returns what is left of the line of the last token.
  std::vector<std::string_view> rest_of_line();
  // The line of the last token read, or the last line once past it; 0 before the first.
  std::size_t line() const { return lines_.line(); }
  std::string where() const;  // "line N", or "" before the first line

private:
  LineReader lines_;
  std::vector<std::string_view> tokens_;
  std::size_t index_ = 0;
};

// The whole token as a number, or nothing ("1.5x", "", "0x10" are not numbers). A leading '+' is
// allowed; "nan" and "inf" are numbers here, so that the caller can say they are not finite.
std::optional<double> to_double(std::string_view token);
std::optional<std::int64_t> to_int(std::string_view token);

std::string at_line(std::size_t line);  // "line N"

// A T stored at `bytes` in the given byte order.
template <typename T>
T load(const unsigned char* bytes, bool big_endian) {
  unsigned char raw[sizeof(T)];
  std::memcpy(raw, bytes, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(raw, raw + sizeof(T));
  T value;
  std::memcpy(&value, raw, sizeof(T));
  return value;
}

}  // namespace nano::mesh::parse
