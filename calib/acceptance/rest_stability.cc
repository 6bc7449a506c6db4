#include "calib/acceptance/rest_stability.h"

#include <algorithm>
#include <cmath>

#include "common/units.h"
#include "hil/recording/frame_count.h"

namespace adahrs::calib {
namespace {

constexpr double kMgPerG = 1000.0;

constexpr double kThreeSigma = 3.0;
// Above this separation ratio B2 takes its asymptote: the exact form cancels large terms.
constexpr double kAsymptoticRatio = 1e3;

bool AtRest(const ImuOutputRow& row) {
  return row.has_comp && (row.mode == 2 || row.mode == 3) && row.orientation != 0 &&
         std::abs(row.table_rate_dps) <= kRestRate_dps;
}

// [first, last) of the longest stretch of consecutive rest packets in one orientation.
std::pair<size_t, size_t> LongestStretch(const std::vector<ImuOutputRow>& rows,
                                         double packet_period_s) {
  std::pair<size_t, size_t> best{0, 0};
  size_t first = 0;
  for (size_t i = 0; i <= rows.size(); ++i) {
    const bool continues =
        i < rows.size() && AtRest(rows[i]) && i > first &&
        rows[i].orientation == rows[first].orientation && rows[i].mode == rows[first].mode &&
        std::abs(rows[i].chamber_c - rows[first].chamber_c) <= kRestBand_c &&
        hil::FramesBetween(
            rows[i - 1].seq, rows[i].seq, rows[i].t_s - rows[i - 1].t_s, packet_period_s) == 1;
    if (continues) continue;
    if (i > first && AtRest(rows[first]) && i - first > best.second - best.first) best = {first, i};
    first = i;
  }
  return best;
}

}  // namespace

ImuBodyOutput BodyOutput(const hil::ImuRecordRow& row) {
  const std::array<double, 9>& c = *row.comp;
  ImuBodyOutput p;
  if (row.mode == 3) {
    for (size_t i = 0; i < 3; ++i) {
      p.f_B_g[i] = common::Mps2ToG(c[i]);
      p.w_B_dps[i] = c[3 + i];
    }
  } else {
    // Mode 2 channels az1 ax1 ay1 az2 ax2 ay2, each in g along its body axis: an axis is the mean
    // of its pair, as the firmware forms Ca before the cross-axis matrix.
    p.f_B_g = {(c[1] + c[4]) / 2.0, (c[2] + c[5]) / 2.0, (c[0] + c[3]) / 2.0};
    p.w_B_dps = {c[6], c[7], c[8]};
  }
  return p;
}

ImuOutputRow ImuOutputRow::Of(const hil::ImuRecordRow& row) {
  ImuOutputRow out;
  out.t_s = row.t_s;
  out.chamber_c = row.chamber_c;
  out.table_rate_dps = row.table_rate_dps;
  if (row.comp) out.body = BodyOutput(row);
  out.seq = row.seq;
  out.step = row.step;
  out.orientation = row.orientation;
  out.tag = row.tag;
  out.mode = row.mode;
  out.has_comp = row.comp.has_value();
  return out;
}

double RestStability::SigmaAt(const AllanTerms& terms, double tau_s) {
  const auto& c = terms.curve;
  if (tau_s <= c.front().tau_s) return c.front().adev;
  for (size_t i = 0; i + 1 < c.size(); ++i) {
    if (tau_s <= c[i + 1].tau_s) {
      const double f = std::log(tau_s / c[i].tau_s) / std::log(c[i + 1].tau_s / c[i].tau_s);
      return std::exp(std::log(c[i].adev) + f * std::log(c[i + 1].adev / c[i].adev));
    }
  }
  return c.back().adev;
}

double RestStability::Floor(const AllanTerms& terms) {
  double lowest = terms.curve.front().adev;
  for (const auto& point : terms.curve) lowest = std::min(lowest, point.adev);
  return lowest;
}

nlohmann::json RestStability::ToJson() const {
  nlohmann::json axes = nlohmann::json::object();
  const char* names[3] = {"x", "y", "z"};
  for (size_t i = 0; i < 3; ++i) {
    axes[std::string("rate_") + names[i]] = {
        {"floor_dps", Floor(rate_dps[i])},
        {"floor_tau_s", rate_dps[i].bias_instability_tau_s},
        {"floor_is_upper_bound", rate_dps[i].minimum_at_longest_tau}};
    axes[std::string("accel_") + names[i]] = {
        {"floor_mg", Floor(accel_mg[i])},
        {"floor_tau_s", accel_mg[i].bias_instability_tau_s},
        {"floor_is_upper_bound", accel_mg[i].minimum_at_longest_tau}};
  }
  return {{"t_start_s", t_start_s},
          {"record_s", record_s},
          {"orientation", orientation},
          {"chamber_c", chamber_c},
          {"allan_floor", axes}};
}

double FlickerSeparationRatio(double r) {
  if (!(r > 1.0)) return 1.0;
  const double four_ln2 = 4.0 * std::log(2.0);
  if (r > kAsymptoticRatio) return (2.0 * std::log(r) + 3.0) / four_ln2;
  const double a = (r + 1.0) * (r + 1.0) * std::log(r + 1.0);
  const double b = (r - 1.0) * (r - 1.0) * std::log(r - 1.0);
  const double c = 2.0 * r * r * std::log(r);
  return (a + b - c) / four_ln2;
}

std::optional<RestStability> ReadRestStability(const std::vector<ImuOutputRow>& rows,
                                               double packet_period_s) {
  auto [first, last] = LongestStretch(rows, packet_period_s);
  if (last == first) return std::nullopt;
  if (static_cast<double>(last - first) * packet_period_s < kRestRecordMin_s) return std::nullopt;
  const size_t max_packets = static_cast<size_t>(kRestRecordMax_s / packet_period_s);
  if (last - first > max_packets) first = last - max_packets;

  RestStability r;
  r.t_start_s = rows[first].t_s;
  r.orientation = rows[first].orientation;
  std::array<std::vector<double>, 3> accel_mg, rate_dps;
  double chamber_sum_c = 0.0;
  for (size_t i = first; i < last; ++i) {
    const ImuBodyOutput& out = rows[i].body;
    for (size_t k = 0; k < 3; ++k) {
      accel_mg[k].push_back(out.f_B_g[k] * kMgPerG);
      rate_dps[k].push_back(out.w_B_dps[k]);
    }
    chamber_sum_c += rows[i].chamber_c;
  }
  const double n = static_cast<double>(last - first);
  r.record_s = n * packet_period_s;
  r.chamber_c = chamber_sum_c / n;
  for (size_t k = 0; k < 3; ++k) {
    r.accel_mg[k] = ReadAllanTerms(accel_mg[k], packet_period_s);
    r.rate_dps[k] = ReadAllanTerms(rate_dps[k], packet_period_s);
  }
  return r;
}

double PointSigma(const AllanTerms& terms, double iid_std_error, double point_s) {
  return std::max(iid_std_error, RestStability::SigmaAt(terms, point_s));
}

double PointLimit(const AllanTerms& terms,
                  double iid_std_error,
                  double point_s,
                  double since_calibration_s) {
  const double point = PointSigma(terms, iid_std_error, point_s);
  const double floor = RestStability::Floor(terms);
  const double wander_sq =
      2.0 * FlickerSeparationRatio(since_calibration_s / point_s) * floor * floor;
  return kThreeSigma * std::sqrt(point * point + wander_sq);
}

}  // namespace adahrs::calib
