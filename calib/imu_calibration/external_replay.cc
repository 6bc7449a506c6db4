#include "calib/imu_calibration/external_replay.h"

#include <algorithm>

#include <fmt/format.h>

#include "calib/constants/constants_file.h"
#include "calib/imu_calibration/imu_run_data.h"
#include "calib/imu_calibration/imu_strategy.h"
#include "common/sha256.h"
#include "hil/recording/gzip_reader.h"

namespace adahrs::calib {
namespace {

using nlohmann::json;

std::string Gunzip(const std::filesystem::path& path) {
  hil::GzipReader reader(path);
  std::string text;
  char buffer[1 << 16];
  while (const size_t n = reader.Read(buffer, sizeof buffer)) text.append(buffer, n);
  if (reader.truncated()) throw ExternalStrategyError(path.string() + ": cut short");
  return text;
}

// The first number or value that differs between two JSON trees of the same schema: its path and
// both values; empty when they are equal.
std::string FirstDifference(const json& kept, const json& now, const std::string& path) {
  if (kept.type() != now.type() || kept.size() != now.size()) {
    return fmt::format("{}: kept {}, now {}", path, kept.dump(), now.dump());
  }
  if (kept.is_object()) {
    for (const auto& [key, value] : kept.items()) {
      if (!now.contains(key)) return fmt::format("{}.{}: not in the new reply", path, key);
      const std::string d = FirstDifference(value, now.at(key), path + "." + key);
      if (!d.empty()) return d;
    }
    return "";
  }
  if (kept.is_array()) {
    for (size_t i = 0; i < kept.size(); ++i) {
      const std::string d = FirstDifference(kept[i], now[i], fmt::format("{}[{}]", path, i));
      if (!d.empty()) return d;
    }
    return "";
  }
  return kept == now ? "" : fmt::format("{}: kept {}, now {}", path, kept.dump(), now.dump());
}

ExternalReplayOutcome Replay(const std::filesystem::path& fit_dir,
                             const ConstantsFile& file,
                             const std::optional<std::filesystem::path>& strategy_override) {
  const ExternalFitRecord& record = *file.provenance.external;
  const std::filesystem::path request_path = fit_dir / (file.serial + ".request.json.gz");
  const std::string request = Gunzip(request_path);
  if (common::Sha256Hex(request) != record.request_sha256) {
    throw ExternalStrategyError(request_path.string() + ": not the request the constants of " +
                                file.serial + " were fitted from (its SHA-256 differs from " +
                                "$.provenance.external.request_sha256)");
  }
  ExternalReplayOutcome o;
  o.serial = file.serial;
  o.strategy_file = strategy_override ? strategy_override->string() : record.strategy_file;
  const ImuStrategy strategy = ImuStrategy::Load(o.strategy_file);
  if (!strategy.external) {
    throw ExternalStrategyError(o.strategy_file + ": names no program (a built-in strategy)");
  }
  const ExternalImuProgram& program = *strategy.external;
  o.strategy_unchanged = program.strategy_sha256 == record.strategy_sha256;
  const ExternalRun run = RunExternalProgram(
      program, request, file.serial, "replay of " + file.serial + " with " + o.strategy_file);
  o.elapsed_s = run.elapsed_s;
  o.reply_identical = common::Sha256Hex(run.reply_bytes) == record.reply_sha256;
  o.difference = FirstDifference(firmware_model::ToJson(*file.imu),
                                 firmware_model::ToJson(run.reply.constants),
                                 "$.constants");
  o.constants_identical = o.difference.empty();
  return o;
}

}  // namespace

json ExternalReplayOutcome::ToJson() const {
  return {{"serial", serial},
          {"strategy_file", strategy_file},
          {"strategy_unchanged", strategy_unchanged},
          {"reply_identical", reply_identical},
          {"constants_identical", constants_identical},
          {"difference", difference},
          {"elapsed_s", elapsed_s}};
}

std::vector<ExternalReplayOutcome> ReplayExternalFits(
    const std::filesystem::path& fit_dir,
    const std::optional<std::filesystem::path>& strategy_file) {
  std::vector<std::filesystem::path> kept;
  if (std::filesystem::is_directory(fit_dir)) {
    for (const auto& entry : std::filesystem::directory_iterator(fit_dir)) {
      const std::string name = entry.path().filename().string();
      const std::string suffix = ".request.json.gz";
      if (name.size() > suffix.size() && name.ends_with(suffix)) kept.push_back(entry.path());
    }
  }
  std::sort(kept.begin(), kept.end());
  std::vector<ExternalReplayOutcome> outcomes;
  for (const std::filesystem::path& request : kept) {
    const std::string name = request.filename().string();
    const std::string serial = name.substr(0, name.size() - std::string(".request.json.gz").size());
    const ConstantsFile file = ReadConstantsFile(fit_dir / (serial + ".json"));
    if (!file.provenance.external) {
      throw ExternalStrategyError((fit_dir / (serial + ".json")).string() +
                                  ": $.provenance.external missing: not an external fit");
    }
    outcomes.push_back(Replay(fit_dir, file, strategy_file));
  }
  if (outcomes.empty()) {
    throw ImuInputError(fit_dir.string() +
                        ": no external fit to replay (no <serial>.request.json.gz)");
  }
  return outcomes;
}

}  // namespace adahrs::calib
