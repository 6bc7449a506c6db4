// An IMU calibration strategy run as an external program (docs/strategies-external.md): the
// strategy file's "program" block, and the fit of one unit by that program: the request built
// (external_request.h), the program run with it on stdin (common/child_program.h), its reply
// checked (external_reply.h) into a constants file whose provenance records the exchange.
// Left out: staged fits (a program fits every stage at once), ADS strategies as programs.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calib/constants/constants_file.h"
#include "calib/imu_calibration/external_reply.h"
#include "calib/imu_calibration/external_request.h"
#include "common/param_reader.h"

namespace adahrs::calib {

struct ExternalImuProgram {
  std::string name;                         ///< the strategy file's "strategy"
  std::vector<std::string> argv;            ///< "program"
  std::filesystem::path working_directory;  ///< the strategy file's directory
  double timeout_s = 600.0;
  int firmware_format = 2;
  ExternalRequestInputs inputs;
  nlohmann::json options = nlohmann::json::object();
  std::string strategy_file;    ///< its absolute path
  std::string strategy_sha256;  ///< of its bytes
};

/// Reads the program block of a strategy file whose reader is `r` (the file `path`, parsed as
/// `j`); refuses a bad key with the file and JSON path (common::ParamError).
ExternalImuProgram ReadExternalProgram(const common::ParamReader& r,
                                       const nlohmann::json& j,
                                       const std::filesystem::path& path);

class ExternalStrategyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The bytes exchanged with the program for one unit, and its log lines.
struct ExternalExchange {
  std::string request;
  std::string reply;
  std::vector<std::string> log;
  double elapsed_s = 0.0;
};

/// A program's run on one request: its reply as checked and as written.
struct ExternalRun {
  CheckedReply reply;
  std::string reply_bytes;
  double elapsed_s = 0.0;
};

/// Runs the program with `request` on stdin and checks its reply for unit `serial`; throws
/// ExternalStrategyError led by `who` with the cause (start, timeout, exit status, an unread
/// request, the reply's refusal) and the tail of the program's stderr.
ExternalRun RunExternalProgram(const ExternalImuProgram& program,
                               const std::string& request,
                               const std::string& serial,
                               const std::string& who);

struct ImuUnitData;
struct ImuRunData;

/// Fits one unit of `data` with the program; fills `exchange`. Throws ExternalStrategyError
/// naming the program, the unit and the cause, with the tail of the program's stderr.
ConstantsFile FitImuExternal(const ImuUnitData& unit,
                             const ImuRunData& data,
                             const ExternalImuProgram& program,
                             const std::string& software_version,
                             ExternalExchange* exchange);

}  // namespace adahrs::calib
