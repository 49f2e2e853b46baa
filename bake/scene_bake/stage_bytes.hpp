#pragma once
// The bytes of a cached bake stage (shell_cache.cpp, tile_set_cache.cpp): plain values and arrays of
// them, in this machine's byte order (the file is this baker's own, keyed on its executable).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

namespace nano::scene_bake {

class StageWriter {
public:
  template <typename T>
  void put(const T& value) {
    const auto* p = reinterpret_cast<const std::byte*>(&value);
    bytes.insert(bytes.end(), p, p + sizeof(T));
  }
  template <typename T>
  void put_all(const std::vector<T>& values) {
    const auto* p = reinterpret_cast<const std::byte*>(values.data());
    bytes.insert(bytes.end(), p, p + values.size() * sizeof(T));
  }
  std::vector<std::byte> bytes;
};

// Reads what the writer wrote; every read checks what is left, so a truncated or hostile file is
// a failed decode, never a read past its end.
class StageReader {
public:
  explicit StageReader(std::span<const std::byte> bytes) : bytes_(bytes) {}
  template <typename T>
  bool get(T& value) {
    if (bytes_.size() - at_ < sizeof(T)) return false;
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return true;
  }
  template <typename T>
  bool get_all(std::vector<T>& values, std::uint64_t count) {
    if (count > (bytes_.size() - at_) / sizeof(T)) return false;
    values.resize(count);
    std::memcpy(values.data(), bytes_.data() + at_, count * sizeof(T));
    at_ += count * sizeof(T);
    return true;
  }
  bool done() const { return at_ == bytes_.size(); }

private:
  std::span<const std::byte> bytes_;
  std::size_t at_ = 0;
};

}  // namespace nano::scene_bake
