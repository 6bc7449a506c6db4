#include "calib/imu_calibration/imu_observations.h"

#include <cmath>
#include <map>
#include <sstream>
#include <tuple>

#include "common/units.h"

namespace adahrs::calib {

void ObservationBuilder::Add(const firmware_model::ImuRawFrame& raw, double t_s) {
  if (windows_.empty() || t_s < windows_.back().last_s ||
      t_s - windows_.back().last_s > kWindowMergeGap_s) {
    windows_.push_back({t_s, t_s, 0});
    slope_.emplace_back();
  }
  windows_.back().last_s = t_s;
  ++windows_.back().rows;
  SlopeSums& w = slope_.back();
  const double since_s = t_s - windows_.back().first_s;
  w.n += 1.0;
  w.u += since_s;
  w.uu += since_s * since_s;
  for (int i = 0; i < 6; ++i) {
    const double u = static_cast<double>(raw.t1_cnt[i]) / static_cast<double>(raw.t2_cnt[i]) - 0.5;
    sum_[i] += u;
    sum2_[i] += u * u;
  }
  for (int g = 0; g < 3; ++g) {
    // Gyro counts ~4e6: accumulate about a fixed 2^22 so the sum of squares keeps its digits.
    const double u = static_cast<double>(raw.gyro_cnt[g]) - 4194304.0;
    sum_[6 + g] += u;
    sum2_[6 + g] += u * u;
    const double t = raw.temp_cnt[g];
    t_sum_[g] += t;
    t2_sum_[g] += t * t;
    t3_sum_[g] += t * t * t;
    w.t[g] += t;
    w.ut[g] += since_s * t;
  }
  ++n_;
}

ImuObservation ObservationBuilder::Finish(std::string source,
                                          bool thermal,
                                          int run,
                                          const Eigen::Vector3d& f_B_g,
                                          const Eigen::Vector3d& w_B_dps) const {
  if (n_ < 2) throw ImuInputError(source + ": fewer than 2 rows");
  ImuObservation o;
  o.source = std::move(source);
  o.thermal = thermal;
  o.count = n_;
  o.run = run;
  o.windows = windows_;
  const double n = n_;
  for (int i = 0; i < 9; ++i) {
    const double mean = sum_[i] / n;
    o.u_mean[i] = mean + (i >= 6 ? 4194304.0 : 0.0);
    o.u_sd[i] = std::sqrt(std::max(0.0, (sum2_[i] - n * mean * mean) / (n - 1.0)));
  }
  for (int g = 0; g < 3; ++g) {
    o.t_mean_cnt[g] = t_sum_[g] / n;
    o.t2_mean_cnt2[g] = t2_sum_[g] / n;
    o.t3_mean_cnt3[g] = t3_sum_[g] / n;
    double sxx = 0.0, sxy = 0.0;
    for (const SlopeSums& w : slope_) {
      sxx += w.uu - w.u * w.u / w.n;
      sxy += w.ut[g] - w.u * w.t[g] / w.n;
    }
    o.t_rate_cnt_per_s[g] = sxx > 0.0 ? sxy / sxx : 0.0;
  }
  o.f_B_g = f_B_g;
  o.w_B_dps = w_B_dps;
  return o;
}

std::vector<ImuObservation> ImuObservations(const ImuUnitData& unit,
                                            double g_local_mps2,
                                            double band_width_cnt) {
  const double g_l = common::Mps2ToG(g_local_mps2);
  std::vector<ImuObservation> out;
  auto up_of = [](int orientation) {
    const auto up = UpAxisOf(orientation);
    return Eigen::Vector3d(up[0], up[1], up[2]);
  };
  for (const auto* list : {&unit.accel, &unit.gyro, &unit.cross_axis}) {
    for (const ImuAcquisition& a : *list) {
      ObservationBuilder b;
      for (const ImuSample& s : a.samples) b.Add(s.raw, s.t_s);
      std::ostringstream source;
      source << a.run << " step " << a.step << " (" << a.step_kind << ") orientation "
             << a.orientation << " rate " << a.rate_dps << " dps";
      const Eigen::Vector3d up = up_of(a.orientation);
      out.push_back(
          b.Finish(source.str(), false, a.samples.front().run, g_l * up, a.rate_dps * up));
    }
  }
  if (!unit.thermal.empty()) {
    if (unit.thermal_orientation == 0) {
      throw ImuInputError("unit " + unit.serial + ": the thermal profile's orientation is unknown");
    }
    const Eigen::Vector3d up = up_of(unit.thermal_orientation);
    // (run, band, segment) -> rows
    std::map<std::tuple<int, long, int>, ObservationBuilder> bands;
    for (size_t i = 0; i < unit.thermal.size(); ++i) {
      const ImuSample& s = unit.thermal[i];
      const long band = std::lround(std::floor(s.raw.temp_cnt[0] / band_width_cnt));
      bands[{s.run, band, static_cast<int>(unit.thermal_segment[i])}].Add(s.raw, s.t_s);
    }
    static constexpr const char* kSegment[] = {"up", "down", "soak"};
    for (const auto& [key, b] : bands) {
      const auto& [run, band, segment] = key;
      try {
        out.push_back(b.Finish("run " + std::to_string(run) + " thermal band " +
                                   std::to_string(band) + " " + kSegment[segment],
                               true,
                               run,
                               g_l * up,
                               Eigen::Vector3d::Zero()));
      } catch (const ImuInputError&) {
        // A band crossed by a single row carries no spread; its row is too few to weigh.
      }
    }
  }
  return out;
}

}  // namespace adahrs::calib
