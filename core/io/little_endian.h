// Reading little-endian numbers from byte buffers (binary STL, binary MSH).
#pragma once

#include <bit>
#include <cstring>
#include <type_traits>
#include <utility>

namespace afmesh {

// The value of type T stored little-endian at `bytes` (any alignment).
template <typename T>
T load_little_endian(const char* bytes) {
  static_assert(std::is_trivially_copyable_v<T>);
  char copy[sizeof(T)];
  std::memcpy(copy, bytes, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) {
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(copy[i], copy[sizeof(T) - 1 - i]);
  }
  T value;
  std::memcpy(&value, copy, sizeof(T));
  return value;
}

}  // namespace afmesh
