// A calibration certificate per unit (docs/report.md "Certificate"): the one page a production
// line hands out with a unit. Built from the unit's acceptance.json (its outcome, points and
// worst margins, the specification's identity), the acceptance run's meta.json (station,
// instruments, the unit's firmware and mode) and, when known, the constants file the unit was
// given (its SHA-256, strategy and firmware constants format); plus the date issued, the operator
// and the software. Written as self-contained XHTML; pdf_render.h prints it to PDF.
// Left out: signatures and a certificate number sequence (the records database has no users).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "calib/acceptance/acceptance_file.h"
#include "calib/constants/constants_file.h"
#include "hil/recording/recording_meta.h"

namespace adahrs::calib {

struct CertificateInputs {
  AcceptanceFile acceptance;
  hil::RecordingMeta run;  ///< the acceptance run's meta.json
  std::optional<ConstantsFile> constants;
  std::string constants_sha256;  ///< of the constants file's bytes ("" when not known)
  std::string operator_name;     ///< "" when not given
  std::string issued_utc;
  std::string software_version;
};

/// Reads the unit's acceptance.json, its run's meta.json (the directory the file names) and, if
/// `constants_file` is not empty, the constants file; throws with the reader's message.
CertificateInputs ReadCertificateInputs(const std::filesystem::path& acceptance_file,
                                        const std::filesystem::path& constants_file,
                                        const std::string& operator_name,
                                        const std::string& software_version);

/// The constants file of `serial` in a fit directory: <dir>/<serial>.json, else the *.json whose
/// "format" is adahrs-constants and whose serial it is; empty if none.
std::filesystem::path FindConstantsOf(const std::filesystem::path& fit_dir,
                                      const std::string& serial);

/// The certificate page.
std::string CertificateHtml(const CertificateInputs& in);

struct WrittenCertificate {
  std::filesystem::path html;
  std::optional<std::filesystem::path> pdf;
  std::string pdf_error;  ///< why there is no PDF (pdf_render.h), "" when there is one
};

/// Writes `<dir>/<serial>.html` and prints it to `<dir>/<serial>.pdf`; a PDF that cannot be
/// printed is reported in the result, not thrown (the HTML is the record).
WrittenCertificate WriteCertificate(const CertificateInputs& in, const std::filesystem::path& dir);

}  // namespace adahrs::calib
