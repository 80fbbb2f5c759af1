#pragma once

#include "tsr/cov/vocabulary.hpp"

#include <cstdint>

namespace tsr::cov {

// The caller's name for what an instance shows; several instances may share
// one (their pixels add up). 0 is reserved for the background.
using ObjectId = std::uint32_t;
inline constexpr ObjectId kBackground = 0;

}  // namespace tsr::cov
