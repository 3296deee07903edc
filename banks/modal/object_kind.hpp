#pragma once
// The object bank kind (banks/kind.hpp): `clatter-bank object`, a sweep of one task per object (a
// closed mesh in a material, from the config's lists or a scene's bodies below the proxy
// threshold): its FEM modes by SLEPc spectrum slicing and each mode's transfer for an arbitrary
// shape, on a PETSc session; `info` and `probe` of it. It shares the modal kind's FEM, solve and
// transfer stage (this folder).
#include "banks/kind.hpp"

namespace clatter::jobs {

const BankKind& object_kind();

}  // namespace clatter::jobs
