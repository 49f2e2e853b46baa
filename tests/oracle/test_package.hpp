#pragma once
// A hand scene as an opened, validated in-memory package (the oracle's precondition).
#include "format/validator.hpp"
#include "tests/format/sample_scene.hpp"

namespace nano::explicit_test {

struct TestPackage {
  explicit TestPackage(const format::test::SampleScene& s)
      : package(format::Package::from_bytes(format::test::build(s, format::Compression::none), "hand.nup")) {
    format::validate_semantics(package);
  }
  format::Package package;
};

}  // namespace nano::explicit_test
