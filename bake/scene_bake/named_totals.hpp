#pragma once
// Lists of (name, value) in first-appearance order, as the report prints them (copies per
// molecule name, seconds per stage): the entry called `name`, appended at zero when missing.
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace nano::scene_bake {

template <class T>
T& named_entry(std::vector<std::pair<std::string, T>>& list, const std::string& name) {
  auto it = std::find_if(list.begin(), list.end(), [&](const auto& e) { return e.first == name; });
  if (it != list.end()) return it->second;
  return list.emplace_back(name, T{}).second;
}

}  // namespace nano::scene_bake
