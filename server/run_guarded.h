// Runs a job step, turning exceptions into statuses: the server never dies on a request.
#pragma once

#include <exception>
#include <new>
#include <string>
#include <string_view>
#include <type_traits>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"

namespace afmesh::server {

// `step()` (returning absl::Status or absl::StatusOr<T>), with std::bad_alloc as
// RESOURCE_EXHAUSTED ("the server ran out of memory <doing>") and any other exception as
// INTERNAL ("<doing> failed: <what>").
template <class Step>
std::invoke_result_t<Step> run_guarded(std::string_view doing, Step&& step) {
  try {
    return step();
  } catch (const std::bad_alloc&) {
    return absl::ResourceExhaustedError(
        absl::StrCat("the server ran out of memory ", std::string(doing)));
  } catch (const std::exception& e) {
    return absl::InternalError(absl::StrCat(std::string(doing), " failed: ", e.what()));
  }
}

}  // namespace afmesh::server
