// The two kinds of unit a batch holds: an IMU or an air-data sensor (ADS). The values are the
// firmware's wire codes (the identity reply's unit kind and the flash image's kind word,
// firmware_model/target/unit_protocol.h), which firmware_model/unit_firmware.h checks; the text
// names are those of every file that names a kind (station, sequence, constants, study files).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace adahrs::common {

enum class UnitKind : uint8_t {
  kImu = 0x01,
  kAds = 0x02,
};

/// "imu" or "ads".
constexpr const char* UnitKindName(UnitKind kind) { return kind == UnitKind::kImu ? "imu" : "ads"; }

/// The kind named `name` ("imu" or "ads", exactly); nullopt for any other text.
constexpr std::optional<UnitKind> ParseUnitKind(std::string_view name) {
  if (name == "imu") return UnitKind::kImu;
  if (name == "ads") return UnitKind::kAds;
  return std::nullopt;
}

}  // namespace adahrs::common
