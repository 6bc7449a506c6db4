// Test helper: the ordinary least-squares line y = offset + slope·x through paired samples, in
// closed form (the datasheets' best-fit straight line, against which nonlinearity is quoted).
// Written here, not borrowed from calib/solvers, so sensor tests do not check code against itself.
#pragma once

#include <cstddef>
#include <vector>

namespace adahrs::test_support {

struct Line {
  double offset = 0.0;
  double slope = 0.0;
};

inline Line FitLine(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  return {(sy - slope * sx) / n, slope};
}

}  // namespace adahrs::test_support
