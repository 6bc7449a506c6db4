#include "calib/campaign/campaign_fits.h"

#include <algorithm>

#include "calib/ads_calibration/ads_calibration_points.h"
#include "calib/ads_calibration/tolerance_ads_strategy.h"
#include "calib/constants/recording_checksum.h"
#include "calib/imu_calibration/imu_run_data.h"
#include "calib/sequence/sequence_json.h"
#include "common/atomic_file.h"
#include "hil/recording/gzip_bytes.h"
#include "hil/recording/recording_reader.h"

namespace adahrs::calib {
namespace {

WrittenConstants Write(const std::filesystem::path& fit_dir, ConstantsFile file) {
  std::filesystem::create_directories(fit_dir);
  const std::filesystem::path path = fit_dir / (file.serial + ".json");
  WriteConstantsFile(path, file);
  return {path, std::move(file), {}};
}

// An external program's fits: every unit fitted first, then each file written with the request
// and reply it came from.
std::vector<WrittenConstants> FitExternalIntoDirectory(
    const std::vector<std::filesystem::path>& run_dirs,
    const ImuStrategy& strategy,
    const std::filesystem::path& fit_dir,
    const std::string& software_version) {
  const ImuRunData data = LoadImuRuns(run_dirs);
  std::vector<std::pair<ConstantsFile, ExternalExchange>> fits;
  for (const auto& [serial, unit] : data.units) {
    ExternalExchange exchange;
    ConstantsFile file =
        FitImuExternal(unit, data, *strategy.external, software_version, &exchange);
    fits.emplace_back(std::move(file), std::move(exchange));
  }
  std::vector<WrittenConstants> written;
  for (auto& [file, exchange] : fits) {
    std::filesystem::create_directories(fit_dir);
    common::WriteFileAtomically(fit_dir / (file.serial + ".request.json.gz"),
                                hil::GzipBytes(exchange.request));
    common::WriteFileAtomically(fit_dir / (file.serial + ".reply.json.gz"),
                                hil::GzipBytes(exchange.reply));
    written.push_back(Write(fit_dir, std::move(file)));
    written.back().log = std::move(exchange.log);
  }
  return written;
}

}  // namespace

std::vector<WrittenConstants> FitImuIntoDirectory(
    const std::vector<std::filesystem::path>& run_dirs,
    const ImuStrategy& strategy,
    const std::filesystem::path& fit_dir,
    const std::string& software_version,
    const std::optional<ImuStageRequest>& staged) {
  if (strategy.external && !staged) {
    return FitExternalIntoDirectory(run_dirs, strategy, fit_dir, software_version);
  }
  std::vector<WrittenConstants> written;
  for (ConstantsFile& file : FitImuRuns(run_dirs, strategy, software_version, staged)) {
    written.push_back(Write(fit_dir, std::move(file)));
  }
  return written;
}

std::vector<WrittenConstants> FitAdsIntoDirectory(const std::filesystem::path& run_dir,
                                                  const std::string& strategy,
                                                  const std::filesystem::path& fit_dir,
                                                  const std::string& software_version) {
  const hil::RecordingMeta meta = hil::ReadRecordingMeta(run_dir).meta;
  const std::string source = run_dir.string();
  const RecordingReference reference{run_dir.string(), RecordingSha256(run_dir)};
  if (!meta.sequence) throw std::runtime_error(source + "/meta.json: $.sequence missing");
  const std::string sequence_name =
      SequenceFromJson(*meta.sequence, source + "/meta.json $.sequence").name;
  std::vector<std::string> serials;
  for (const hil::RecordingUnit& unit : meta.units) {
    if (unit.kind == hil::UnitKind::kAds) serials.push_back(unit.serial);
  }
  const auto points = StreamAdsCalibrationPoints(run_dir, serials, source);
  std::vector<WrittenConstants> written;
  for (const std::string& serial : serials) {
    const AdsFitResult fit = FitAdsStrategy(strategy, serial, points.at(serial));
    ConstantsFile file;
    file.serial = serial;
    file.kind = hil::UnitKind::kAds;
    file.strategy = fit.strategy;
    file.created_utc = UtcNowIso8601();
    file.software_version = software_version;
    file.ads = fit.constants;
    file.standard_errors = fit.standard_errors;
    file.provenance = {{reference}, {sequence_name}, std::nullopt};
    file.ads_diagnostics = fit.diagnostics;
    written.push_back(Write(fit_dir, std::move(file)));
  }
  return written;
}

std::vector<WrittenConstants> ReadFitDirectory(const std::filesystem::path& fit_dir) {
  std::vector<std::filesystem::path> files;
  if (std::filesystem::is_directory(fit_dir)) {
    for (const auto& entry : std::filesystem::directory_iterator(fit_dir)) {
      const std::filesystem::path& p = entry.path();
      if (p.extension() == ".json" && p.filename() != "evaluation.json") files.push_back(p);
    }
  }
  std::sort(files.begin(), files.end());
  std::vector<WrittenConstants> written;
  for (const std::filesystem::path& p : files) written.push_back({p, ReadConstantsFile(p), {}});
  return written;
}

}  // namespace adahrs::calib
