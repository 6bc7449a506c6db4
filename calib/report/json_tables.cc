#include "calib/report/json_tables.h"

#include <algorithm>

#include <fmt/format.h>

#include "calib/report/html_builder.h"

namespace adahrs::calib {
namespace {

bool IsVerdictKey(const std::string& key) {
  return key == "pass" || (key.size() > 5 && key.ends_with("_pass"));
}

std::string Cell(const std::string& key, const nlohmann::json& value) {
  if (value.is_boolean() && IsVerdictKey(key)) return value.get<bool>() ? "PASS" : "FAIL";
  if (value.is_number_float()) return FormatNumber(value.get<double>(), 6);
  if (value.is_string()) return value.get<std::string>();
  return value.dump();
}

void Walk(const std::string& title,
          const std::string& path,
          const nlohmann::json& node,
          std::string* html) {
  if (node.is_array() && !node.empty() &&
      std::all_of(
          node.begin(), node.end(), [](const nlohmann::json& e) { return e.is_object(); })) {
    HtmlTable table{fmt::format("{} {}", title, path), {}, {}};
    for (const auto& element : node) {
      for (const auto& [key, value] : element.items()) {
        if (std::find(table.header.begin(), table.header.end(), key) == table.header.end()) {
          table.header.push_back(key);
        }
      }
    }
    for (const auto& element : node) {
      std::vector<std::string> row;
      for (const std::string& key : table.header) {
        row.push_back(element.contains(key) ? Cell(key, element[key]) : "");
      }
      table.rows.push_back(row);
    }
    *html += RenderTable(table);
    return;
  }
  if (node.is_object()) {
    for (const auto& [key, value] : node.items()) Walk(title, path + "." + key, value, html);
  } else if (node.is_array()) {
    for (size_t i = 0; i < node.size(); ++i)
      Walk(title, fmt::format("{}[{}]", path, i), node[i], html);
  }
}

}  // namespace

std::string RenderJsonTables(const std::string& title, const nlohmann::json& document) {
  std::string html;
  if (document.is_object()) {
    HtmlTable scalars{title + " summary", {"key", "value"}, {}};
    for (const auto& [key, value] : document.items()) {
      if (value.is_primitive()) scalars.rows.push_back({key, Cell(key, value)});
    }
    if (!scalars.rows.empty()) html += RenderTable(scalars);
  }
  Walk(title, "$", document, &html);
  return html;
}

}  // namespace adahrs::calib
