#pragma once
// The modal bank kind (banks/kind.hpp): `clatter-bank modal`, a sweep of one task per patch sample
// (FEM modes by SLEPc spectrum slicing, then each mode's acoustic transfer) on a PETSc session;
// `info`, `probe` and `plan` of it; and `modal-samples` beside it.
#include "banks/kind.hpp"

namespace clatter::jobs {

const BankKind& modal_kind();

}  // namespace clatter::jobs
