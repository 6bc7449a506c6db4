#include "calib/imu_calibration/external_strategy.h"

#include "calib/imu_calibration/imu_run_data.h"
#include "common/child_program.h"
#include "common/printable_text.h"
#include "common/sha256.h"

namespace adahrs::calib {
namespace {

constexpr size_t kStderrInMessage = 2000;
constexpr const char* kBuiltInNames[] = {"reference", "joint"};

ExternalRequestInputs ReadInputs(const common::ParamReader& r) {
  ExternalRequestInputs inputs;
  if (!r.Has("inputs")) return inputs;
  const common::ParamReader in = r.Child("inputs");
  if (in.Has("acquisition_samples")) inputs.acquisition_samples = in.Flag("acquisition_samples");
  if (in.Has("thermal_band_width_cnt")) {
    inputs.thermal_band_width_cnt = in.Number("thermal_band_width_cnt", 10.0, 2000.0, "counts");
  }
  in.ExpectAllKeysUsed();
  return inputs;
}

std::string Joined(const std::vector<std::string>& argv) {
  std::string s;
  for (const std::string& a : argv) s += (s.empty() ? "" : " ") + a;
  return s;
}

// The end of the program's stderr, for a refusal.
std::string StderrTail(const std::string& tail) {
  if (tail.empty()) return "; its stderr was empty";
  const size_t from = tail.size() > kStderrInMessage ? tail.size() - kStderrInMessage : 0;
  return "; the end of its stderr:\n" + common::PrintableMessage(tail.substr(from));
}

}  // namespace

ExternalImuProgram ReadExternalProgram(const common::ParamReader& r,
                                       const nlohmann::json& j,
                                       const std::filesystem::path& path) {
  ExternalImuProgram p;
  p.strategy_file = std::filesystem::absolute(path).lexically_normal().string();
  p.name = r.String("strategy");
  for (const char* built_in : kBuiltInNames) {
    if (p.name == built_in) {
      r.Fail("$.strategy",
             "\"" + p.name +
                 "\" is a built-in strategy's name; name the program's "
                 "strategy otherwise");
    }
  }
  if (p.name.empty()) r.Fail("$.strategy", "expected a name");
  const size_t n = r.ArrayLength("program", 1, 64);
  for (size_t i = 0; i < n; ++i) {
    const nlohmann::json& arg = j.at("program").at(i);
    if (!arg.is_string() || arg.get<std::string>().empty()) {
      r.Fail("$.program[" + std::to_string(i) + "]", "expected a non-empty string");
    }
    p.argv.push_back(arg.get<std::string>());
  }
  if (r.Has("timeout_s")) p.timeout_s = r.Number("timeout_s", 1.0, 86400.0, "s");
  if (r.Has("firmware_format")) {
    p.firmware_format = static_cast<int>(r.Integer("firmware_format", 2, 3));
  }
  p.inputs = ReadInputs(r);
  if (r.Has("options")) {
    r.Child("options");  // any object, the program's
    p.options = j.at("options");
  }
  p.working_directory = std::filesystem::absolute(path).parent_path();
  p.strategy_sha256 = common::FileSha256(path);
  return p;
}

ExternalRun RunExternalProgram(const ExternalImuProgram& program,
                               const std::string& request,
                               const std::string& serial,
                               const std::string& who) {
  const common::ChildProgramResult run = common::RunChildProgram(
      {program.argv, program.working_directory, request, program.timeout_s});
  if (!run.Succeeded()) {
    throw ExternalStrategyError(who + ": " + run.Outcome(program.timeout_s) +
                                StderrTail(run.stderr_tail));
  }
  if (!run.stdin_fully_read) {
    throw ExternalStrategyError(who + ": exited without reading its whole request from stdin" +
                                StderrTail(run.stderr_tail));
  }
  try {
    return {CheckExternalReply(run.stdout_bytes, serial, program.firmware_format),
            run.stdout_bytes,
            run.elapsed_s};
  } catch (const std::runtime_error& e) {
    throw ExternalStrategyError(who + ": reply refused: " + e.what() + StderrTail(run.stderr_tail));
  }
}

ConstantsFile FitImuExternal(const ImuUnitData& unit,
                             const ImuRunData& data,
                             const ExternalImuProgram& program,
                             const std::string& software_version,
                             ExternalExchange* exchange) {
  const std::string who = "strategy \"" + program.name + "\" (" + Joined(program.argv) + ", " +
                          program.strategy_file + ") for " + unit.serial;
  const ExternalRequestHeader header{
      program.name, program.options, program.firmware_format, program.inputs};
  exchange->request = ExternalImuRequest(unit, data, header).dump() + "\n";
  const ExternalRun run = RunExternalProgram(program, exchange->request, unit.serial, who);
  exchange->reply = run.reply_bytes;
  exchange->elapsed_s = run.elapsed_s;
  const CheckedReply& reply = run.reply;
  exchange->log = reply.log;
  ConstantsFile f;
  f.serial = unit.serial;
  f.kind = hil::UnitKind::kImu;
  f.strategy = program.name;
  f.created_utc = UtcNowIso8601();
  f.software_version = software_version;
  f.imu = reply.constants;
  f.standard_errors = reply.standard_errors;
  f.provenance.recordings = data.recordings;
  f.provenance.sequence_names = data.sequence_names;
  f.provenance.external = ExternalFitRecord{program.argv,
                                            program.strategy_file,
                                            program.strategy_sha256,
                                            common::Sha256Hex(exchange->request),
                                            common::Sha256Hex(exchange->reply)};
  ImuFitDiagnostics diagnostics;
  diagnostics.local_gravity_mps2 = data.local_gravity_mps2;
  diagnostics.excluded_rows = static_cast<int64_t>(unit.exclusions.size());
  diagnostics.rejected_interval_rows = unit.rejected_interval_rows;
  f.imu_diagnostics = diagnostics;
  return f;
}

}  // namespace adahrs::calib
