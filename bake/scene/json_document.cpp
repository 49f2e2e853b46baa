#include "bake/scene/json_document.hpp"

#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "common/error.hpp"

namespace nano::scene {
namespace {

// Tracks where the parser is, as a key path, so that a duplicate key can be named exactly.
class KeyPathTracker {
public:
  explicit KeyPathTracker(std::string file) : file_(std::move(file)) {}

  void on_event(nlohmann::detail::parse_event_t event, const Json& parsed) {
    using E = nlohmann::detail::parse_event_t;
    switch (event) {
      case E::object_start: push(false); break;
      case E::array_start: push(true); break;
      case E::key: on_key(parsed.get<std::string>()); break;
      case E::object_end:
      case E::array_end: frames_.pop_back(); value_done(); break;
      case E::value: value_done(); break;
    }
  }

private:
  struct Frame {
    std::string path;
    bool is_array = false;
    std::size_t next_index = 0;
    std::string current_key;
    std::set<std::string> keys;
  };

  std::string child_path() const {
    if (frames_.empty()) return "";
    const Frame& parent = frames_.back();
    if (parent.is_array) return parent.path + "[" + std::to_string(parent.next_index) + "]";
    return parent.path.empty() ? parent.current_key : parent.path + "." + parent.current_key;
  }
  void push(bool is_array) {
    Frame f;
    f.path = child_path();
    f.is_array = is_array;
    frames_.push_back(std::move(f));
  }
  void on_key(const std::string& key) {
    Frame& top = frames_.back();
    if (!top.keys.insert(key).second) {
      const std::string where = top.path.empty() ? key : top.path + "." + key;
      throw InputError(file_, where, "key \"" + key + "\" appears more than once in this object");
    }
    top.current_key = key;
  }
  void value_done() {
    if (!frames_.empty() && frames_.back().is_array) ++frames_.back().next_index;
  }

  std::string file_;
  std::vector<Frame> frames_;
};

// nlohmann reports the 1-based byte position of the last character it read.
std::string line_and_column(std::string_view text, std::size_t byte) {
  const std::size_t end = std::min(byte == 0 ? 0 : byte - 1, text.size());
  std::size_t line = 1, line_start = 0;
  for (std::size_t i = 0; i < end; ++i)
    if (text[i] == '\n') { ++line; line_start = i + 1; }
  return std::to_string(line) + ":" + std::to_string(end - line_start + 1);
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

}  // namespace

Json parse_json_text(std::string_view text, const std::string& file_for_messages) {
  KeyPathTracker tracker(file_for_messages);
  const Json::parser_callback_t callback = [&tracker](int, nlohmann::detail::parse_event_t event, Json& parsed) {
    tracker.on_event(event, parsed);
    return true;
  };
  try {
    return Json::parse(text.begin(), text.end(), callback);
  } catch (const Json::parse_error& e) {
    throw InputError(file_for_messages, line_and_column(text, e.byte), parser_explanation(e.what()));
  }
}

Json read_json_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path.string(), "", "file does not exist or is not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "", "cannot open the file for reading");
  std::ostringstream content;
  content << in.rdbuf();
  return parse_json_text(content.str(), path.string());
}

}  // namespace nano::scene
