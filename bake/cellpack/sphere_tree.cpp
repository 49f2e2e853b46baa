#include "bake/cellpack/sphere_tree.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "common/error.hpp"

namespace nano::cellpack {
namespace {

// The file's meaningful lines with their numbers: comments and blank lines dropped.
class Lines {
public:
  Lines(std::string_view text, const std::string& file) : file_(file) {
    std::size_t number = 0, start = 0;
    while (start <= text.size()) {
      const std::size_t end = std::min(text.find('\n', start), text.size());
      std::string line(text.substr(start, end - start));
      ++number;
      const std::size_t first = line.find_first_not_of(" \t\r");
      if (first != std::string::npos && line[first] != '#') lines_.emplace_back(number, line);
      start = end + 1;
    }
  }
  // The next line's numbers: exactly `count`, or at least `count` when `at_least`.
  std::vector<double> next(std::size_t count, bool at_least, const char* what) {
    if (at_ >= lines_.size()) throw InputError(file_, "end", std::string("the file ends before ") + what);
    const auto& [number, line] = lines_[at_++];
    std::istringstream in(line);
    std::vector<double> values;
    std::string word;
    while (in >> word) {
      char* end = nullptr;
      const double v = std::strtod(word.c_str(), &end);
      if (end != word.c_str() + word.size() || !std::isfinite(v)) fail(number, std::string("expected ") + what + ", got '" + line + "'");
      values.push_back(v);
    }
    if (values.size() < count || (!at_least && values.size() != count)) fail(number, std::string("expected ") + what + ", got '" + line + "'");
    return values;
  }
  std::size_t line_number() const { return at_ == 0 ? 0 : lines_[at_ - 1].first; }
  [[noreturn]] void fail(std::size_t number, const std::string& rule) const {
    throw InputError(file_, "line " + std::to_string(number), rule);
  }

private:
  std::string file_;
  std::vector<std::pair<std::size_t, std::string>> lines_;
  std::size_t at_ = 0;
};

std::size_t whole(Lines& lines, double v, std::size_t max, const char* what) {
  if (!(v >= 0.0) || v != std::floor(v) || v > double(max))
    lines.fail(lines.line_number(), std::string(what) + " must be a whole number in [0, " + std::to_string(max) + "]");
  return std::size_t(v);
}

}  // namespace

SphereTree parse_sphere_tree(std::string_view text, const std::string& file) {
  Lines lines(text, file);
  SphereTree tree;
  const std::vector<double> range = lines.next(2, false, "\"rmin rmax\"");
  tree.min_radius = range[0], tree.max_radius = range[1];
  if (!(tree.min_radius >= 0.0) || !(tree.max_radius > 0.0))
    lines.fail(lines.line_number(), "expected rmin >= 0 and rmax > 0 Å");
  const std::size_t level_count = whole(lines, lines.next(1, false, "the number of levels")[0], 64, "the number of levels");
  std::size_t total = 0;
  for (std::size_t level = 0; level < level_count; ++level) {
    const std::size_t n = whole(lines, lines.next(1, false, "a level's sphere count")[0], kMaxSphereTreeSpheres, "a sphere count");
    if ((total += n) > kMaxSphereTreeSpheres)
      lines.fail(lines.line_number(), "a sphere tree holds at most " + std::to_string(kMaxSphereTreeSpheres) + " spheres");
    std::vector<glm::dvec4> spheres;
    for (std::size_t k = 0; k < n; ++k) {
      const std::vector<double> s = lines.next(4, true, "\"x y z r\"");
      if (!(s[3] > 0.0)) lines.fail(lines.line_number(), "expected a sphere radius > 0 Å");
      spheres.emplace_back(s[0], s[1], s[2], s[3]);
    }
    tree.levels.push_back(std::move(spheres));
  }
  return tree;
}

SphereTree read_sphere_tree(const std::filesystem::path& file) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  if (ec) throw InputError(file.string(), "", "cannot read the sphere tree: " + ec.message());
  if (size > (std::uintmax_t(64) << 20)) throw InputError(file.string(), "", "a sphere tree file is at most 64 MiB");
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return parse_sphere_tree(text.str(), file.string());
}

}  // namespace nano::cellpack
