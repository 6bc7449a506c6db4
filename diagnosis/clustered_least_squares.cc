#include "diagnosis/clustered_least_squares.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace adahrs::diagnosis {
namespace {

constexpr double kMinReciprocalCondition = 1e-11;

// Solves (A) theta = b with A scaled to unit diagonal; false when A is (numerically) singular.
bool SolveScaled(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, Eigen::VectorXd* theta) {
  const Eigen::VectorXd d = a.diagonal();
  for (int i = 0; i < d.size(); ++i) {
    if (!(d[i] > 0.0)) return false;
  }
  const Eigen::VectorXd s = d.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd as = s.asDiagonal() * a * s.asDiagonal();
  const Eigen::LLT<Eigen::MatrixXd> llt(as);
  if (llt.info() != Eigen::Success || llt.rcond() < kMinReciprocalCondition) return false;
  *theta = s.asDiagonal() * llt.solve(s.asDiagonal() * b);
  return true;
}

Eigen::MatrixXd Sub(const Eigen::MatrixXd& m, const std::vector<int>& idx) {
  const int p = static_cast<int>(idx.size());
  Eigen::MatrixXd out(p, p);
  for (int i = 0; i < p; ++i) {
    for (int j = 0; j < p; ++j) out(i, j) = m(idx[i], idx[j]);
  }
  return out;
}

Eigen::VectorXd Sub(const Eigen::VectorXd& v, const std::vector<int>& idx) {
  Eigen::VectorXd out(static_cast<int>(idx.size()));
  for (size_t i = 0; i < idx.size(); ++i) out[static_cast<int>(i)] = v[idx[i]];
  return out;
}

}  // namespace

ClusteredLeastSquares::ClusteredLeastSquares(int columns, int clusters) : columns_(columns) {
  clusters_.resize(static_cast<size_t>(clusters));
  for (Cluster& c : clusters_) {
    c.gram = Eigen::MatrixXd::Zero(columns, columns);
    c.xty = Eigen::VectorXd::Zero(columns);
    c.xtw = Eigen::VectorXd::Zero(columns);
  }
}

void ClusteredLeastSquares::Add(int cluster, const Eigen::VectorXd& x, double y, double w) {
  if (cluster < 0 || cluster >= static_cast<int>(clusters_.size()) || x.size() != columns_ ||
      !(w > 0.0)) {
    throw std::invalid_argument(
        "ClusteredLeastSquares::Add: cluster, row size or weight out of range");
  }
  Cluster& c = clusters_[static_cast<size_t>(cluster)];
  c.gram.selfadjointView<Eigen::Lower>().rankUpdate(x, w);
  c.xty += w * y * x;
  c.yty += w * y * y;
  c.xtw += w * x;
  c.ysum += w * y;
  c.weight += w;
}

ClusteredFit ClusteredLeastSquares::Fit(const std::vector<int>& subset) const {
  ClusteredFit fit;
  const int p = static_cast<int>(subset.size());
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(p, p);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(p);
  double yty = 0.0;
  std::vector<Eigen::MatrixXd> grams;
  std::vector<Eigen::VectorXd> xtys;
  std::vector<double> ytys;
  for (const Cluster& c : clusters_) {
    Eigen::MatrixXd full = c.gram.selfadjointView<Eigen::Lower>();
    grams.push_back(Sub(full, subset));
    xtys.push_back(Sub(c.xty, subset));
    ytys.push_back(c.yty);
    if (std::isfinite(lambda_) && c.weight > 0.0) {
      // (W - W1 1'W / (lambda + 1'W1)): the cluster's share of the random-intercept GLS.
      const Eigen::VectorXd v = Sub(c.xtw, subset);
      const double k = 1.0 / (lambda_ + c.weight);
      grams.back() -= k * v * v.transpose();
      xtys.back() -= k * c.ysum * v;
      ytys.back() -= k * c.ysum * c.ysum;
    }
    a += grams.back();
    b += xtys.back();
    yty += ytys.back();
    fit.weight += c.weight;
    fit.cluster_weight.push_back(c.weight);
    if (c.weight > 0.0) ++fit.clusters;
  }
  fit.ok = SolveScaled(a, b, &fit.theta);
  if (!fit.ok) return fit;
  fit.rss = yty - 2.0 * fit.theta.dot(b) + fit.theta.dot(a * fit.theta);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  fit.held_out_ss.assign(clusters_.size(), nan);
  std::vector<Eigen::VectorXd> leave_out;
  fit.jackknife_ok = fit.clusters >= 2;
  for (size_t c = 0; c < clusters_.size(); ++c) {
    if (clusters_[c].weight <= 0.0) continue;
    Eigen::VectorXd theta;
    if (!SolveScaled(a - grams[c], b - xtys[c], &theta)) {
      fit.jackknife_ok = false;
      continue;
    }
    fit.held_out_ss[c] = ytys[c] - 2.0 * theta.dot(xtys[c]) + theta.dot(grams[c] * theta);
    leave_out.push_back(theta);
  }
  fit.covariance = Eigen::MatrixXd::Zero(p, p);
  if (fit.jackknife_ok) {
    Eigen::VectorXd mean = Eigen::VectorXd::Zero(p);
    for (const Eigen::VectorXd& t : leave_out) mean += t;
    mean /= static_cast<double>(leave_out.size());
    for (const Eigen::VectorXd& t : leave_out)
      fit.covariance += (t - mean) * (t - mean).transpose();
    const double n = static_cast<double>(leave_out.size());
    fit.covariance *= (n - 1.0) / n;
  }
  return fit;
}

bool ClusteredLeastSquares::FullRank(const std::vector<int>& subset) const {
  const int p = static_cast<int>(subset.size());
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(p, p);
  for (const Cluster& c : clusters_) {
    Eigen::MatrixXd full = c.gram.selfadjointView<Eigen::Lower>();
    a += Sub(full, subset);
  }
  Eigen::VectorXd theta;
  return SolveScaled(a, Eigen::VectorXd::Zero(p), &theta);
}

Eigen::MatrixXd ClusteredLeastSquares::Information(const std::vector<int>& subset) const {
  const int p = static_cast<int>(subset.size());
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(p, p);
  for (size_t c = 0; c < clusters_.size(); ++c) {
    Eigen::MatrixXd full = clusters_[c].gram.selfadjointView<Eigen::Lower>();
    const Eigen::VectorXd s = ClusterShrink(static_cast<int>(c), subset);
    a += Sub(full, subset) - s * Sub(clusters_[c].xtw, subset).transpose();
  }
  return a;
}

Eigen::VectorXd ClusteredLeastSquares::ClusterShrink(int cluster,
                                                     const std::vector<int>& subset) const {
  const Cluster& c = clusters_[static_cast<size_t>(cluster)];
  if (!std::isfinite(lambda_) || !(c.weight > 0.0))
    return Eigen::VectorXd::Zero(static_cast<int>(subset.size()));
  return Sub(c.xtw, subset) / (lambda_ + c.weight);
}

HeldOutComparison CompareHeldOut(const ClusteredFit& a, const ClusteredFit& b) {
  HeldOutComparison out;
  for (size_t c = 0; c < a.held_out_ss.size() && c < b.held_out_ss.size(); ++c) {
    if (std::isnan(a.held_out_ss[c]) || std::isnan(b.held_out_ss[c])) continue;
    out.ss_a += a.held_out_ss[c];
    out.ss_b += b.held_out_ss[c];
    out.weight += a.cluster_weight[c];
  }
  return out;
}

}  // namespace adahrs::diagnosis
