#include "calib/download/constants_download.h"

#include <fmt/format.h>

#include "calib/download/readback_check.h"
#include "hil/drivers/unit_serial.h"
#include "hil/instruments/instrument_error.h"

namespace adahrs::calib {
namespace {

namespace fm = firmware_model;

class Context {
 public:
  Context(const hil::UnitLink& link, const std::string& source)
      : prefix_(fmt::format(
            "download of {} into {} on {}", source, link.entry().role, link.entry().port.path)) {}
  // Before COMMIT nothing is committed; from COMMIT on the failure says what is known.
  [[noreturn]] void Fail(const std::string& step, const std::string& what, bool verified) const {
    const char* state = !verified          ? "nothing committed"
                        : step == "commit" ? "commit state unknown (IDENTIFY the unit)"
                                           : "the unit reported a commit";
    throw DownloadError(fmt::format("{}: {}: {}; {}", prefix_, step, what, state), verified);
  }
  // Runs `action`, turning an instrument error into a DownloadError naming `step`.
  template <typename F>
  auto Run(const std::string& step, bool verified, F&& action) const {
    try {
      return action();
    } catch (const hil::InstrumentError& e) {
      Fail(step, e.what(), verified);
    }
  }

 private:
  std::string prefix_;
};

// The IMU mode step 6 sets: after the file's last stage (a whole file: fully calibrated).
fm::ImuCompensationMode ImuModeAfter(const ConstantsFile& file) {
  if (!file.stages.empty()) return ModeAfter(file.stages.back());
  return fm::ImuCompensationMode::kFullyCalibrated;
}

}  // namespace

DownloadResult DownloadConstants(hil::UnitLink& link,
                                 const ConstantsFile& file,
                                 const std::string& source) {
  const Context context(link, source);
  DownloadResult result;
  try {
    result.blocks = ExportConstantsBlocks(file, source);
  } catch (const ConstantsBlocksError& e) {
    context.Fail("export", e.what(), false);
  }
  result.before = context.Run("identify", false, [&] { return link.Identify(); });
  const hil::UnitKind unit_kind = result.before.unit_kind;  // UnitLink::Identify checked it
  const std::string unit_serial = hil::UnitSerialText(unit_kind, result.before.serial_number);
  if (unit_kind != file.kind || unit_serial != file.serial) {
    context.Fail("identify",
                 fmt::format("the unit is {}, the constants are for {}", unit_serial, file.serial),
                 false);
  }
  context.Run("set raw mode", false, [&] {
    if (unit_kind == hil::UnitKind::kImu) {
      link.SetImuMode(fm::ImuCompensationMode::kRaw);
    } else {
      link.SetAdsMode(fm::AdsCompensationMode::kRaw);
    }
  });
  for (const ConstantsBlock& block : result.blocks.blocks) {
    context.Run(fmt::format("write block 0x{:02X} ({})", block.block_id, block.name), false, [&] {
      link.WriteBlock(block.block_id, block.words);
    });
  }
  for (const ConstantsBlock& block : result.blocks.blocks) {
    const std::string step =
        fmt::format("read back block 0x{:02X} ({})", block.block_id, block.name);
    const std::vector<int16_t> read =
        context.Run(step, false, [&] { return link.ReadBlock(block.block_id); });
    if (const auto mismatch = CompareReadback(block.words, read)) {
      context.Fail(step, "differs from what was written, " + mismatch->Describe(), false);
    }
  }
  result.commit = context.Run("commit", true, [&] { return link.Commit(); });
  result.after = context.Run("identify after commit", true, [&] { return link.Identify(); });
  if (!result.after.constants_valid ||
      result.after.constants_version != result.commit.constants_version ||
      result.after.constants_crc != result.commit.constants_crc) {
    context.Fail("identify after commit",
                 fmt::format("COMMIT answered version {} crc 0x{:04X}, IDENTIFY reports constants "
                             "{}, version {}, crc 0x{:04X}",
                             result.commit.constants_version,
                             result.commit.constants_crc,
                             result.after.constants_valid ? "valid" : "invalid",
                             result.after.constants_version,
                             result.after.constants_crc),
                 true);
  }
  context.Run("set calibrated mode", true, [&] {
    if (unit_kind == hil::UnitKind::kImu) {
      const fm::ImuCompensationMode mode = ImuModeAfter(file);
      link.SetImuMode(mode);
      result.mode = static_cast<uint8_t>(mode);
    } else {
      link.SetAdsMode(fm::AdsCompensationMode::kSurface);
      result.mode = static_cast<uint8_t>(fm::AdsCompensationMode::kSurface);
    }
  });
  return result;
}

}  // namespace adahrs::calib
