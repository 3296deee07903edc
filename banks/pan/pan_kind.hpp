#pragma once
// The PAN bank kind (banks/kind.hpp): `clatter-bank pan`, a sweep of proxy x field tasks (FDTD
// solve, then the wavelet fit) merged into one bank file; `info`, `probe` and `plan` of it; and the
// raw `solve` beside it.
#include "banks/kind.hpp"

namespace clatter::jobs {

const BankKind& pan_kind();
// `clatter-bank pan-object`: the same sweep over given meshes (per-object PAN), a PAN bank file.
const BankKind& pan_object_kind();

}  // namespace clatter::jobs
