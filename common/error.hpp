#pragma once
// One error type for bad input everywhere: it names the file, where in it, and the broken rule,
// so every command can print "FILE:WHERE: RULE" and exit non-zero instead of crashing.
#include <stdexcept>
#include <string>

namespace nano {

class InputError : public std::runtime_error {
public:
  InputError(std::string file, std::string where, std::string rule)
      : std::runtime_error(compose(file, where, rule)),
        file_(std::move(file)), where_(std::move(where)), rule_(std::move(rule)) {}

  const std::string& file() const { return file_; }
  const std::string& where() const { return where_; }
  const std::string& rule() const { return rule_; }

private:
  static std::string compose(const std::string& file, const std::string& where, const std::string& rule) {
    std::string s = file.empty() ? std::string("<input>") : file;
    if (!where.empty()) s += ":" + where;
    return s + ": " + rule;
  }
  std::string file_, where_, rule_;
};

// Where a text came from, handed down to the function that parses it so that function can throw
// the InputError itself: an option ("--camera"), or a file and a place in it ("run.nvs", "line 12").
struct InputSource {
  InputSource(std::string file, std::string where = {}) : file(std::move(file)), where(std::move(where)) {}
  InputSource(const char* file) : file(file) {}

  [[noreturn]] void fail(std::string rule) const { throw InputError(file, where, std::move(rule)); }

  std::string file, where;
};

}  // namespace nano
