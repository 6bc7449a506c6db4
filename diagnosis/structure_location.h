// Where an IMU channel's final residual has structure no candidate term explains (docs/diagnose.md
// "Method (IMU)", items 5 and 6): segments whose mean lies far outside the others' (10 robust
// spreads and 6 white-noise standard errors), abrupt steps inside long segments (a 30-cell contrast
// beyond the quantile of a stated false-alarm rate in its own spread over the segment), and
// periodic lines in the rows' spectra (row_spectrum.h, both bands) above half the output step.
// Located, never fitted. Residuals are in raw channel units (duty, counts); `phys` scales them to
// `unit` (mg, dps) for the report.
// Left out: structure on the ADS channels (ads_diagnosis.h has its own).
#pragma once

#include <string>
#include <vector>

#include "diagnosis/diagnosis_cells.h"
#include "diagnosis/diagnosis_result.h"

namespace adahrs::diagnosis {

/// Outlying segments and steps of channel `ch`'s residual (one value per cell of `data`); in
/// `notes` the smallest step each segment would show with 90 % probability (least and most).
void LocateStructure(const DiagnosisData& data,
                     int ch,
                     const std::vector<double>& residual,
                     double phys,
                     const std::string& unit,
                     std::vector<Unexplained>* out,
                     std::vector<std::string>* notes);

/// Periodic lines of channel `ch` at family level `alpha`; lines below half the output step are
/// capture quantisation of a slowly moving input and go to `notes` instead.
void LocatePeriodic(const DiagnosisData& data,
                    int ch,
                    double alpha,
                    double phys,
                    const std::string& unit,
                    std::vector<Unexplained>* out,
                    std::vector<std::string>* notes);

}  // namespace adahrs::diagnosis
