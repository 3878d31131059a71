// AFMESH_RETURN_IF_ERROR(expr): evaluates `expr` (an absl::Status) and returns it from the
// enclosing function when it is not OK. Keeps the readers' long sequences of checked steps flat.
#pragma once

#include "absl/status/status.h"

#define AFMESH_RETURN_IF_ERROR(expr)                                  \
  do {                                                                \
    if (absl::Status afmesh_status_ = (expr); !afmesh_status_.ok()) { \
      return afmesh_status_;                                          \
    }                                                                 \
  } while (false)
