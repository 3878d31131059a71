#include "security/constant_time_equal.h"

#include <cstddef>

namespace afmesh::security {

bool constant_time_equal(std::string_view presented, std::string_view secret) {
  // volatile: the compiler may neither stop the loop at the first difference nor replace it by
  // memcmp (which does stop there).
  volatile unsigned char difference = presented.size() == secret.size() ? 0 : 1;
  if (secret.empty()) return presented.empty();  // depends on lengths only
  std::size_t j = 0;
  for (std::size_t i = 0; i < presented.size(); ++i) {
    difference = difference | static_cast<unsigned char>(presented[i] ^ secret[j]);
    // Cycles through `secret` without a division, whose time can vary with its operands.
    j = j + 1 == secret.size() ? 0 : j + 1;
  }
  return difference == 0;
}

}  // namespace afmesh::security
