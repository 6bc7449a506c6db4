// The recording format (a contract, docs/recording-format.md): a run directory with meta.json and
// one CSV per unit kind, one row per received packet. Production recordings from real rigs use it
// and the analysis tools read it; a change of columns is a change of kRecordingFormatVersion.
// Version 4 is written (ADS raw counts named ps_cnt … oat_cnt); versions 1 to 3 are still read
// (ps_counts … oat_counts; version 3 adds frame and t_sample_s, version 2 the compensated columns,
// EMPTY in raw mode). Imu and ads CSVs are stored plain or gzip-compressed (recording_files.h).
// Units: every column's unit is in its name or the format doc; compensated values are in the
// engineering units of the unit's mode (compensated_values.h: duty, counts, g, deg/s, m/s^2, ft,
// kt), body frame for IMU mode 3.
// Columns, modes and versions: docs/recording-format.md ("imu.csv", "ads.csv", "Version 3" …).
// Left out: the time base and every run-level fact, which live in meta.json.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace adahrs::hil {

inline constexpr int kRecordingFormatVersion = 4;
/// The oldest version ReadRecording still accepts.
inline constexpr int kOldestReadableFormatVersion = 1;
inline constexpr std::string_view kImuCsvName = "imu.csv";
inline constexpr std::string_view kAdsCsvName = "ads.csv";
inline constexpr std::string_view kMetaJsonName = "meta.json";

inline constexpr std::string_view kImuCsvHeaderV1 =
    "t_s,unit,seq,step,tag,orientation,chamber_c,table_rate_dps,"
    "az1_t1,az1_t2,ax1_t1,ax1_t2,ay1_t1,ay1_t2,az2_t1,az2_t2,ax2_t1,ax2_t2,ay2_t1,ay2_t2,"
    "gx,gy,gz,tx,ty,tz";
inline constexpr std::string_view kAdsCsvHeaderV1 =
    "t_s,unit,seq,step,tag,chamber_c,ps_ref_pa,qc_ref_pa,ps_counts,pt_counts,ps_temp_counts,"
    "pt_temp_counts,oat_counts";
inline constexpr std::string_view kImuCsvHeaderV2 =
    "t_s,unit,seq,step,tag,orientation,chamber_c,table_rate_dps,"
    "az1_t1,az1_t2,ax1_t1,ax1_t2,ay1_t1,ay1_t2,az2_t1,az2_t2,ax2_t1,ax2_t2,ay2_t1,ay2_t2,"
    "gx,gy,gz,tx,ty,tz,mode,comp0,comp1,comp2,comp3,comp4,comp5,comp6,comp7,comp8,comp_flags";
inline constexpr std::string_view kAdsCsvHeaderV2 =
    "t_s,unit,seq,step,tag,chamber_c,ps_ref_pa,qc_ref_pa,ps_counts,pt_counts,ps_temp_counts,"
    "pt_temp_counts,oat_counts,mode,alt_ft,cas_kt,comp_flags";
/// The latest version's columns; the IMU columns are the same in versions 3 and 4.
inline constexpr std::string_view kImuCsvHeader =
    "t_s,unit,seq,step,tag,orientation,chamber_c,table_rate_dps,"
    "az1_t1,az1_t2,ax1_t1,ax1_t2,ay1_t1,ay1_t2,az2_t1,az2_t2,ax2_t1,ax2_t2,ay2_t1,ay2_t2,"
    "gx,gy,gz,tx,ty,tz,mode,comp0,comp1,comp2,comp3,comp4,comp5,comp6,comp7,comp8,comp_flags,"
    "frame,t_sample_s";
inline constexpr std::string_view kAdsCsvHeaderV3 =
    "t_s,unit,seq,step,tag,chamber_c,ps_ref_pa,qc_ref_pa,ps_counts,pt_counts,ps_temp_counts,"
    "pt_temp_counts,oat_counts,mode,alt_ft,cas_kt,comp_flags,frame,t_sample_s";
inline constexpr std::string_view kAdsCsvHeader =
    "t_s,unit,seq,step,tag,chamber_c,ps_ref_pa,qc_ref_pa,ps_cnt,pt_cnt,ps_temp_cnt,pt_temp_cnt,"
    "oat_cnt,mode,alt_ft,cas_kt,comp_flags,frame,t_sample_s";

/// One received IMU packet with the instrument readings current when it arrived.
struct ImuRecordRow {
  double t_s = 0.0;             ///< time on the run's time base (meta.json), seconds
  std::string unit;             ///< unit serial text, "IMU-0001"
  uint32_t seq = 0;             ///< packet sequence counter as sent by the unit
  int step = 0;                 ///< index of the sequence step
  uint8_t tag = 0;              ///< the step's one-byte TAG carried by the packet
  int orientation = 0;          ///< fixture orientation code (11…32), 0 when not mounted
  double chamber_c = 0.0;       ///< chamber process value as the controller reports it
  double table_rate_dps = 0.0;  ///< rate as the rate table reports it
  std::array<uint16_t, 12> accel_ticks{};  ///< az1_t1, az1_t2, ax1_t1, … ay2_t2
  std::array<int32_t, 3> gyro_cnt{};       ///< gx gy gz
  std::array<uint16_t, 3> temp_cnt{};      ///< tx ty tz
  uint8_t mode = 0;                        ///< the unit's mode byte (0 raw)
  /// Compensated values in the mode's engineering units; absent in raw mode and in version 1.
  std::optional<std::array<double, 9>> comp;
  uint32_t comp_flags = 0;  ///< compensation status flags (compensated_frame.h), 0 when absent
  /// The unit's frame index (frame_count.h); sample time frame * 10 ms. -1: not known yet, the
  /// writer counts it from seq and t_s.
  int64_t frame = -1;
  /// The packet's index on a lockstep rig's count of the unit's packets (hil::ReceivedPacket),
  /// which the writer counts frames by; not written. -1: none.
  int64_t packet_index = -1;
};

/// One received ADS packet with the instrument readings current when it arrived.
struct AdsRecordRow {
  double t_s = 0.0;
  std::string unit;  ///< unit serial text, "ADS-0001"
  uint32_t seq = 0;
  int step = 0;
  uint8_t tag = 0;
  double chamber_c = 0.0;
  double ps_ref_pa = 0.0;        ///< static pressure as the air data test set reports it
  double qc_ref_pa = 0.0;        ///< impact pressure as the air data test set reports it
  int32_t ps_cnt = 0;            ///< static bridge output, ADS1254 code
  int32_t pt_cnt = 0;            ///< pitot bridge output, ADS1254 code
  int32_t ps_temp_cnt = 0;       ///< static bridge voltage (its temperature), ADS1254 code
  int32_t pt_temp_cnt = 0;       ///< pitot bridge voltage (its temperature), ADS1254 code
  int32_t oat_cnt = 0;           ///< outside-air-temperature probe, ADS1254 code
  uint8_t mode = 0;              ///< the unit's mode byte (0 raw)
  std::optional<double> alt_ft;  ///< surface-mode pressure altitude; absent in raw mode
  std::optional<double> cas_kt;  ///< surface-mode calibrated airspeed; absent in raw mode
  uint32_t comp_flags = 0;       ///< compensation status flags, 0 when absent
  int64_t frame = -1;            ///< as ImuRecordRow::frame
  int64_t packet_index = -1;     ///< as ImuRecordRow::packet_index
};

}  // namespace adahrs::hil
