#pragma once
// The ground bank kind (banks/kind.hpp): `clatter-bank ground`, a sweep of one task per (material,
// elevation) (the regularized Lamb problem radiated by the Rayleigh integral); `info` of it. Run
// without -c, it builds the built-in configs/ground-demo.toml.
#include "banks/kind.hpp"

namespace clatter::jobs {

const BankKind& ground_kind();

}  // namespace clatter::jobs
