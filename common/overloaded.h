// Overloaded: a set of lambdas as one visitor for std::visit, one call operator per alternative.
#pragma once

namespace adahrs::common {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// The deduction guide C++20 makes implicit; clang 14 (the fuzz build) still needs it written.
template <typename... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

}  // namespace adahrs::common
