#include "common/json_document.hpp"

#include <algorithm>
#include <fstream>
#include <functional>
#include <tuple>
#include <utility>
#include <vector>

#include "common/error.hpp"

namespace nano {
namespace {

std::string bytes_in_words(std::uintmax_t bytes) {
  std::string s = std::to_string(bytes) + " bytes";
  if (bytes >= (1u << 20) && bytes % (1u << 20) == 0) s += " (" + std::to_string(bytes >> 20) + " MiB)";
  return s;
}

// nlohmann reports the 1-based byte position of the last character it read.
std::string line_and_column(std::string_view text, std::size_t byte) {
  const std::size_t end = std::min(byte == 0 ? 0 : byte - 1, text.size());
  std::size_t line = 1, line_start = 0;
  for (std::size_t i = 0; i < end; ++i)
    if (text[i] == '\n') { ++line; line_start = i + 1; }
  return std::to_string(line) + ":" + std::to_string(end - line_start + 1);
}

// The 1-based byte position of the bracket that opens nesting level `level`. Called only once
// the parser has read that far, so everything before it is valid JSON.
std::size_t opening_of_level(std::string_view text, std::size_t level) {
  std::size_t depth = 0;
  bool in_string = false, escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (in_string) {
      if (escaped) escaped = false;
      else if (ch == '\\') escaped = true;
      else if (ch == '"') in_string = false;
    } else if (ch == '"') {
      in_string = true;
    } else if (ch == '[' || ch == '{') {
      if (++depth == level) return i + 1;
    } else if (ch == ']' || ch == '}') {
      --depth;
    }
  }
  return text.size();
}

// Keeps the parser's explanation but drops its "[json.exception...] parse error at line L,
// column C: " prefix, since the location is already in the WHERE part of the message.
std::string parser_explanation(const std::string& what) {
  const std::size_t column = what.find("column ");
  if (column != std::string::npos) {
    const std::size_t colon = what.find(": ", column);
    if (colon != std::string::npos) return "invalid JSON: " + what.substr(colon + 2);
  }
  return "invalid JSON: " + what;
}

// Builds the document from nlohmann's SAX events while keeping the key path of the value being
// read, so that every refusal names it. Members are appended in O(1): ordered_json's own
// insertion searches the object's keys linearly, quadratic in a hostile object's size. A
// duplicate key is found at once in a small object and by sorting key hashes when a large one
// ends. Memory is O(document) + O(depth × key length).
class StrictDomBuilder {
public:
  StrictDomBuilder(std::string_view text, const std::string& file, Json& root) : text_(text), file_(file), root_(root) {}

  bool null() { return put(Json(nullptr)); }
  bool boolean(bool v) { return put(Json(v)); }
  bool number_integer(Json::number_integer_t v) { return put(Json(v)); }
  bool number_unsigned(Json::number_unsigned_t v) { return put(Json(v)); }
  bool number_float(Json::number_float_t v, const Json::string_t&) { return put(Json(v)); }
  bool string(Json::string_t& s) {
    if (s.size() > kMaxJsonStringBytes)
      throw InputError(file_, value_path(),
                       "a string of " + std::to_string(s.size()) + " bytes; strings may be at most " +
                           bytes_in_words(kMaxJsonStringBytes));
    return put(Json(std::move(s)));
  }
  bool binary(Json::binary_t& b) { return put(Json::binary(std::move(b))); }  // not produced by JSON text

  bool start_object(std::size_t) { return open(Json(Json::value_t::object), false); }
  bool start_array(std::size_t) { return open(Json(Json::value_t::array), true); }
  bool end_object() {
    check_large_object_keys();
    return close();
  }
  bool end_array() { return close(); }

  bool key(Json::string_t& k) {
    Frame& top = frames_.back();
    if (k.size() > kMaxJsonStringBytes)
      throw InputError(file_, container_path(),
                       "a key of " + std::to_string(k.size()) + " bytes; keys may be at most " +
                           bytes_in_words(kMaxJsonStringBytes));
    // The object as the vector it is (ordered_map's operator[] takes a key).
    auto& members = static_cast<Json::object_t::Container&>(top.value->get_ref<Json::object_t&>());
    if (members.size() < kSmallObject) {
      for (const auto& member : members)
        if (member.first == k) duplicate_key(k);
    } else {
      if (top.hashes.empty())
        for (std::size_t i = 0; i < members.size(); ++i) top.hashes.emplace_back(std::hash<std::string>{}(members[i].first), i);
      top.hashes.emplace_back(std::hash<std::string>{}(k), members.size());
    }
    members.emplace_back(k, Json());
    top.key = std::move(k);
    return true;
  }

  bool parse_error(std::size_t position, const std::string& last_token, const nlohmann::detail::exception& e) {
    if (dynamic_cast<const Json::out_of_range*>(&e) != nullptr) {
      // The lexer read a number such as 1e400 that is infinite as a double.
      const std::string shown = last_token.size() > 40 ? last_token.substr(0, 37) + "..." : last_token;
      const std::string path = value_path();
      throw InputError(file_, path.empty() ? line_and_column(text_, position) : path,
                       "the number " + shown + " is out of the range of a double (it would be infinite)");
    }
    throw InputError(file_, line_and_column(text_, position), parser_explanation(e.what()));
  }

private:
  static constexpr std::size_t kSmallObject = 16;  // members compared directly

  struct Frame {
    Json* value = nullptr;        // the array or object being filled
    bool is_array = false;
    std::size_t next_index = 0;   // arrays: index of the next element
    std::string key;              // objects: the key of the member being read
    std::vector<std::pair<std::size_t, std::size_t>> hashes;  // large objects: (key hash, member index)
  };

  [[noreturn]] void duplicate_key(const std::string& k) const {
    throw InputError(file_, joined(container_path(), k), "key \"" + k + "\" appears more than once in this object");
  }
  // A large object's members sorted by (hash, key, position): equal keys end up side by side.
  // The duplicate reported is the first in file order, as in a small object.
  void check_large_object_keys() {
    Frame& top = frames_.back();
    if (top.hashes.empty()) return;
    const auto& members = static_cast<const Json::object_t::Container&>(top.value->get_ref<const Json::object_t&>());
    auto& h = top.hashes;
    std::sort(h.begin(), h.end(), [&](const auto& a, const auto& b) {
      return std::tie(a.first, members[a.second].first, a.second) < std::tie(b.first, members[b.second].first, b.second);
    });
    std::size_t first_repeat = members.size();
    for (std::size_t i = 1; i < h.size(); ++i)
      if (h[i].first == h[i - 1].first && members[h[i].second].first == members[h[i - 1].second].first)
        first_repeat = std::min(first_repeat, h[i].second);
    if (first_repeat < members.size()) duplicate_key(members[first_repeat].first);
    std::vector<std::pair<std::size_t, std::size_t>>().swap(h);
  }

  // Keys in messages: a key of up to 1 MiB is valid JSON, but no scene key is that long.
  static std::string joined(const std::string& path, const std::string& key) {
    const std::string shown = key.size() > 64 ? key.substr(0, 32) + "..." : key;
    return path.empty() ? shown : path + "." + shown;
  }
  // The path of frames_[0 .. count): frame i contributes the step to its current child.
  std::string path_of(std::size_t count) const {
    std::string path;
    for (std::size_t i = 0; i < count; ++i) {
      const Frame& f = frames_[i];
      path = f.is_array ? path + "[" + std::to_string(f.next_index) + "]" : joined(path, f.key);
    }
    return path;
  }
  std::string value_path() const { return path_of(frames_.size()); }                 // the value being read
  std::string container_path() const { return path_of(frames_.size() - 1); }        // the innermost container

  // Stores a finished value where it belongs and returns where it now is.
  Json* place(Json&& v) {
    if (++values_ > kMaxJsonValues)
      throw InputError(file_, value_path(),
                       "the document has more than " + std::to_string(kMaxJsonValues) +
                           " values (numbers, strings, booleans, nulls, arrays and objects), the most a document may have");
    if (frames_.empty()) {
      root_ = std::move(v);
      return &root_;
    }
    Frame& top = frames_.back();
    if (top.is_array) {
      auto& array = top.value->get_ref<Json::array_t&>();
      array.push_back(std::move(v));
      return &array.back();
    }
    Json& member = top.value->get_ref<Json::object_t&>().back().second;  // appended by key()
    member = std::move(v);
    return &member;
  }
  // A value is complete: the next one in an array has the next index.
  void advance() {
    if (!frames_.empty() && frames_.back().is_array) ++frames_.back().next_index;
  }
  bool put(Json&& v) {
    place(std::move(v));
    advance();
    return true;
  }
  bool open(Json&& container, bool is_array) {
    if (frames_.size() == kMaxJsonDepth)
      throw InputError(file_, line_and_column(text_, opening_of_level(text_, kMaxJsonDepth + 1)),
                       "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
    Json* where = place(std::move(container));
    Frame f;
    f.value = where;
    f.is_array = is_array;
    frames_.push_back(std::move(f));
    return true;
  }
  bool close() {
    frames_.pop_back();
    advance();
    return true;
  }

  std::string_view text_;
  const std::string& file_;
  Json& root_;
  std::vector<Frame> frames_;
  std::size_t values_ = 0;
};

[[noreturn]] void refuse_size(const std::string& file, std::uintmax_t bytes, bool at_least) {
  throw InputError(file, "",
                   std::string("the file is ") + (at_least ? "at least " : "") + bytes_in_words(bytes) +
                       "; a JSON document may be at most " + bytes_in_words(kMaxJsonFileBytes));
}

}  // namespace

Json parse_json_text(std::string_view text, const std::string& file_for_messages) {
  if (text.size() > kMaxJsonFileBytes) refuse_size(file_for_messages, text.size(), false);
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos)
    throw InputError(file_for_messages, "", "the file is empty; expected a JSON document");
  // nlohmann's lexer takes a NUL byte for the end of the input and would ignore what follows.
  if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos)
    throw InputError(file_for_messages, line_and_column(text, nul + 1),
                     "a NUL byte: this is binary data, not JSON text (UTF-8)");
  Json root;
  StrictDomBuilder builder(text, file_for_messages, root);
  // Every failure, the parser's included, is thrown by the builder as an InputError.
  Json::sax_parse(text.begin(), text.end(), &builder);
  return root;
}

Json read_json_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path.string(), "", "file does not exist or is not a regular file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path.string(), "", "cannot read the file's size: " + ec.message());
  if (size > kMaxJsonFileBytes) refuse_size(path.string(), size, false);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "", "cannot open the file for reading");
  // Read in pieces with the bound rechecked, in case the file grows while it is read.
  std::string content;
  content.reserve(static_cast<std::size_t>(size));
  std::vector<char> piece(1 << 16);
  while (in.read(piece.data(), static_cast<std::streamsize>(piece.size())) || in.gcount() > 0) {
    content.append(piece.data(), static_cast<std::size_t>(in.gcount()));
    if (content.size() > kMaxJsonFileBytes) refuse_size(path.string(), content.size(), true);
  }
  if (in.bad()) throw InputError(path.string(), "", "error while reading the file");
  return parse_json_text(content, path.string());
}

}  // namespace nano
