// The request an external IMU strategy program reads (docs/strategies-external.md "The
// request"): one unit's calibration data as the pipeline selected it (imu_run_data.h), each
// acquisition's raw outputs U (duty, counts) summarised per channel and optionally row by row,
// and the thermal profile summed per thermometer, temperature band and segment about the band's
// lower edge (the sufficient statistics of a band-weighted fit of order <= 2).
// Units: duty (accelerometers), counts (gyros, TEMP), deg/s, degC, m/s^2.
// Left out: the thermal profile's rows themselves (a program that needs them reads the recordings
// named in the request), anything of the simulator.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calib/imu_calibration/external_protocol.h"
#include "calib/imu_calibration/imu_run_data.h"

namespace adahrs::calib {

/// What the strategy file asks the request to hold.
struct ExternalRequestInputs {
  bool acquisition_samples = false;
  double thermal_band_width_cnt = 110.0;
};

/// One thermometer's rows of one temperature band and segment, summed about the band's lower edge
/// (pivot): d = temp_cnt - pivot_cnt, an integer in [0, band width).
struct ThermalBandSums {
  int thermometer = 0;
  long long band = 0;
  ThermalSegment segment = ThermalSegment::kSoak;
  double pivot_cnt = 0.0;
  long long count = 0;
  double temp_min_cnt = 0.0;
  double temp_max_cnt = 0.0;
  std::array<double, 4> d_sums{};  ///< sum d^k, k = 1..4
  struct Channel {
    int channel = 0;
    std::array<double, 3> u_sums{};  ///< sum d^k U, k = 0..2
    double u_mean = 0.0;
    double u_m2 = 0.0;  ///< sum (U - u_mean)^2
  };
  std::vector<Channel> channels;  ///< the channels this thermometer drives, in channel order
};

/// The thermal profile's band sums of one unit, sorted by thermometer, band and segment.
std::vector<ThermalBandSums> SumThermalBands(const ImuUnitData& unit, double band_width_cnt);

nlohmann::json ToJson(const ThermalBandSums& sums);

/// Everything the request says besides the data: the strategy's name, options and format.
struct ExternalRequestHeader {
  std::string strategy;
  nlohmann::json options = nlohmann::json::object();
  int firmware_format = 2;
  ExternalRequestInputs inputs;
};

/// The request for one unit of `data`.
nlohmann::json ExternalImuRequest(const ImuUnitData& unit,
                                  const ImuRunData& data,
                                  const ExternalRequestHeader& header);

}  // namespace adahrs::calib
