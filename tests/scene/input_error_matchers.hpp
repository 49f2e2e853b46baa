#pragma once
// Runs code that must reject its input and hands back the InputError for inspection.
#include <gtest/gtest.h>

#include <string>

#include "common/error.hpp"

namespace nano::scene::testing {

template <class F>
InputError expect_input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "expected nano::InputError, nothing was thrown";
  return InputError("<none>", "<none>", "<none>");
}

// The error names `where` exactly and its rule mentions `rule_part`.
#define EXPECT_INPUT_ERROR(statement, where_expected, rule_part)                                   \
  do {                                                                                              \
    const ::nano::InputError e_ = ::nano::scene::testing::expect_input_error([&] { statement; });   \
    EXPECT_EQ(e_.where(), (where_expected)) << e_.what();                                           \
    EXPECT_NE(std::string(e_.rule()).find(rule_part), std::string::npos) << e_.what();              \
    if (!std::string(where_expected).empty()) {                                                     \
      EXPECT_NE(std::string(e_.what()).find(std::string(":") + (where_expected) + ": "), std::string::npos) \
          << e_.what();                                                                             \
    }                                                                                               \
  } while (false)

}  // namespace nano::scene::testing
