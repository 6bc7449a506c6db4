#include "calib/report/certificate.h"

#include <fmt/format.h>

#include "calib/report/acceptance_section.h"
#include "calib/report/html_builder.h"
#include "calib/report/pdf_render.h"
#include "common/atomic_file.h"
#include "common/html_page.h"
#include "common/param_reader.h"
#include "common/sha256.h"
#include "hil/recording/recording_reader.h"
#include "hil/utc_time.h"

namespace adahrs::calib {
namespace {

std::string ConstantsFormat(const ConstantsFile& c) {
  if (c.imu) return c.imu->scale_temperature.active ? "IMU format 3" : "IMU format 2";
  return "ADS surfaces";
}

HtmlTable IdentityTable(const CertificateInputs& in) {
  const UnitAcceptance& u = in.acceptance.unit;
  const hil::RecordingUnit* unit = in.run.Unit(u.serial);
  HtmlTable t{"Unit, station and constants", {"item", "value"}, {}};
  t.rows.push_back({"serial", u.serial});
  t.rows.push_back({"unit kind", u.kind});
  t.rows.push_back({"firmware", unit && unit->firmware ? *unit->firmware : "not recorded"});
  t.rows.push_back({"mode judged", std::to_string(u.mode)});
  t.rows.push_back(
      {"station", in.run.station ? in.run.station->value("name", "not named") : "not recorded"});
  for (const hil::RecordingInstrument& i :
       in.run.instruments.value_or(std::vector<hil::RecordingInstrument>{})) {
    t.rows.push_back({"instrument " + i.role, i.model + (i.detail.empty() ? "" : ", " + i.detail)});
  }
  t.rows.push_back({"acceptance run",
                    in.acceptance.run.run_id + " (" + in.acceptance.run.sequence +
                        ", recording SHA-256 " + in.acceptance.run.recording_sha256 + ")"});
  if (in.constants) {
    t.rows.push_back({"constants",
                      fmt::format("{}, strategy {}, created {}",
                                  ConstantsFormat(*in.constants),
                                  in.constants->strategy,
                                  in.constants->created_utc)});
  }
  t.rows.push_back(
      {"constants SHA-256",
       in.constants_sha256.empty() ? "not known (no constants file given)" : in.constants_sha256});
  const AcceptanceFileSpecification& s = in.acceptance.specification_id;
  t.rows.push_back({"specification", s.name + " version " + s.version});
  t.rows.push_back({"specification SHA-256", s.sha256.empty() ? "not recorded" : s.sha256});
  return t;
}

}  // namespace

std::filesystem::path FindConstantsOf(const std::filesystem::path& fit_dir,
                                      const std::string& serial) {
  const std::filesystem::path named = fit_dir / (serial + ".json");
  if (std::filesystem::exists(named)) return named;
  for (const auto& entry : std::filesystem::directory_iterator(fit_dir)) {
    if (entry.path().extension() != ".json") continue;
    const nlohmann::json document = common::ParamReader::LoadFile(entry.path().string());
    if (document.is_object() && document.value("format", "") == kConstantsFormatName &&
        document.value("serial", "") == serial) {
      return entry.path();
    }
  }
  return {};
}

CertificateInputs ReadCertificateInputs(const std::filesystem::path& acceptance_file,
                                        const std::filesystem::path& constants_file,
                                        const std::string& operator_name,
                                        const std::string& software_version) {
  CertificateInputs in;
  in.acceptance = ReadAcceptanceFile(acceptance_file);
  in.run = hil::ReadRecordingMeta(in.acceptance.run.dir).meta;
  if (!constants_file.empty()) {
    in.constants = ReadConstantsFile(constants_file);
    in.constants_sha256 = common::FileSha256(constants_file);
    if (in.constants->serial != in.acceptance.unit.serial) {
      throw std::runtime_error(fmt::format("{}: constants of {}, but {} judges {}",
                                           constants_file.string(),
                                           in.constants->serial,
                                           acceptance_file.string(),
                                           in.acceptance.unit.serial));
    }
  }
  in.operator_name = operator_name;
  in.issued_utc = hil::UtcNowIso8601();
  in.software_version = software_version;
  return in;
}

std::string CertificateHtml(const CertificateInputs& in) {
  const UnitAcceptance& u = in.acceptance.unit;
  const std::string outcome = OutcomeText(u.outcome());
  const std::string title = "Calibration certificate " + u.serial;
  std::string body = fmt::format(
      "<h1>{}</h1>\n<p class=\"verdict {}\">Acceptance: {} ({} of {} points fail, {} "
      "marginal)</p>\n",
      common::XmlEscape(title),
      outcome == "FAIL"       ? "fail"
      : outcome == "MARGINAL" ? "marginal"
                              : "pass",
      outcome,
      u.failed(),
      u.points.size(),
      u.marginal());
  body += RenderTable(IdentityTable(in));
  body += RenderTable(WorstMarginTable(u));
  body += fmt::format(
      "<p>Issued {} by {}; adahrs {}. This certificate states the acceptance of the unit above as "
      "recorded against the specification named; the acceptance.json it comes from holds every "
      "point.</p>\n",
      common::XmlEscape(in.issued_utc),
      common::XmlEscape(in.operator_name.empty() ? std::string("operator not recorded")
                                                 : "operator " + in.operator_name),
      common::XmlEscape(in.software_version));
  return common::HtmlPage(title, body);
}

WrittenCertificate WriteCertificate(const CertificateInputs& in, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  WrittenCertificate written;
  written.html = dir / (in.acceptance.unit.serial + ".html");
  common::WriteFileAtomically(written.html, CertificateHtml(in));
  const std::filesystem::path pdf = dir / (in.acceptance.unit.serial + ".pdf");
  try {
    RenderPdf(written.html, pdf);
    written.pdf = pdf;
  } catch (const PdfRenderError& e) {
    written.pdf_error = e.what();
  }
  return written;
}

}  // namespace adahrs::calib
