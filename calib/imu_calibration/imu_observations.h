// Per-acquisition and per-temperature-band means of one IMU's calibration data with their known
// stimulus: the observations of the joint strategy (imu_joint_fit.h) and of the evaluation's
// projection of a true unit onto the firmware model (calib/evaluation).
//
// Each observation holds, over its rows, the mean raw output U of the nine channels (duty
// T1/T2 - 0.5, gyro counts) with its sample standard deviation, the mean of t and of t^2 of each
// TEMP sensor (so a model linear in its parameters with t and t^2 terms is averaged exactly), the
// specific force f_B in g (local gravity along the up axis: f = g_local / 9.80665 * up) and the
// rate w_B in deg/s (reported table rate about the up axis).
// Thermal-profile rows are grouped into bands of band_width_cnt of TEMP sensor 0, ramp segment
// (up, down, soak) and run, so up- and down-ramp bands stay apart.
// When its rows were taken: the run they come from and their time windows (rows closer than
// kWindowMergeGap_s in time form one window; a band revisited by a later ramp has two), for the
// covariance of slowly wandering gyro bias between observations (gyro_bias_covariance.h).
// Not represented: centripetal acceleration on the table (the unit sits on the axis), Earth rate.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "calib/imu_calibration/imu_run_data.h"

namespace adahrs::calib {

/// Rows this far apart or less in time belong to one window.
inline constexpr double kWindowMergeGap_s = 2.0;

/// A stretch of time the rows of an observation cover: first and last row times and row count.
struct TimeWindow {
  double first_s = 0.0;
  double last_s = 0.0;
  int rows = 0;
};

struct ImuObservation {
  std::string source;  ///< "step 4 orientation 11 rate 50.004 dps", "thermal band 3 up"
  bool thermal = false;
  int count = 0;
  int run = 0;                      ///< index of the run (ImuSample::run)
  std::vector<TimeWindow> windows;  ///< in time order within the run
  std::array<double, 9> u_mean{};
  std::array<double, 9> u_sd{};
  std::array<double, 3> t_mean_cnt{};    ///< per TEMP sensor
  std::array<double, 3> t2_mean_cnt2{};  ///< mean of t^2 per TEMP sensor
  std::array<double, 3> t3_mean_cnt3{};  ///< mean of t^3 per TEMP sensor
  /// dt/dtime per TEMP sensor, counts per s: the least-squares slope of t against the rows' times
  /// within each window, pooled over the windows (0 with fewer than 2 rows per window).
  std::array<double, 3> t_rate_cnt_per_s{};
  Eigen::Vector3d f_B_g = Eigen::Vector3d::Zero();
  Eigen::Vector3d w_B_dps = Eigen::Vector3d::Zero();
};

/// Accumulates rows into one observation.
class ObservationBuilder {
 public:
  /// Adds a row taken at `t_s` (the run's clock; rows in time order).
  void Add(const firmware_model::ImuRawFrame& raw, double t_s);
  /// Needs at least 2 rows; throws ImuInputError naming `source` otherwise.
  ImuObservation Finish(std::string source,
                        bool thermal,
                        int run,
                        const Eigen::Vector3d& f_B_g,
                        const Eigen::Vector3d& w_B_dps) const;

 private:
  // Sums of one window for the temperature slope: u = time since the window's first row.
  struct SlopeSums {
    double n = 0.0, u = 0.0, uu = 0.0;
    std::array<double, 3> t{}, ut{};
  };
  int n_ = 0;
  std::vector<TimeWindow> windows_;
  std::vector<SlopeSums> slope_;
  std::array<double, 9> sum_{}, sum2_{};
  std::array<double, 3> t_sum_{}, t2_sum_{}, t3_sum_{};
};

/// Every acquisition of `unit` and its thermal bands as observations.
std::vector<ImuObservation> ImuObservations(const ImuUnitData& unit,
                                            double g_local_mps2,
                                            double band_width_cnt = 110.0);

}  // namespace adahrs::calib
