#pragma once
// Error-path helper shared by the tests.
#include <gtest/gtest.h>

#include <string>

namespace ltp::test {

/// The message of the E thrown by f, or a test failure if nothing is thrown.
template <typename E, typename F>
std::string ThrownMessage(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an exception";
  return "";
}

}  // namespace ltp::test
