#pragma once
// One number into a printf pattern, for the reports' and errors' sentences.
#include <cstdio>
#include <string>

namespace nano::mesh {

inline std::string number_text(const char* pattern, double value) {
  char text[128];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

inline constexpr double kDegreesPerRadian = 57.29577951308232;

}  // namespace nano::mesh
