#include "calib/imu_calibration/mode_conformance.h"

#include <cmath>
#include <tuple>

#include "calib/imu_calibration/imu_run_data.h"
#include "common/atomic_file.h"
#include "firmware_model/reference_compensator.h"
#include "hil/recording/recording_reader.h"

namespace adahrs::calib {

namespace fm = firmware_model;

nlohmann::json ModeConformance::ToJson() const {
  nlohmann::json channel_list = nlohmann::json::array();
  for (const ChannelConformance& c : channels) {
    channel_list.push_back({{"max_abs_diff", c.max_abs_diff}, {"rms_diff", c.rms_diff}});
  }
  return {{"serial", serial},
          {"mode", mode},
          {"rows", rows},
          {"flagged_rows", flagged_rows},
          {"channels", channel_list}};
}

std::vector<ModeConformance> CheckModeConformance(
    const std::filesystem::path& run_dir,
    const std::map<std::string, fm::ImuCalibrationConstants>& constants) {
  std::map<std::pair<std::string, int>, ModeConformance> found;
  std::map<std::pair<std::string, int>, std::array<double, 9>> sum_sq;
  hil::RowSinks sinks;
  sinks.imu = [&](hil::ImuRecordRow&& row, int) {
    if (row.mode == 0 || !row.comp) return;
    const auto c = constants.find(row.unit);
    if (c == constants.end()) return;
    const std::pair<std::string, int> key{row.unit, row.mode};
    ModeConformance& m = found[key];
    m.serial = row.unit;
    m.mode = row.mode;
    if (row.comp_flags != 0) {
      ++m.flagged_rows;
      return;
    }
    const std::array<double, 9> model = fm::ImuReference(
        c->second, static_cast<fm::ImuCompensationMode>(row.mode), RawFrameOf(row));
    std::array<double, 9>& sq = sum_sq[key];
    for (size_t i = 0; i < 9; ++i) {
      const double d = (*row.comp)[i] - model[i];
      m.channels[i].max_abs_diff = std::max(m.channels[i].max_abs_diff, std::abs(d));
      sq[i] += d * d;
    }
    ++m.rows;
  };
  hil::StreamRecording(run_dir, sinks);
  std::vector<ModeConformance> out;
  for (auto& [key, m] : found) {
    for (size_t i = 0; i < 9 && m.rows > 0; ++i) {
      m.channels[i].rms_diff = std::sqrt(sum_sq[key][i] / static_cast<double>(m.rows));
    }
    out.push_back(m);
  }
  return out;
}

void WriteModeConformance(const std::filesystem::path& path,
                          const std::vector<RunConformance>& runs) {
  nlohmann::json entries = nlohmann::json::array();
  for (const RunConformance& run : runs) {
    for (const ModeConformance& m : run.units) {
      nlohmann::json j = m.ToJson();
      j["run"] = run.run_dir.string();
      entries.push_back(j);
    }
  }
  const nlohmann::json doc{
      {"format", "adahrs-mode-conformance"}, {"format_version", 1}, {"units", entries}};
  common::WriteFileAtomically(path, doc.dump(2) + "\n");
}

}  // namespace adahrs::calib
