#include "calib/records/records_sources.h"

#include <array>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>
#include <openssl/evp.h>

#include "calib/constants/constants_file.h"
#include "calib/constants/provenance_check.h"
#include "calib/constants/recording_checksum.h"
#include "calib/sequence/sequence_json.h"
#include "common/param_reader.h"
#include "hil/recording/recording_format.h"
#include "hil/recording/recording_reader.h"

namespace adahrs::calib {
namespace {

constexpr int kOldestMetaFormatVersion = 2;  // the first with run id, status and units

// Reads every row as a fit would: the reader refuses a bad cell by file, line and column, a row of
// a unit meta.json does not list, a unit's time going back and a repeated row, and a torn last
// line unless the run did not complete. A certified record must not stand on rows the pipeline
// would not trust.
void CheckRecordingRows(const std::filesystem::path& run_dir, bool complete) {
  hil::ReadOptions options;
  options.allow_truncated_tail = !complete;
  hil::StreamRecording(run_dir, {}, options);
}

}  // namespace

std::string FileSha256(const std::filesystem::path& file) {
  const std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(),
                                                                    &EVP_MD_CTX_free);
  if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1) {
    throw std::runtime_error(file.string() + ": OpenSSL SHA-256 initialisation failed");
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file.string() + ": cannot open for its checksum");
  std::array<char, 1 << 16> buffer;
  while (in) {
    in.read(buffer.data(), buffer.size());
    if (in.gcount() > 0 &&
        EVP_DigestUpdate(ctx.get(), buffer.data(), static_cast<size_t>(in.gcount())) != 1) {
      throw std::runtime_error(file.string() + ": SHA-256 update failed");
    }
  }
  if (in.bad()) throw std::runtime_error(file.string() + ": read error");
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int length = 0;
  if (EVP_DigestFinal_ex(ctx.get(), digest.data(), &length) != 1) {
    throw std::runtime_error(file.string() + ": SHA-256 finalisation failed");
  }
  std::string hex;
  for (unsigned int i = 0; i < length; ++i) hex += fmt::format("{:02x}", digest[i]);
  return hex;
}

RunRecord RunRecordFromDirectory(const std::filesystem::path& run_dir) {
  const std::filesystem::path meta_path = run_dir / hil::kMetaJsonName;
  const nlohmann::json meta_json = common::ParamReader::LoadFile(meta_path.string());
  const common::ParamReader meta(meta_json, meta_path.string());
  const int64_t version = meta.Integer("format_version", 1, 1000);
  if (version < kOldestMetaFormatVersion || version > hil::kRecordingFormatVersion) {
    meta.Fail("$.format_version",
              fmt::format("recording format {} cannot be recorded; the "
                          "records need format {} to {} (run id, status, units)",
                          version,
                          kOldestMetaFormatVersion,
                          hil::kRecordingFormatVersion));
  }
  RunRecord run;
  run.run_dir = std::filesystem::absolute(run_dir).lexically_normal().string();
  run.run_id = meta.String("run_id");
  run.started_utc = meta.String("started_utc");
  run.status = meta.String("status");
  if (run.status != "running" && run.status != "complete" && run.status != "aborted" &&
      run.status != "interrupted") {
    meta.Fail("$.status", "'" + run.status + "' is not running, complete, aborted or interrupted");
  }
  run.station_name = meta.Child("station").String("name");
  run.sequence_file = meta.String("sequence_file");
  const Sequence sequence =
      SequenceFromJson(meta_json.at("sequence"), meta_path.string() + " $.sequence");
  run.sequence_name = sequence.name;
  const std::vector<uint8_t> tags = EffectiveTags(sequence);
  for (size_t i = 0; i < sequence.steps.size(); ++i) {
    run.steps.push_back({static_cast<int>(i), StepKindName(sequence.steps[i].body), tags[i], 0.0});
  }
  const size_t rejected = meta.ArrayLength("rejected_intervals", 0, 1000000);
  for (size_t i = 0; i < rejected; ++i) {
    const common::ParamReader interval = meta.Element("rejected_intervals", i, rejected);
    const int64_t step = interval.Integer("step", 0, static_cast<int64_t>(run.steps.size()) - 1);
    const double t_start_s = interval.Number("t_start_s", 0.0, 1e9, "s");
    const double t_end_s = interval.Number("t_end_s", t_start_s, 1e9, "s");
    run.steps[static_cast<size_t>(step)].rejected_s += t_end_s - t_start_s;
  }
  const size_t units = meta.ArrayLength("units", 0, 64);
  for (size_t i = 0; i < units; ++i) {
    const common::ParamReader unit = meta.Element("units", i, units);
    RunUnitRecord record;
    record.role = unit.String("role");
    record.kind = unit.String("kind");
    if (record.kind != "imu" && record.kind != "ads") {
      unit.Fail(unit.path() + ".kind", "'" + record.kind + "' is neither imu nor ads");
    }
    record.serial = unit.String("serial");
    record.slot = static_cast<int>(unit.Integer("slot", 0, 64));
    record.firmware = unit.String("firmware");
    record.constants_version = unit.Integer("constants_version", 0, 65535);
    record.mode = static_cast<int>(unit.Integer("mode", 0, 255));
    run.units.push_back(record);
  }
  run.meta_json = meta_json.dump();
  CheckRecordingRows(run_dir, run.status == "complete");
  run.recording_sha256 = RecordingSha256(run_dir);
  return run;
}

ConstantsRecord ConstantsRecordFromFile(const std::filesystem::path& constants_json) {
  const ConstantsFile file = ReadConstantsFile(constants_json);
  RequireUnchangedRecordings(file, constants_json.string());  // never record what no longer stands
  ConstantsRecord record;
  record.serial = file.serial;
  record.kind = file.kind == hil::UnitKind::kImu ? "imu" : "ads";
  record.strategy = file.strategy;
  record.created_utc = file.created_utc;
  record.software_version = file.software_version;
  record.file_sha256 = FileSha256(constants_json);
  std::ifstream in(constants_json, std::ios::binary);
  record.json.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  record.provenance_json = ToJson(file).at("provenance").dump();
  return record;
}

}  // namespace adahrs::calib
