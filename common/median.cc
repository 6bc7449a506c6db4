#include "common/median.h"

#include <algorithm>
#include <cstddef>

namespace adahrs::common {

double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto mid = static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  return values[static_cast<size_t>(mid)];
}

}  // namespace adahrs::common
