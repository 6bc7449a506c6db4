// One IMU's recorded rows cut into segments and cells, the units of diagnosis. A segment is one
// acquisition (step, orientation, table rate) or one contiguous thermal-profile stretch of one
// trend: the clusters of every inference and the folds of every held-out check, so a segment-wide
// disturbance never counts as evidence twice. A cell is at most kCellDuration_s of one segment's
// rows, holding the means of the raw outputs and of the stimulus (a linear model averages
// exactly), and per thermometer the temperature, its rate (slope over +-kRateWindow_s within the
// run), the sense of its last change and the time since the run's first row. Also each segment's
// row spectra (row_spectrum.h) and the gyros' lock-ins at the table's revolution frequency
// (rate_ripple.h).
// Units: accelerometer duty T1/T2 - 0.5, gyro counts (az1 ax1 ay1 az2 ax2 ay2 gx gy gz); the gyro
// TEMP pins in degC by a line fitted on the recording's own soaks (110.1 counts/degC datasheet
// slope when it visits one temperature); f_B in g, rates in deg/s, times in s.
// Segments, cells and their derived values: docs/diagnose.md ("Method (IMU)", steps 1, 6, 7).
// Left out: interpolation across gaps (a gap only splits cells), any model of the sensors.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "calib/imu_calibration/imu_run_data.h"
#include "common/imu_layout.h"
#include "diagnosis/rate_ripple.h"
#include "diagnosis/row_spectrum.h"

namespace adahrs::diagnosis {

inline constexpr int kImuChannels = common::kImuChannelCount;
inline constexpr double kCellDuration_s = 1.0;
inline constexpr double kRateWindow_s = 60.0;
/// A thermometer changing slower than this is still (0.05 degC/min): the soaks the thermometer
/// map is fitted on.
inline constexpr double kTrendThreshold_c_per_s = 0.05 / 60.0;
/// ADXRS150 TEMP through 16 summed 12-bit conversions: 16 * 4096 / 5 V * 8.4 mV/K (datasheet).
inline constexpr double kDatasheetTempCountsPerC = 110.10;
/// ADXL210E duty-cycle sensitivity, 4 %/g (datasheet), where a recording does not give its own.
inline constexpr double kAccelDatasheetDutyPerG = 0.04;
/// ADXRS150 rate through 16 summed 19-bit conversions: 16 * 2^19 / 5 V * 12.5 mV/(deg/s).
inline constexpr double kGyroDatasheetCountsPerDps = 20971.52;

struct DiagnosisSegment {
  std::string label;  ///< "run 0 step 4 accel orientation 11", "run 0 thermal down-ramp 2"
  std::string
      kind;  ///< "thermal_up", "thermal_down", "thermal_soak", "accel", "gyro", "cross_axis"
  int run = 0;
  int step = -1;  ///< -1 for thermal stretches (the profile's step is in the label)
  int orientation = 0;
  double rate_dps = 0.0;
  double t_first_s = 0.0;
  double t_last_s = 0.0;
  double chamber_mean_c = 0.0;
  int rows = 0;
};

struct DiagnosisCell {
  int segment = 0;
  int run = 0;
  int rows = 0;
  double t_mean_s = 0.0;
  double t_first_s = 0.0;
  double t_last_s = 0.0;
  std::array<double, kImuChannels> y_mean{};
  std::array<double, kImuChannels> y_var{};  ///< sample variance of the rows (0 for one row)
  std::array<double, 3> temp_cnt_mean{};
  double chamber_c = 0.0;
  Eigen::Vector3d f_B_g = Eigen::Vector3d::Zero();
  Eigen::Vector3d w_B_dps = Eigen::Vector3d::Zero();
  // Derived from the recording (DeriveThermalState):
  std::array<double, 3> temp_c{};
  std::array<double, 3> dtemp_dt_c_per_s{};
  std::array<double, 3> last_change_sense{};
  double t_since_start_s = 0.0;
};

/// The line counts = offset_cnt + slope_cnt_per_c * temp_c of one TEMP sensor.
struct ThermometerMap {
  double offset_cnt = 0.0;
  double slope_cnt_per_c = kDatasheetTempCountsPerC;
  bool fitted = false;  ///< false: datasheet slope, offset from the recording's mean
  double ToC(double counts) const { return (counts - offset_cnt) / slope_cnt_per_c; }
};

struct DiagnosisData {
  std::string serial;
  std::vector<DiagnosisSegment> segments;
  std::vector<DiagnosisCell> cells;  ///< grouped by segment, time order within each
  std::array<ThermometerMap, 3> thermometers;
  double temp_span_c = 0.0;  ///< range of thermometer 0 over the cells
  int rows = 0;
  /// Row-level spectra of the raw outputs, per channel and segment, at the recording's median
  /// row interval (row_spectrum.h).
  RowSpectra spectra{kImuChannels, 0.0};
  /// The same rows in windows kSlowWindowFactor times longer: the slow band below `spectra`'s.
  RowSpectra slow_spectra{kImuChannels, 0.0, kSpectrumWindowRows* kSlowWindowFactor};
  /// The step of each raw output: one timer tick over the mean period (duty), or one count.
  std::array<double, kImuChannels> output_quantum{};
  /// Packets missing inside segments, by the 8-bit sequence counter against its usual step in
  /// the segment (1, or the recording's log_every): gaps, packets missing (a gap of 256 packets
  /// or more is under-counted modulo 256), and the time of the largest. Cells close at a gap in
  /// time; nothing is interpolated.
  int seq_gaps = 0;
  int64_t seq_missing = 0;
  /// Per gyro (x, y, z): the lock-ins at the table's revolution frequency of the rate segments
  /// with that gyro on the table axis (rate_ripple.h), from the rows.
  std::array<std::vector<RippleSegment>, 3> ripple;
  double largest_seq_gap_at_s = 0.0;
  int largest_seq_gap = 0;
};

/// Cuts one unit's calibration data into segments and cells and derives the thermal state.
/// Throws ImuInputError naming the unit when it has fewer than 2 segments.
DiagnosisData BuildDiagnosisData(const calib::ImuUnitData& unit,
                                 double g_local_mps2,
                                 double cell_duration_s = kCellDuration_s);

}  // namespace adahrs::diagnosis
