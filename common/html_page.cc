#include "common/html_page.h"

namespace adahrs::common {
namespace {

// Tables with captions, PASS/FAIL cells (class pass / fail), notes and "not available" lines.
constexpr const char* kStyle =
    "body{font-family:sans-serif;max-width:70em;margin:1em auto}"
    "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #bbb;padding:2px 6px;"
    "font-size:90%}caption{text-align:left;font-weight:bold}.pass{background:#d8f0d8}"
    ".fail{background:#f6d0d0}.marginal{background:#f6ecc8}.unavailable{color:#a33;font-style:"
    "italic}.note{color:#555}";

}  // namespace

std::string XmlEscape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string HtmlPage(const std::string& title, const std::string& body_html) {
  return "<!DOCTYPE html>\n<html xmlns=\"http://www.w3.org/1999/xhtml\" lang=\"en\">\n<head>\n"
         "<meta charset=\"utf-8\"/>\n<title>" +
         XmlEscape(title) + "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n" +
         body_html + "</body>\n</html>\n";
}

}  // namespace adahrs::common
