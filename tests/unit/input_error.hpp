#pragma once
// The message of the InputError `f` throws (one line, asserted); fails the test if it throws none.
#include <gtest/gtest.h>

#include <string>

#include "core/errors.hpp"

template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const clatter::InputError& e) {
    std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos) << "message is not one line: " << m;
    return m;
  }
  ADD_FAILURE() << "no InputError";
  return {};
}
