// Builds a std::array of objects that have no default constructor, element i from make(i).
#pragma once

#include <array>
#include <cstddef>
#include <utility>

namespace adahrs::sensor_sim {

template <size_t N, typename Make>
auto MakeArray(Make&& make) {
  return [&]<size_t... I>(std::index_sequence<I...>) {
    return std::array{make(static_cast<int>(I))...};
  }
  (std::make_index_sequence<N>{});
}

}  // namespace adahrs::sensor_sim
