#include "diagnosis/term_selection.h"

#include <algorithm>
#include <cmath>

#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/students_t.hpp>

namespace adahrs::diagnosis {

std::vector<int> WithColumns(std::vector<int> subset, const std::vector<int>& extra) {
  subset.insert(subset.end(), extra.begin(), extra.end());
  return subset;
}

TermTest TestTerm(const ClusteredLeastSquares& ls,
                  const std::vector<int>& selected,
                  const ClusteredFit& selected_fit,
                  const std::vector<int>& columns) {
  TermTest t;
  t.subset = WithColumns(selected, columns);
  if (!ls.FullRank(t.subset)) {
    t.note = "not excited by this recording (its term is zero or a combination of the model's)";
    return t;
  }
  t.fit = ls.Fit(t.subset);
  if (!t.fit.ok || !t.fit.jackknife_ok) {
    t.note = "rests on a single segment (cannot be told from that segment's own disturbance)";
    return t;
  }
  const int q = static_cast<int>(columns.size());
  const Eigen::VectorXd theta = t.fit.theta.tail(q);
  const Eigen::MatrixXd v = t.fit.covariance.bottomRightCorner(q, q);
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(v);
  if (ldlt.info() != Eigen::Success || !(v.diagonal().minCoeff() > 0.0)) {
    t.note = "its jackknife variance vanishes";
    return t;
  }
  const double wald = theta.dot(ldlt.solve(theta));
  const double dof = std::max(1, t.fit.clusters - 1);
  const boost::math::fisher_f dist(q, dof);
  t.p_value = std::isfinite(wald) && wald >= 0.0
                  ? boost::math::cdf(boost::math::complement(dist, wald / q))
                  : 1.0;
  const HeldOutComparison cv = CompareHeldOut(selected_fit, t.fit);
  t.gain = cv.ss_a - cv.ss_b;
  t.testable = true;
  return t;
}

void FloorCandidateVariance(double variance, TermTest* t) {
  if (!t->testable) return;
  const int pos = static_cast<int>(t->subset.size()) - 1;
  double& v = t->fit.covariance(pos, pos);
  if (!(variance > v)) return;
  v = variance;
  const double theta = t->fit.theta[pos];
  const boost::math::fisher_f dist(1, std::max(1, t->fit.clusters - 1));
  t->p_value = boost::math::cdf(boost::math::complement(dist, theta * theta / v));
}

TermSelection SelectTerms(const ClusteredLeastSquares& ls,
                          const std::vector<int>& base,
                          const ClusteredFit& base_fit,
                          const std::vector<std::vector<int>>& candidates,
                          double alpha,
                          int max_terms,
                          const std::function<bool(int, const std::vector<int>&)>& allowed,
                          const std::function<void(int, TermTest*)>& adjust,
                          const ClusteredLeastSquares* alternate,
                          const std::function<bool(int)>& in_alternate) {
  const auto uses_alternate = [&](int k) {
    return alternate != nullptr && in_alternate && in_alternate(k);
  };
  TermSelection out{{}, base, base_fit};
  while (static_cast<int>(out.chosen.size()) < max_terms) {
    int best = -1;
    TermTest best_test;
    for (int k = 0; k < static_cast<int>(candidates.size()); ++k) {
      if (std::find(out.chosen.begin(), out.chosen.end(), k) != out.chosen.end()) continue;
      if (allowed && !allowed(k, out.chosen)) continue;
      const bool alt = uses_alternate(k);
      TermTest t = TestTerm(alt ? *alternate : ls,
                            out.selected,
                            alt ? alternate->Fit(out.selected) : out.fit,
                            candidates[static_cast<size_t>(k)]);
      if (adjust && t.testable) adjust(k, &t);
      if (!t.testable || t.p_value >= alpha || t.gain <= 0.0) continue;
      if (best < 0 || t.p_value < best_test.p_value) {
        best = k;
        best_test = std::move(t);
      }
    }
    if (best < 0) break;
    out.chosen.push_back(best);
    out.selected = std::move(best_test.subset);
    out.fit = uses_alternate(best) ? ls.Fit(out.selected) : std::move(best_test.fit);
  }
  return out;
}

std::vector<int> WithoutColumns(const std::vector<int>& subset, const std::vector<int>& columns) {
  std::vector<int> out;
  for (int c : subset) {
    if (std::find(columns.begin(), columns.end(), c) == columns.end()) out.push_back(c);
  }
  return out;
}

void ColumnEstimates(const ClusteredFit& fit,
                     const std::vector<int>& subset,
                     const std::vector<int>& columns,
                     Eigen::VectorXd* theta,
                     Eigen::VectorXd* se) {
  const int q = static_cast<int>(columns.size());
  theta->resize(q);
  se->resize(q);
  for (int k = 0; k < q; ++k) {
    const int pos = static_cast<int>(
        std::find(subset.begin(), subset.end(), columns[static_cast<size_t>(k)]) - subset.begin());
    (*theta)[k] = fit.theta[pos];
    (*se)[k] = std::sqrt(fit.covariance(pos, pos));
  }
}

bool LimitStandardErrors(const ClusteredLeastSquares& ls,
                         const std::vector<int>& selected,
                         const std::vector<int>& columns,
                         Eigen::VectorXd* se,
                         std::string* note) {
  const std::vector<int> others = WithoutColumns(selected, columns);
  const TermTest t = TestTerm(ls, others, ls.Fit(others), columns);
  if (!t.fit.ok || !t.fit.jackknife_ok || !t.note.empty()) {
    *note = t.note;
    return false;
  }
  const int q = static_cast<int>(columns.size());
  *se = t.fit.covariance.bottomRightCorner(q, q).diagonal().cwiseSqrt();
  return true;
}

double TCritical(double alpha, int clusters) {
  const boost::math::students_t dist(std::max(1, clusters - 1));
  return boost::math::quantile(boost::math::complement(dist, alpha / 2.0));
}

double HeldOutRms(const ClusteredFit& a, const ClusteredFit& b, bool second, double scale) {
  const HeldOutComparison cv = CompareHeldOut(a, b);
  if (!(cv.weight > 0.0)) return 0.0;
  return std::sqrt(std::max(0.0, (second ? cv.ss_b : cv.ss_a) / cv.weight)) * scale;
}

}  // namespace adahrs::diagnosis
