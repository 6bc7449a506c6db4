// Test helper: parses an XML/XHTML file with Python's xml.etree (xml_tree.py, an independent
// parser) and returns its element tree as JSON, plus small search helpers.
#pragma once

#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>
#include "adahrs_build_paths.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace adahrs::calib::testing {

/// The element tree of `file`; fails the test (and returns null) if it is not well-formed.
inline nlohmann::json ParseXmlTree(const std::filesystem::path& file) {
  const std::string command = std::string(ADAHRS_PYTHON) + " " + ADAHRS_SOURCE_DIR +
                              "/tests/support/xml_tree.py " + file.string();
  FILE* pipe = ::popen(command.c_str(), "r");
  std::string out;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) out += buffer;
  const int status = ::pclose(pipe);
  EXPECT_EQ(status, 0) << file << " is not well-formed XML";
  if (status != 0) return nullptr;
  return nlohmann::json::parse(out);
}

/// Every element below (and including) `tree` for which `match` holds, in document order.
inline std::vector<nlohmann::json> FindAll(
    const nlohmann::json& tree, const std::function<bool(const nlohmann::json&)>& match) {
  std::vector<nlohmann::json> found;
  std::function<void(const nlohmann::json&)> walk = [&](const nlohmann::json& node) {
    if (match(node)) found.push_back(node);
    for (const auto& child : node["children"]) walk(child);
  };
  walk(tree);
  return found;
}

/// Elements with tag `tag` and (if given) attribute class == `css_class`.
inline std::vector<nlohmann::json> FindTag(const nlohmann::json& tree,
                                           const std::string& tag,
                                           const std::string& css_class = "") {
  return FindAll(tree, [&](const nlohmann::json& n) {
    return n["tag"] == tag && (css_class.empty() || (n["attrib"].contains("class") &&
                                                     n["attrib"]["class"] == css_class));
  });
}

}  // namespace adahrs::calib::testing
