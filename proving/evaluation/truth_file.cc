#include "proving/evaluation/truth_file.h"

#include <fmt/format.h>

#include "common/param_reader.h"

namespace adahrs::proving {
namespace {

using common::ParamError;
using common::ParamReader;

void RequireKind(const TruthFile& t, const char* kind) {
  if (t.kind != kind) {
    throw ParamError(fmt::format("{}: $.kind: '{}', not an {} truth file", t.path, t.kind, kind));
  }
}

template <typename Params>
Params Read(const TruthFile& t, const char* kind, const std::string& serial) {
  RequireKind(t, kind);
  Params p = Params::FromJson(ParamReader(t.file["params"], t.path, "$.params"));
  if (!serial.empty() && p.serial != serial) {
    throw ParamError(fmt::format(
        "{}: $.params.serial: '{}' is not the unit judged, '{}'", t.path, p.serial, serial));
  }
  return p;
}

}  // namespace

TruthFile ReadTruthFile(const std::filesystem::path& path) {
  TruthFile t{path.string(), "", ParamReader::LoadFile(path.string())};
  if (!t.file.is_object() || !t.file.contains("params") || !t.file["params"].is_object()) {
    throw ParamError(t.path + ": $.params: missing (not a truth file: {kind, params})");
  }
  t.kind = ParamReader(t.file, t.path).String("kind");
  return t;
}

sensor_sim::ImuUnitParams ImuTruth(const TruthFile& truth, const std::string& serial) {
  return Read<sensor_sim::ImuUnitParams>(truth, "imu", serial);
}

sensor_sim::AdsUnitParams AdsTruth(const TruthFile& truth, const std::string& serial) {
  return Read<sensor_sim::AdsUnitParams>(truth, "ads", serial);
}

}  // namespace adahrs::proving
