#include "proving/demo/truth_evaluation.h"

#include <fstream>
#include <limits>
#include <stdexcept>

#include "calib/acceptance/specification.h"
#include "proving/evaluation/ads_evaluation_report.h"
#include "proving/evaluation/imu_evaluation.h"
#include "proving/evaluation/truth_file.h"

namespace adahrs::proving {
namespace {

void WriteJson(const std::filesystem::path& path, const nlohmann::json& json) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path);
  out << json.dump(2) << "\n";
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

EvaluatedQuantity AdsRow(const std::string& serial,
                         const std::string& name,
                         const AdsQuantityEvaluation& q,
                         const std::string& verdict) {
  return {serial, name, "x tolerance", q.worst_ratio_no_history, 1.0, verdict};
}

}  // namespace

std::vector<EvaluatedQuantity> EvaluateAgainstTruth(
    const std::vector<calib::WrittenConstants>& constants,
    const std::filesystem::path& truth_dir,
    double g_local_mps2,
    const std::filesystem::path& fit_dir) {
  const calib::Specification spec = calib::Specification::Reference();
  std::vector<EvaluatedQuantity> rows;
  for (const calib::WrittenConstants& written : constants) {
    const calib::ConstantsFile& file = written.file;
    const TruthFile truth = ReadTruthFile(truth_dir / (file.serial + ".json"));
    nlohmann::json detail;
    if (file.kind == hil::UnitKind::kImu) {
      ImuEvaluationOptions options;
      options.g_local_mps2 = g_local_mps2;
      try {
        const ImuEvaluation e = EvaluateImu(file, ImuTruth(truth, file.serial), spec, options);
        rows.push_back(
            {file.serial, "acceleration", "mg", e.worst_accel_mg, spec.accel_mg, e.accel_verdict});
        rows.push_back({file.serial,
                        "body rate",
                        "deg/s",
                        e.worst_rate_dps,
                        spec.body_rate_dps,
                        e.rate_verdict});
        detail = e.report;
      } catch (const ConstantsNotExportable& e) {
        // Constants the firmware cannot hold (the exporter's refusal) are a result of the
        // strategy, not an error of the campaign: no worst error, the reason as the verdict.
        const std::string verdict = std::string("not evaluated: ") + e.what();
        const double nan = std::numeric_limits<double>::quiet_NaN();
        rows.push_back({file.serial, "acceleration", "mg", nan, spec.accel_mg, verdict});
        rows.push_back({file.serial, "body rate", "deg/s", nan, spec.body_rate_dps, verdict});
        detail = {{"serial", file.serial}, {"error", e.what()}};
      }
    } else {
      const AdsFileEvaluation e = EvaluateAds(file, AdsTruth(truth, file.serial));
      rows.push_back(AdsRow(file.serial, "altitude", e.evaluation.altitude, e.altitude_verdict));
      rows.push_back(AdsRow(file.serial, "airspeed", e.evaluation.airspeed, e.airspeed_verdict));
      detail = e.report;
    }
    WriteJson(fit_dir / "evaluation" / (file.serial + ".json"), detail);
  }
  nlohmann::json table = nlohmann::json::array();
  for (const EvaluatedQuantity& r : rows) {
    table.push_back({{"serial", r.serial},
                     {"quantity", r.quantity},
                     {"worst_error", r.worst},
                     {"tolerance", r.tolerance},
                     {"unit", r.unit},
                     {"verdict", r.verdict}});
  }
  WriteJson(
      fit_dir / "evaluation.json",
      {{"truth_dir", truth_dir.string()}, {"specification", spec.ToJson()}, {"units", table}});
  return rows;
}

}  // namespace adahrs::proving
