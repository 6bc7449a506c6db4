// report.html for one run (docs/report.md): a self-contained XHTML page (inline CSS and SVG, no
// scripts, no external references) from the run directory (recording format 2) and, if given, the
// fit directory holding each unit's constants.json (any *.json whose "format" is
// "adahrs-constants"), acceptance.json and evaluation.json. Sections: run summary (sequence,
// station, units, rejected intervals), then per unit its constants with standard errors and the
// IMU (imu_report_sections.h) or ADS (ads_report_sections.h) figures, then the acceptance and
// evaluation tables. A missing input makes its section say "not available (why)".
// Acceptance: the <serial>/acceptance.json files (calib/acceptance/acceptance_file.h) of the
// acceptance directory given, else of <run>/acceptance when it exists (where `adahrs acceptance`
// writes by default), rendered as verdict, worst-margin and per-point PASS/FAIL tables
// (acceptance_section.h); without any, a fit directory's acceptance.json as generic tables.
// Errors: unreadable or malformed inputs throw with their own readers' messages (file, line,
// column, JSON path); the report is written atomically (temporary file + rename).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "calib/acceptance/specification.h"

namespace adahrs::calib {

/// The report's HTML. `specification` sets the tolerances the ADS error figures and maps are
/// drawn against (Specification::Reference() when none is given); the acceptance tables show each
/// file's own judgement.
std::string BuildRunReport(
    const std::filesystem::path& run_dir,
    const std::optional<std::filesystem::path>& fit_dir,
    const std::optional<std::filesystem::path>& acceptance_dir = std::nullopt,
    const std::optional<Specification>& specification = std::nullopt);

/// BuildRunReport written to `out`.
void WriteRunReport(const std::filesystem::path& run_dir,
                    const std::optional<std::filesystem::path>& fit_dir,
                    const std::filesystem::path& out,
                    const std::optional<std::filesystem::path>& acceptance_dir = std::nullopt,
                    const std::optional<Specification>& specification = std::nullopt);

}  // namespace adahrs::calib
