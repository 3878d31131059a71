#include "core/io/output_buffer.h"

#include <algorithm>
#include <cerrno>
#include <system_error>

#include "core/io/string_util.h"

namespace afmesh {

OutputBuffer::OutputBuffer(std::string* target)
    : data_(new char[kCapacity]), string_target_(target) {}

OutputBuffer::OutputBuffer(std::FILE* target, std::string_view name)
    : data_(new char[kCapacity]), file_target_(target), name_(name) {}

void OutputBuffer::drain() {
  if (used_ == 0) return;
  if (string_target_ != nullptr) {
    string_target_->append(data_.get(), used_);
  } else if (status_.ok() && std::fwrite(data_.get(), 1, used_, file_target_) != used_) {
    const int error = errno;
    status_ = absl::InternalError(
        str_cat("cannot write '", name_, "': ", std::generic_category().message(error)));
  }
  used_ = 0;
}

void OutputBuffer::put_large(std::string_view text) {
  while (!text.empty()) {
    make_room(1);
    const std::size_t chunk = std::min(text.size(), kCapacity - used_);
    std::memcpy(data_.get() + used_, text.data(), chunk);
    used_ += chunk;
    text.remove_prefix(chunk);
  }
}

absl::Status OutputBuffer::flush() {
  drain();
  if (file_target_ != nullptr && status_.ok() && std::fflush(file_target_) != 0) {
    const int error = errno;
    status_ = absl::InternalError(
        str_cat("cannot write '", name_, "': ", std::generic_category().message(error)));
  }
  return status_;
}

}  // namespace afmesh
