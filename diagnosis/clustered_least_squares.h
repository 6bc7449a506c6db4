// Weighted linear least squares whose observations fall into clusters (the recording's segments),
// solved for any subset of the design's columns from per-cluster Gram matrices, with the
// leave-one-cluster-out fits that give the held-out error (folds by segment) and the jackknife
// covariance, which holds whatever the correlation of the errors within a cluster. A random
// intercept per cluster (SetClusterOffsetRatio) makes a long segment count as one offset plus its
// detail; solved by generalised least squares in closed form per cluster. A cluster that alone
// supports a column sets jackknife_ok = false.
// Units: those of the caller's rows.
// Formulas: docs/diagnose.md ("Method (IMU)", step 3).
// Left out: iteration (the model is linear), outlier rejection.
#pragma once

#include <limits>
#include <vector>

#include <Eigen/Dense>

namespace adahrs::diagnosis {

struct ClusteredFit {
  bool ok = false;            ///< the design of the chosen columns has full rank
  bool jackknife_ok = false;  ///< every leave-one-cluster-out design has full rank too
  Eigen::VectorXd theta;
  Eigen::MatrixXd covariance;       ///< jackknife over clusters (valid when jackknife_ok)
  double rss = 0.0;                 ///< weighted in-sample residual sum of squares
  double weight = 0.0;              ///< total weight
  std::vector<double> held_out_ss;  ///< per cluster; NaN where the leave-out fit is singular
  std::vector<double> cluster_weight;
  int clusters = 0;  ///< clusters holding observations
};

class ClusteredLeastSquares {
 public:
  ClusteredLeastSquares(int columns, int clusters);

  /// Adds one observation y with design row x and weight w (> 0) to `cluster`.
  void Add(int cluster, const Eigen::VectorXd& x, double y, double w);

  /// lambda = sigma_e^2 / sigma_w^2 of the random intercept per cluster; infinity (the default)
  /// is none.
  void SetClusterOffsetRatio(double lambda) { lambda_ = lambda; }

  /// Fits the columns `subset` (indices into the design, in that order).
  ClusteredFit Fit(const std::vector<int>& subset) const;
  /// True when the columns `subset` have full rank over all clusters (no leave-out fits).
  bool FullRank(const std::vector<int>& subset) const;
  /// The fit's weights on the observations: theta = M^-1 sum_i w_i (x_i - s_c) y_i, with M this
  /// information matrix of `subset` and s_c = X_c' W 1 / (lambda + W_c) of the row's cluster.
  Eigen::MatrixXd Information(const std::vector<int>& subset) const;
  Eigen::VectorXd ClusterShrink(int cluster, const std::vector<int>& subset) const;

  int columns() const { return columns_; }

 private:
  struct Cluster {
    Eigen::MatrixXd gram;
    Eigen::VectorXd xty;
    Eigen::VectorXd xtw;  ///< X' W 1
    double yty = 0.0;
    double ysum = 0.0;  ///< 1' W y
    double weight = 0.0;
  };
  int columns_;
  double lambda_ = std::numeric_limits<double>::infinity();
  std::vector<Cluster> clusters_;
};

/// Held-out sum of squares of `fit` summed over the clusters where both fits have one, and the
/// weight of those clusters.
struct HeldOutComparison {
  double ss_a = 0.0;
  double ss_b = 0.0;
  double weight = 0.0;
};
HeldOutComparison CompareHeldOut(const ClusteredFit& a, const ClusteredFit& b);

}  // namespace adahrs::diagnosis
