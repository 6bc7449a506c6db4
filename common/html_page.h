// The project's HTML pages (run report, study report, diagnosis, re-simulation check) as one
// shell: XHTML-compatible (every element closed, attributes quoted) so an XML parser reads a whole
// page, UTF-8, one inline style sheet for all of them, no scripts.
#pragma once

#include <string>

namespace adahrs::common {

/// Escapes &, <, >, " and ' for XML text and attributes.
std::string XmlEscape(const std::string& text);

/// A complete page: `title` (escaped here) in <title>, the shared style sheet, and `body_html`
/// (markup, its text already escaped by whoever built it) as the <body>'s content.
std::string HtmlPage(const std::string& title, const std::string& body_html);

}  // namespace adahrs::common
