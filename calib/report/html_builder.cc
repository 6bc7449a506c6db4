#include "calib/report/html_builder.h"

#include <cmath>

#include <fmt/format.h>

#include "calib/report/svg_plot.h"

namespace adahrs::calib {

std::string RenderTable(const HtmlTable& table) {
  std::string html = "<table>\n<caption>" + XmlEscape(table.caption) + "</caption>\n<tr>";
  for (const std::string& h : table.header) html += "<th>" + XmlEscape(h) + "</th>";
  html += "</tr>\n";
  for (const auto& row : table.rows) {
    html += "<tr>";
    for (const std::string& cell : row) {
      const char* css = cell == "PASS"       ? " class=\"pass\""
                        : cell == "FAIL"     ? " class=\"fail\""
                        : cell == "MARGINAL" ? " class=\"marginal\""
                                             : "";
      html += fmt::format("<td{}>{}</td>", css, XmlEscape(cell));
    }
    html += "</tr>\n";
  }
  return html + "</table>\n";
}

std::string NotAvailable(const std::string& what, const std::string& why) {
  return "<p class=\"unavailable\">" + XmlEscape(what) + " not available (" + XmlEscape(why) +
         ")</p>\n";
}

std::string Section(const std::string& id,
                    int level,
                    const std::string& title,
                    const std::string& body) {
  return fmt::format("<section id=\"{}\">\n<h{}>{}</h{}>\n{}</section>\n",
                     XmlEscape(id),
                     level,
                     XmlEscape(title),
                     level,
                     body);
}

std::string FormatNumber(double value, int significant) {
  if (!std::isfinite(value)) return "n/a";
  return fmt::format("{:.{}g}", value, significant);
}

}  // namespace adahrs::calib
