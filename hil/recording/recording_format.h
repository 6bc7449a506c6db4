// The recording format (a contract, docs/recording-format.md): a run directory with meta.json and
// one CSV per unit kind, one row per received packet. Production recordings from real rigs use it
// and the analysis tools read it; a change of columns is a change of kFormatVersion.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace adahrs::hil {

inline constexpr int kRecordingFormatVersion = 1;
inline constexpr std::string_view kImuCsvName = "imu.csv";
inline constexpr std::string_view kAdsCsvName = "ads.csv";
inline constexpr std::string_view kMetaJsonName = "meta.json";

inline constexpr std::string_view kImuCsvHeader =
    "t_s,unit,seq,step,tag,orientation,chamber_c,table_rate_dps,"
    "az1_t1,az1_t2,ax1_t1,ax1_t2,ay1_t1,ay1_t2,az2_t1,az2_t2,ax2_t1,ax2_t2,ay2_t1,ay2_t2,"
    "gx,gy,gz,tx,ty,tz";
inline constexpr std::string_view kAdsCsvHeader =
    "t_s,unit,seq,step,tag,chamber_c,ps_ref_pa,qc_ref_pa,ps_counts,pt_counts,ps_temp_counts,"
    "pt_temp_counts,oat_counts";

/// One received IMU packet with the instrument readings current when it arrived.
struct ImuRecordRow {
  double t_s = 0.0;             ///< time on the run's time base (meta.json), seconds
  std::string unit;             ///< unit serial number
  uint32_t seq = 0;             ///< packet sequence counter as sent by the unit
  int step = 0;                 ///< index of the sequence step
  uint8_t tag = 0;              ///< the step's one-byte TAG carried by the packet
  int orientation = 0;          ///< fixture orientation code (11…32), 0 when not mounted
  double chamber_c = 0.0;       ///< chamber process value as the controller reports it
  double table_rate_dps = 0.0;  ///< rate as the rate table reports it
  std::array<uint16_t, 12> accel_ticks{};  ///< az1_t1, az1_t2, ax1_t1, … ay2_t2
  std::array<int32_t, 3> gyro_cnt{};       ///< gx gy gz
  std::array<uint16_t, 3> temp_cnt{};      ///< tx ty tz
};

/// One received ADS packet with the instrument readings current when it arrived.
struct AdsRecordRow {
  double t_s = 0.0;
  std::string unit;
  uint32_t seq = 0;
  int step = 0;
  uint8_t tag = 0;
  double chamber_c = 0.0;
  double ps_ref_pa = 0.0;  ///< static pressure as the air data test set reports it
  double qc_ref_pa = 0.0;  ///< impact pressure as the air data test set reports it
  int32_t ps_counts = 0;
  int32_t pt_counts = 0;
  int32_t ps_temp_counts = 0;
  int32_t pt_temp_counts = 0;
  int32_t oat_counts = 0;
};

}  // namespace adahrs::hil
