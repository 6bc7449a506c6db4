// The selection rule every diagnoser shares (docs/diagnose.md "Method"): a candidate's columns
// added to the selected ones are tested by the jackknife Wald statistic over clusters against
// F(q, C-1), and kept only when the leave-one-cluster-out error drops as well.
#pragma once

#include <string>
#include <vector>

#include "calib/diagnosis/clustered_least_squares.h"

namespace adahrs::calib {

struct TermTest {
  bool testable = false;
  std::string note;  ///< why it is not testable
  double p_value = 1.0;
  double gain = 0.0;  ///< held-out sum of squares without minus with the columns
  ClusteredFit fit;   ///< of `subset`
  std::vector<int> subset;  ///< the selected columns, then the candidate's
};

/// `subset` followed by `extra`.
std::vector<int> WithColumns(std::vector<int> subset, const std::vector<int>& extra);

/// Tests `columns` added to `selected` (whose fit is `selected_fit`).
TermTest TestTerm(const ClusteredLeastSquares& ls, const std::vector<int>& selected, const ClusteredFit& selected_fit,
                  const std::vector<int>& columns);

/// Two-sided Student t quantile at `alpha` with clusters - 1 degrees of freedom.
double TCritical(double alpha, int clusters);

/// Held-out RMS (leave one cluster out) of fit `a` or, with `second`, of `b`, over the clusters
/// where both have one, times `scale`.
double HeldOutRms(const ClusteredFit& a, const ClusteredFit& b, bool second, double scale);

}  // namespace adahrs::calib
