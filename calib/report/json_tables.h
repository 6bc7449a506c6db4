// Renders a result file (acceptance.json, evaluation.json) as report tables without assuming more
// of its layout than JSON itself: every array of objects found in the document (at any depth)
// becomes one table, its columns the union of the objects' scalar keys in first-seen order, its
// caption the array's JSON path; booleans under a key named "pass" (or ending in "_pass") show
// as PASS / FAIL; nested values show as compact JSON. Scalars at the top level are listed first.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace adahrs::calib {

/// The tables of `document`, captioned with `title` and each array's path.
std::string RenderJsonTables(const std::string& title, const nlohmann::json& document);

}  // namespace adahrs::calib
