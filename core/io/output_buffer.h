// OutputBuffer: buffered writing of mesh files, to a stdio file or to a string.
//
// Bytes collect in a 1 MiB buffer that is handed to the destination when full, so writing a
// large mesh costs memory for the buffer only. Numbers are formatted in place with
// std::to_chars; doubles use the shortest text that parses back to the same bits.
// The first failed file write is remembered; later writes are dropped and `flush()` returns it.
#pragma once

#include <bit>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "absl/status/status.h"

namespace afmesh {

class OutputBuffer {
 public:
  static constexpr std::size_t kCapacity = std::size_t{1} << 20;

  // Appends everything written to `*target` (not owned; must outlive the buffer).
  explicit OutputBuffer(std::string* target);
  // Writes to the open file `target` (not owned); `name` is used in error messages.
  OutputBuffer(std::FILE* target, std::string_view name);
  OutputBuffer(const OutputBuffer&) = delete;
  OutputBuffer& operator=(const OutputBuffer&) = delete;

  void put(std::string_view text) {
    if (text.size() > kCapacity - used_) {
      put_large(text);
      return;
    }
    std::memcpy(data_.get() + used_, text.data(), text.size());
    used_ += text.size();
  }
  void put(char c) {
    if (used_ == kCapacity) drain();
    data_[used_++] = c;
  }
  // Shortest decimal text that parses back to exactly `value` (e.g. "0.1", "-0", "1e-300").
  void put_double(double value) {
    make_room(kMaxNumberChars);
    used_ = std::to_chars(data_.get() + used_, data_.get() + kCapacity, value).ptr - data_.get();
  }
  // Shortest decimal text that parses back to exactly `value` as a float.
  void put_float(float value) {
    make_room(kMaxNumberChars);
    used_ = std::to_chars(data_.get() + used_, data_.get() + kCapacity, value).ptr - data_.get();
  }
  void put_int(std::int64_t value) {
    make_room(kMaxNumberChars);
    used_ = std::to_chars(data_.get() + used_, data_.get() + kCapacity, value).ptr - data_.get();
  }
  // The bytes of `value` in little-endian order (binary STL, VTK raw data).
  template <typename T>
  void put_little_endian(T value) {
    static_assert(std::is_trivially_copyable_v<T>);
    make_room(sizeof(T));
    char* out = data_.get() + used_;
    std::memcpy(out, &value, sizeof(T));
    if constexpr (std::endian::native == std::endian::big) {
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(out[i], out[sizeof(T) - 1 - i]);
    }
    used_ += sizeof(T);
  }

  // Hands the buffered bytes to the destination and flushes the file's stdio buffer. Returns
  // the first write error met so far, naming the file.
  absl::Status flush();

 private:
  static constexpr std::size_t kMaxNumberChars = 32;  // "-2.2250738585072014e-308" fits

  void make_room(std::size_t bytes) {
    if (kCapacity - used_ < bytes) drain();
  }
  // Empties the buffer into the destination.
  void drain();
  void put_large(std::string_view text);

  std::unique_ptr<char[]> data_;
  std::size_t used_ = 0;
  std::string* string_target_ = nullptr;
  std::FILE* file_target_ = nullptr;
  std::string name_;
  absl::Status status_;
};

}  // namespace afmesh
