// Minimal builders for report.html: escaped text, headed tables and "not available (why)"
// notes. Output is XHTML-compatible (every element closed, attributes quoted), so an XML parser
// reads the whole report, which is how the tests check its structure.
// Left out: styling beyond one inline style sheet (run_report.cc), scripts (the report has none).
#pragma once

#include <string>
#include <vector>

namespace adahrs::calib {

/// A table: a caption naming what and in which units, column headers, rows of cell texts.
/// A cell "PASS", "FAIL" or "MARGINAL" gets class pass / fail / marginal.
struct HtmlTable {
  std::string caption;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

std::string RenderTable(const HtmlTable& table);

/// <p class="unavailable">NAME not available (WHY)</p>: never fake content for a missing input.
std::string NotAvailable(const std::string& what, const std::string& why);

/// <section id=ID><hN>TITLE</hN>BODY</section>.
std::string Section(const std::string& id,
                    int level,
                    const std::string& title,
                    const std::string& body);

/// A number to `significant` digits ("1.23e-05", "25.08"); NaN as "n/a".
std::string FormatNumber(double value, int significant = 6);

}  // namespace adahrs::calib
