#include "calib/download/constants_blocks.h"

#include <array>

#include <fmt/format.h>

#include "common/imu_layout.h"
#include "firmware_model/unit_firmware.h"

namespace adahrs::calib {
namespace {

namespace fm = firmware_model;

std::string ImuBlockName(uint8_t id) {
  if (id >= fm::kImuBlockThermalFirst && id <= fm::kImuBlockThermalLast) {
    return fmt::format("thermal {}", common::kImuChannelNames[id - fm::kImuBlockThermalFirst]);
  }
  if (id == fm::kImuBlockAccelOffsetScale) return "accel offsets and scales";
  if (id >= fm::kImuBlockGyroCubicFirst && id <= fm::kImuBlockGyroCubicLast) {
    return fmt::format("gyro {} cubic", "xyz"[id - fm::kImuBlockGyroCubicFirst]);
  }
  if (id == fm::kImuBlockCa) return "CA";
  if (id == fm::kImuBlockCg) return "CG";
  if (id == fm::kImuBlockScaleSwitch) return "scale-temperature switch";
  if (id >= fm::kImuBlockScaleFactorFirst && id <= fm::kImuBlockScaleFactorLast) {
    return fmt::format("scale factor {}",
                       common::kImuChannelNames[id - fm::kImuBlockScaleFactorFirst]);
  }
  return id == fm::kImuBlockAccelQuadratic ? "accel nonlinearity" : "gyro g-sensitivity";
}

}  // namespace

ConstantsBlocks ExportConstantsBlocks(const ConstantsFile& file, const std::string& source) {
  ConstantsBlocks out;
  out.kind = file.kind;
  try {
    if (file.kind == hil::UnitKind::kImu) {
      if (!file.imu) throw ConstantsBlocksError("no IMU constants");
      const fm::ImuExport exported = fm::ExportImuConstants(*file.imu);
      out.imu_report = exported.report;
      out.error_bounds = {{"accel_g", exported.report.accel_g},
                          {"rate_dps", exported.report.rate_dps},
                          {"accel_mps2", exported.report.accel_mps2},
                          {"rate_full_dps", exported.report.rate_full_dps}};
      // Every block, the format-3 ones with their switch off for format-2 constants, so that no
      // stage of an earlier download survives this one (docs/unit-protocol.md §6.3).
      for (uint8_t id = fm::kImuBlockThermalFirst; id <= fm::kImuBlockLast; ++id) {
        std::array<int16_t, fm::kImuMaxBlockWords> words{};
        uint8_t count = 0;
        if (fm::ImuConstantsReadBlock(
                &exported.constants, id, words.data(), words.size(), &count) !=
            fm::ConstantsStatus::kOk) {
          throw ConstantsBlocksError(fmt::format("block 0x{:02X} cannot be serialised", id));
        }
        out.blocks.push_back({id, ImuBlockName(id), {words.begin(), words.begin() + count}});
      }
    } else {
      if (!file.ads) throw ConstantsBlocksError("no ADS constants");
      const fm::AdsExport exported = fm::ExportAdsConstants(*file.ads);
      out.ads_report = exported.report;
      out.error_bounds = {{"altitude_ft", exported.report.altitude_ft},
                          {"airspeed_kt", exported.report.airspeed_kt}};
      for (const uint8_t id : {fm::kAdsBlockAltitude, fm::kAdsBlockAirspeed}) {
        std::array<int16_t, fm::kAdsMaxBlockWords> words{};
        uint8_t count = 0;
        if (fm::AdsConstantsReadBlock(
                &exported.constants, id, words.data(), words.size(), &count) !=
            fm::ConstantsStatus::kOk) {
          throw ConstantsBlocksError(fmt::format("block 0x{:02X} cannot be serialised", id));
        }
        out.blocks.push_back({id,
                              id == fm::kAdsBlockAltitude ? "altitude surface" : "airspeed surface",
                              {words.begin(), words.begin() + count}});
      }
    }
  } catch (const std::exception& e) {
    throw ConstantsBlocksError(
        fmt::format("{} ({}): cannot be converted to the unit's fixed-point "
                    "blocks: {}",
                    source,
                    file.serial,
                    e.what()));
  }
  return out;
}

}  // namespace adahrs::calib
