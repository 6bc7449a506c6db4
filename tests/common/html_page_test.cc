// HtmlPage and XmlEscape: the page read back by an independent XML parser (python3 xml.etree,
// tests/support/xml_tree.py), which must find the title exactly as given, however hostile.
#include "common/html_page.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/xml_tree.h"

namespace adahrs::common {
namespace {

using calib::testing::FindTag;
using calib::testing::ParseXmlTree;

nlohmann::json PageTree(const std::string& title, const std::string& body) {
  const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                     ("adahrs_html_page_" + std::to_string(::getpid()) + ".html");
  std::ofstream(file) << HtmlPage(title, body);
  nlohmann::json tree = ParseXmlTree(file);
  std::filesystem::remove(file);
  return tree;
}

TEST(XmlEscape, EscapesTheFiveMarkupCharacters) {
  EXPECT_EQ(XmlEscape("a<b>&\"c\"'d'"), "a&lt;b&gt;&amp;&quot;c&quot;&apos;d&apos;");
  EXPECT_EQ(XmlEscape("25 \xC2\xB0"
                      "C, plain"),
            "25 \xC2\xB0"
            "C, plain");
  EXPECT_EQ(XmlEscape(""), "");
}

TEST(HtmlPage, TitleArrivesAsWrittenWhateverItHolds) {
  const std::string title = "Run <b>x</b> & \"y\" 'z' </title><script>alert(1)</script> \xC2\xB0";
  const nlohmann::json tree = PageTree(title, "<p>body</p>\n");
  ASSERT_FALSE(tree.is_null());
  const auto titles = FindTag(tree, "title");
  ASSERT_EQ(titles.size(), 1u);
  EXPECT_EQ(titles[0]["text"], title);
  EXPECT_TRUE(titles[0]["children"].empty());  // no element smuggled in
  EXPECT_TRUE(FindTag(tree, "script").empty());
  EXPECT_TRUE(FindTag(tree, "b").empty());
}

TEST(HtmlPage, IsACompleteXhtmlPageWithTheBodyAsGiven) {
  const std::string page = HtmlPage("t", "<h1>Heading</h1>\n<p class=\"note\">n</p>\n");
  EXPECT_EQ(page.rfind("<!DOCTYPE html>\n", 0), 0u);
  const nlohmann::json tree = PageTree("t", "<h1>Heading</h1>\n<p class=\"note\">n</p>\n");
  ASSERT_FALSE(tree.is_null());
  EXPECT_EQ(tree["tag"], "html");
  EXPECT_EQ(tree["attrib"]["lang"], "en");
  ASSERT_EQ(tree["children"].size(), 2u);
  const nlohmann::json& head = tree["children"][0];
  const nlohmann::json& body = tree["children"][1];
  EXPECT_EQ(head["tag"], "head");
  EXPECT_EQ(body["tag"], "body");
  ASSERT_EQ(FindTag(head, "meta").size(), 1u);
  EXPECT_EQ(FindTag(head, "meta")[0]["attrib"]["charset"], "utf-8");
  ASSERT_EQ(FindTag(head, "style").size(), 1u);
  // The classes the pages' builders give (calib/report/html_builder.h, the diagnosis's notes).
  const std::string style = FindTag(head, "style")[0]["text"];
  for (const char* rule : {".pass{", ".fail{", ".unavailable{", ".note{", "caption{"}) {
    EXPECT_NE(style.find(rule), std::string::npos) << rule;
  }
  ASSERT_EQ(body["children"].size(), 2u);
  EXPECT_EQ(body["children"][0]["tag"], "h1");
  EXPECT_EQ(body["children"][0]["text"], "Heading");
  EXPECT_EQ(body["children"][1]["attrib"]["class"], "note");
}

}  // namespace
}  // namespace adahrs::common
