// Prints an XHTML page to PDF with Debian's headless Chromium (/usr/bin/chromium, installed by
// scripts/setup): `--headless --print-to-pdf`, a fresh profile directory, no network use, bounded
// by a timeout. Used for the certificates; the HTML stays the record, the PDF is its print.
// Errors: PdfRenderError naming the page and why (no Chromium, a non-zero exit, a timeout, no
// PDF written).
#pragma once

#include <filesystem>
#include <stdexcept>

namespace adahrs::calib {

class PdfRenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The Chromium the renderer runs.
inline constexpr const char* kChromiumPath = "/usr/bin/chromium";

/// Writes `pdf` from `html` (an absolute or relative path to a local file).
void RenderPdf(const std::filesystem::path& html,
               const std::filesystem::path& pdf,
               double timeout_s = 120.0);

}  // namespace adahrs::calib
