#include "hil/drivers/unit_serial.h"

#include <fmt/format.h>

namespace adahrs::hil {

std::string UnitSerialText(UnitKind kind, uint32_t serial_number) {
  return fmt::format("{}-{:04d}", kind == UnitKind::kImu ? "IMU" : "ADS", serial_number);
}

}  // namespace adahrs::hil
