#include "proving/evaluation/ads_evaluation_report.h"

#include <stdexcept>

#include <fmt/format.h>

#include "calib/acceptance/ads_tolerance.h"
#include "calib/acceptance/specification.h"

namespace adahrs::proving {
namespace {

nlohmann::json GridPointsJson(const AdsQuantityEvaluation& q) {
  nlohmann::json points = nlohmann::json::array();
  for (const AdsGridPoint& g : q.grid) {
    points.push_back({{"value", g.value},
                      {"temp_c", g.temp_c},
                      {"tolerance", g.tolerance},
                      {"error_no_history", g.error_no_history},
                      {"worst_with_history", g.worst_with_history},
                      {"loop_half_width", g.loop_half_width},
                      {"verdict", ToString(g.verdict)}});
  }
  return points;
}

nlohmann::json QuantityReport(const nlohmann::json& summary,
                              const AdsQuantityEvaluation& q,
                              const std::string& verdict) {
  nlohmann::json out = summary;
  out["verdict"] = verdict;
  out["points"] = GridPointsJson(q);
  return out;
}

}  // namespace

std::string AdsVerdictText(const AdsQuantityEvaluation& q) {
  if (q.fail == 0 && q.unreachable == 0) return "within specification";
  return fmt::format("{} of {} grid points fail, {} unreachable by any static calibration",
                     q.fail,
                     q.grid.size(),
                     q.unreachable);
}

AdsFileEvaluation EvaluateAds(const calib::ConstantsFile& constants,
                              const sensor_sim::AdsUnitParams& truth,
                              const AdsEvaluationOptions& options) {
  if (constants.kind != hil::UnitKind::kAds || !constants.ads) {
    throw std::invalid_argument("evaluate: constants of " + constants.serial + " are not an ADS's");
  }
  AdsFileEvaluation e;
  try {
    e.evaluation = EvaluateAdsConstants(*constants.ads, truth, options);
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument("evaluate: constants of " + constants.serial +
                                " cannot be exported to the firmware: " + error.what());
  }
  e.altitude_verdict = AdsVerdictText(e.evaluation.altitude);
  e.airspeed_verdict = AdsVerdictText(e.evaluation.airspeed);
  const nlohmann::json summary = e.evaluation.ToJson();
  e.report = {
      {"format", "adahrs-ads-evaluation"},
      {"format_version", 1},
      {"serial", constants.serial},
      {"strategy", constants.strategy},
      {"specification", calib::Specification::Reference().ToJson()},
      {"grid",
       {{"temp_c", {calib::kAdsMinTempC, calib::kAdsMaxTempC, options.temp_step_c}},
        {"altitude_ft", {calib::kAdsMinAltitudeFt, calib::kAdsMaxAltitudeFt, options.alt_step_ft}},
        {"airspeed_kt", {calib::kAdsMinAirspeedKt, calib::kAdsMaxAirspeedKt, options.cas_step_kt}},
        {"histories",
         "pressure none, rising, falling x temperature none, heating, cooling (major loops)"},
        {"switched_off", "bridge and converter noise, thermal lag (the die soaked)"}}},
      {"altitude_ft",
       QuantityReport(summary["altitude_ft"], e.evaluation.altitude, e.altitude_verdict)},
      {"airspeed_kt",
       QuantityReport(summary["airspeed_kt"], e.evaluation.airspeed, e.airspeed_verdict)}};
  return e;
}

}  // namespace adahrs::proving
