#include "calib/report/constants_table.h"

#include <fmt/format.h>

#include "calib/constants/provenance_check.h"
#include "calib/report/constant_names.h"
#include "calib/report/svg_plot.h"

namespace adahrs::calib {

HtmlTable ConstantsTable(const ConstantsFile& file) {
  const nlohmann::json document = ToJson(file);
  const nlohmann::json values = document.at("constants").flatten();
  const nlohmann::json errors = document.at("standard_errors").flatten();
  HtmlTable table{fmt::format("{} constants ({} strategy), units of calibration_constants.h",
                              file.serial,
                              file.strategy),
                  {"constant", "JSON path", "value", "standard error (1 sigma)"},
                  {}};
  for (const auto& [path, value] : values.items()) {
    if (!value.is_number()) continue;
    const auto error = errors.find(path);
    const std::string se = error == errors.end() || error->is_null()
                               ? "not estimated"
                               : FormatNumber(error->get<double>(), 3);
    const std::string name = file.kind == hil::UnitKind::kImu ? ImuConstantName(path) : path;
    table.rows.push_back({name, path, FormatNumber(value.get<double>(), 10), se});
  }
  return table;
}

std::string ConstantsSection(const ConstantsFile& file) {
  std::string html = fmt::format("<p>strategy {}, created {}, software {}</p>\n<ul>\n",
                                 XmlEscape(file.strategy),
                                 XmlEscape(file.created_utc),
                                 XmlEscape(file.software_version));
  for (const RecordingCheck& c : CheckRecordings(file.provenance)) {
    html += fmt::format(
        "<li{}>recording {}</li>\n", c.changed() ? " class=\"fail\"" : "", XmlEscape(c.Describe()));
  }
  html += "</ul>\n";
  return html + RenderTable(ConstantsTable(file));
}

}  // namespace adahrs::calib
