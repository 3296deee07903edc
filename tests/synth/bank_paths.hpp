#pragma once
// The banks the CTest fixtures made, from clatter-synth-tests' command line: PAN.h5 [MODAL.h5].
#include <string>

namespace clatter::test {
inline std::string pan_bank_path, modal_bank_path;
}  // namespace clatter::test
