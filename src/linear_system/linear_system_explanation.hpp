// The words solve() puts in LinearSystemResult::explanation (internal).
#pragma once

#include <string>

#include "spdfit/linear_system.hpp"

namespace spdfit::detail {

/// The classification of a solved system in the terms of notes 002 section 3.3.2: the
/// equations as lines, planes or hyperplanes, what they have in common, finite or at infinity.
std::string explain(const LinearSystemResult& r);

}  // namespace spdfit::detail
