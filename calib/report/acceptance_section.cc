#include "calib/report/acceptance_section.h"

#include <cmath>

#include <fmt/format.h>

#include "calib/report/html_builder.h"

namespace adahrs::calib {

std::string AcceptanceSectionBody(const std::vector<nlohmann::json>& documents) {
  std::string html;
  for (const nlohmann::json& d : documents) {
    const std::string serial = d["serial"].get<std::string>();
    HtmlTable summary{fmt::format("{}: acceptance verdict", serial), {"item", "value"}, {}};
    summary.rows.push_back({"run id", d["run"]["run_id"].get<std::string>()});
    summary.rows.push_back({"recording sha256", d["run"]["recording_sha256"].get<std::string>()});
    summary.rows.push_back({"mode", std::to_string(d.value("mode", 0))});
    summary.rows.push_back(
        {"points failed",
         fmt::format("{} of {}", d.value("points_failed", 0), d["points"].size())});
    summary.rows.push_back(
        {"verdict", d["verdict"].get<std::string>() == "pass" ? "PASS" : "FAIL"});
    if (d.contains("point_verdicts") && d["point_verdicts"].contains("body_rate")) {
      std::string counts;
      for (const auto& [verdict, n] : d["point_verdicts"]["body_rate"].items()) {
        counts += fmt::format("{}{}: {}", counts.empty() ? "" : "; ", verdict, n.get<int>());
      }
      summary.rows.push_back({"body-rate points", counts});
    }
    if (d.contains("physical_limit") && d["physical_limit"].is_object()) {
      const nlohmann::json& l = d["physical_limit"];
      summary.rows.push_back(
          {"physical limit",
           fmt::format("point noise and bias wander over {:g} h since calibration, from "
                       "a {:.0f} s rest record at {:.1f} degC",
                       l["since_calibration_h"].get<double>(),
                       l["rest_record"]["record_s"].get<double>(),
                       l["rest_record"]["chamber_c"].get<double>())});
    }
    html += RenderTable(summary);
    HtmlTable worst{fmt::format("{}: worst margin per quantity (tolerance - |error|)", serial),
                    {"quantity", "margin", "unit", "step", "point", "verdict"},
                    {}};
    for (const nlohmann::json& w : d.value("worst_margin", nlohmann::json::array())) {
      const double margin = w["margin"].get<double>();
      worst.rows.push_back({w["quantity"].get<std::string>(),
                            FormatNumber(margin, 4),
                            w["unit"].get<std::string>(),
                            std::to_string(w["step"].get<int>()),
                            w["point"].get<std::string>(),
                            margin >= 0.0 ? "PASS" : "FAIL"});
    }
    html += RenderTable(worst);
    HtmlTable points{fmt::format("{}: acceptance points (mean over the step's packets; noise 1 "
                                 "sigma; physical limit 3 sigma)",
                                 serial),
                     {"step",
                      "kind",
                      "quantity",
                      "condition",
                      "measured",
                      "reference",
                      "error",
                      "noise",
                      "tolerance",
                      "physical limit",
                      "margin",
                      "unit",
                      "verdict",
                      "against specification and physical limit"},
                     {}};
    for (const nlohmann::json& p : d["points"]) {
      const double error = p["error"].get<double>();
      const double tolerance = p["tolerance"].get<double>();
      points.rows.push_back(
          {std::to_string(p["step"].get<int>()),
           p["kind"].get<std::string>(),
           p["quantity"].get<std::string>(),
           p["condition"].get<std::string>(),
           FormatNumber(p["measured"].get<double>(), 8),
           FormatNumber(p["reference"].get<double>(), 8),
           FormatNumber(error, 4),
           FormatNumber(p.value("noise", p["std_error"].get<double>()), 3),
           FormatNumber(tolerance, 4),
           p.contains("physical_limit") ? FormatNumber(p["physical_limit"].get<double>(), 4) : "",
           FormatNumber(tolerance - std::abs(error), 4),
           p["unit"].get<std::string>(),
           p["pass"].get<bool>() ? "PASS" : "FAIL",
           p.value("verdict",
                   std::string(p["pass"].get<bool>() ? "within specification"
                                                     : "outside specification"))});
    }
    html += RenderTable(points);
  }
  return html;
}

}  // namespace adahrs::calib
