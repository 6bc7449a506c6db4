#include "calib/diagnosis/term_test.h"

#include <algorithm>
#include <cmath>

#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/students_t.hpp>

namespace adahrs::calib {

std::vector<int> WithColumns(std::vector<int> subset, const std::vector<int>& extra) {
  subset.insert(subset.end(), extra.begin(), extra.end());
  return subset;
}

TermTest TestTerm(const ClusteredLeastSquares& ls, const std::vector<int>& selected, const ClusteredFit& selected_fit,
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
  t.p_value = std::isfinite(wald) && wald >= 0.0 ? boost::math::cdf(boost::math::complement(dist, wald / q)) : 1.0;
  const HeldOutComparison cv = CompareHeldOut(selected_fit, t.fit);
  t.gain = cv.ss_a - cv.ss_b;
  t.testable = true;
  return t;
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

}  // namespace adahrs::calib
