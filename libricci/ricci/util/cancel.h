#pragma once
// Cooperative cancellation: the caller owns a flag, a long computation that was given it checks
// it between its steps and stops there.
#include <atomic>
#include <string>

#include "ricci/mesh/errors.h"

namespace ricci {

/// Throws Cancelled ("`what`: cancelled") when `flag` is not null and set; a no-op otherwise.
inline void throw_if_cancelled(const std::atomic<bool>* flag, const char* what) {
  if (flag != nullptr && flag->load(std::memory_order_relaxed))
    throw Cancelled(std::string(what) + ": cancelled");
}

}  // namespace ricci
