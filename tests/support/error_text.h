// Test helper: what a refusal says — the message of the exception of type E that `f` throws, or
// "no error" when `f` returns. Tests assert on the words a user would read.
#pragma once

#include <string>
#include <utility>

namespace adahrs::test_support {

template <class E, class F>
std::string ErrorText(F&& f) {
  try {
    std::forward<F>(f)();
  } catch (const E& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace adahrs::test_support
