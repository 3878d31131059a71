#include "core/io/file_bytes.h"

#include <cerrno>
#include <filesystem>
#include <memory>
#include <system_error>

#include "core/io/string_util.h"

namespace afmesh {
namespace {

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};

// The size of `path` when it is a regular file, else 0 (pipes, devices: read to the end).
std::size_t regular_file_size(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return 0;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  return error ? 0 : static_cast<std::size_t>(size);
}

}  // namespace

absl::Status file_error(std::string_view action, const std::string& path, int error_number) {
  return absl::ErrnoToStatus(
      error_number,
      str_cat("cannot ", action, " '", path, "': ", std::generic_category().message(error_number)));
}

absl::StatusOr<std::string> read_file_bytes(const std::string& path) {
  std::error_code ignored;
  if (std::filesystem::is_directory(path, ignored)) return file_error("read", path, EISDIR);
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (file == nullptr) return file_error("open", path, errno);

  std::string bytes(regular_file_size(path), '\0');
  bytes.resize(std::fread(bytes.data(), 1, bytes.size(), file.get()));
  // Whatever follows the expected size (a file still growing, or one of unknown size).
  std::string chunk(std::size_t{1} << 16, '\0');
  while (const std::size_t got = std::fread(chunk.data(), 1, chunk.size(), file.get())) {
    bytes.append(chunk.data(), got);
  }
  if (std::ferror(file.get())) return file_error("read", path, errno);
  return bytes;
}

}  // namespace afmesh
