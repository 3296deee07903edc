#pragma once
// The one 3-vector of doubles every layer passes around (positions, directions, moments).
#include <array>

namespace clatter {

using Vec3 = std::array<double, 3>;

}  // namespace clatter
