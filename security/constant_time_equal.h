// Comparison of a secret (a bearer token) with what a client presented, in time that tells the
// client nothing about the secret.
#pragma once

#include <string_view>

namespace afmesh::security {

// True when `presented` and `secret` hold the same bytes.
//
// Timing: the work depends on presented.size() only. Every byte of `presented` is compared
// (with `secret`'s bytes, cycled when the lengths differ) and the differences are OR-ed into
// one accumulator with no early exit: the loop runs presented.size() times whatever the secret
// is, and the position of the first difference does not show in its running time. A length
// mismatch is folded into the accumulator the same way.
// An empty `secret` equals only an empty `presented`.
bool constant_time_equal(std::string_view presented, std::string_view secret);

}  // namespace afmesh::security
