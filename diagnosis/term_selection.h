// The selection rule every diagnoser shares (docs/diagnose.md "Method"): a candidate's columns
// added to the selected ones are tested by the jackknife Wald statistic over clusters against
// F(q, C-1), and kept only when the leave-one-cluster-out error drops as well.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "diagnosis/clustered_least_squares.h"

namespace adahrs::diagnosis {

struct TermTest {
  bool testable = false;
  std::string note;  ///< why it is not testable
  double p_value = 1.0;
  double gain = 0.0;        ///< held-out sum of squares without minus with the columns
  ClusteredFit fit;         ///< of `subset`
  std::vector<int> subset;  ///< the selected columns, then the candidate's
};

/// `subset` followed by `extra`.
std::vector<int> WithColumns(std::vector<int> subset, const std::vector<int>& extra);

/// Tests `columns` added to `selected` (whose fit is `selected_fit`).
TermTest TestTerm(const ClusteredLeastSquares& ls,
                  const std::vector<int>& selected,
                  const ClusteredFit& selected_fit,
                  const std::vector<int>& columns);

/// Raises the variance of a one-column candidate (the last of `t->subset`) to at least `variance`
/// and tests it again against F(1, C-1): a model-based variance the jackknife may miss.
void FloorCandidateVariance(double variance, TermTest* t);

/// Forward selection: from `base` (fitted as `base_fit`), the candidate (a set of columns) with the
/// smallest p-value below `alpha` and a positive held-out gain is added, until none qualifies or
/// `max_terms` are in. `allowed(k, chosen)` may refuse candidate k given those chosen (one of a
/// family of alternatives). `adjust(k, test)`, when given, may revise candidate k's test (its
/// variance floor) before it is judged. `in_alternate(k)`, when given and true, says candidate k is
/// tested in `alternate` (the same design under other weights) instead of `ls`; the selected fit
/// stays in `ls`.
struct TermSelection {
  std::vector<int> chosen;    ///< candidate indices, in the order taken
  std::vector<int> selected;  ///< columns: base, then the chosen candidates'
  ClusteredFit fit;           ///< of `selected`
};
TermSelection SelectTerms(const ClusteredLeastSquares& ls,
                          const std::vector<int>& base,
                          const ClusteredFit& base_fit,
                          const std::vector<std::vector<int>>& candidates,
                          double alpha,
                          int max_terms,
                          const std::function<bool(int, const std::vector<int>&)>& allowed = {},
                          const std::function<void(int, TermTest*)>& adjust = {},
                          const ClusteredLeastSquares* alternate = nullptr,
                          const std::function<bool(int)>& in_alternate = {});

/// `subset` without `columns`.
std::vector<int> WithoutColumns(const std::vector<int>& subset, const std::vector<int>& columns);

/// The estimates and jackknife standard errors of `columns` in `fit` of `subset`.
void ColumnEstimates(const ClusteredFit& fit,
                     const std::vector<int>& subset,
                     const std::vector<int>& columns,
                     Eigen::VectorXd* theta,
                     Eigen::VectorXd* se);

/// Standard errors of `columns` added alone to `selected` less those columns (the detection limit's
/// basis); false with `note` set when the recording cannot test them.
bool LimitStandardErrors(const ClusteredLeastSquares& ls,
                         const std::vector<int>& selected,
                         const std::vector<int>& columns,
                         Eigen::VectorXd* se,
                         std::string* note);

/// Two-sided Student t quantile at `alpha` with clusters - 1 degrees of freedom.
double TCritical(double alpha, int clusters);

/// Held-out RMS (leave one cluster out) of fit `a` or, with `second`, of `b`, over the clusters
/// where both have one, times `scale`.
double HeldOutRms(const ClusteredFit& a, const ClusteredFit& b, bool second, double scale);

}  // namespace adahrs::diagnosis
