#include "calib/records/records_sources.h"

#include <array>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>

#include "calib/constants/constants_file.h"
#include "calib/constants/provenance_check.h"
#include "calib/constants/recording_checksum.h"
#include "calib/records/sqlite_database.h"
#include "calib/sequence/sequence_json.h"
#include "common/param_reader.h"
#include "common/sha256.h"
#include "common/unit_kind.h"
#include "hil/recording/recording_format.h"
#include "hil/recording/recording_reader.h"

namespace adahrs::calib {
namespace {

constexpr int kOldestMetaFormatVersion = 2;  // the first with run id, status and units

// Reads every row as a fit would: the reader refuses a bad cell by file, line and column, a row of
// a unit meta.json does not list, a unit's time going back and a repeated row, and a torn last
// line unless the run did not complete. A certified record must not stand on rows the pipeline
// would not trust.
void CheckRecordingRows(const std::filesystem::path& run_dir,
                        bool complete,
                        bool accept_sample_time_defects) {
  hil::ReadOptions options;
  options.allow_truncated_tail = !complete;
  const hil::Recording rec = hil::StreamRecording(run_dir, {}, options);
  if (rec.sample_time_defects.empty() || accept_sample_time_defects) return;
  std::string what =
      "recording has sample time defects (docs/recording-format.md \"Sample time\"; "
      "--accept-sample-time-defects records it anyway):";
  for (const hil::SampleTimeDefect& d : rec.sample_time_defects) what += "\n  " + d.Describe();
  throw RecordsError(what);
}

}  // namespace

namespace {

// A field the records need, present in meta.json: `where` is its JSON path.
template <typename T>
const T& Required(const std::optional<T>& value,
                  const std::string& source,
                  const std::string& where) {
  if (!value) throw RecordsError(source + ": " + where + " missing (the records need it)");
  return *value;
}

RunUnitRecord UnitRecord(const hil::RecordingUnit& unit, const std::string& source, size_t i) {
  const std::string where = fmt::format("$.units[{}]", i);
  RunUnitRecord record;
  for (const auto& [value, key] :
       {std::pair{&unit.role, "role"}, std::pair{&unit.serial, "serial"}}) {
    if (value->empty()) throw RecordsError(source + ": " + where + "." + key + " missing");
  }
  record.role = unit.role;
  if (!unit.kind) throw RecordsError(source + ": " + where + ".kind missing");
  record.kind = common::UnitKindName(*unit.kind);
  record.serial = unit.serial;
  record.slot = static_cast<int>(Required(unit.slot, source, where + ".slot"));
  record.firmware = Required(unit.firmware, source, where + ".firmware");
  record.constants_version = Required(unit.constants_version, source, where + ".constants_version");
  record.mode = static_cast<int>(Required(unit.mode, source, where + ".mode"));
  return record;
}

}  // namespace

RunRecord RunRecordFromDirectory(const std::filesystem::path& run_dir,
                                 const RunRecordOptions& options) {
  const std::filesystem::path meta_path = run_dir / hil::kMetaJsonName;
  const std::string source = meta_path.string();
  // The file as written is kept in the records beside the fields read from it.
  const nlohmann::json meta_json = common::ParamReader::LoadFile(source);
  if (!meta_json.is_object() || !meta_json.contains("format_version") ||
      !meta_json.at("format_version").is_number_integer()) {
    throw RecordsError(source + ": $.format_version missing or not an integer");
  }
  const hil::RecordingMeta meta = hil::RecordingMeta::FromJson(meta_json, source);
  if (meta.format_version < kOldestMetaFormatVersion ||
      meta.format_version > hil::kRecordingFormatVersion) {
    throw RecordsError(
        fmt::format("{}: $.format_version: recording format {} cannot be recorded; "
                    "the records need format {} to {} (run id, status, units)",
                    source,
                    meta.format_version,
                    kOldestMetaFormatVersion,
                    hil::kRecordingFormatVersion));
  }
  RunRecord run;
  run.run_dir = std::filesystem::absolute(run_dir).lexically_normal().string();
  run.run_id = Required(meta.run_id, source, "$.run_id");
  run.started_utc = Required(meta.started_utc, source, "$.started_utc");
  run.status = Required(meta.status, source, "$.status");
  if (run.status != "running" && run.status != "complete" && run.status != "aborted" &&
      run.status != "interrupted") {
    throw RecordsError(source + ": $.status '" + run.status +
                       "' is not running, complete, aborted or interrupted");
  }
  const nlohmann::json& station = Required(meta.station, source, "$.station");
  run.station_name = common::ParamReader(station, source, "$.station").String("name");
  run.sequence_file = Required(meta.sequence_file, source, "$.sequence_file");
  const Sequence sequence =
      SequenceFromJson(Required(meta.sequence, source, "$.sequence"), source + " $.sequence");
  run.sequence_name = sequence.name;
  const std::vector<uint8_t> tags = EffectiveTags(sequence);
  for (size_t i = 0; i < sequence.steps.size(); ++i) {
    run.steps.push_back({static_cast<int>(i), StepKindName(sequence.steps[i].body), tags[i], 0.0});
  }
  for (size_t i = 0; i < meta.rejected_intervals.size(); ++i) {
    const hil::RejectedInterval& interval = meta.rejected_intervals[i];
    if (interval.step < 0 || static_cast<size_t>(interval.step) >= run.steps.size()) {
      throw RecordsError(
          fmt::format("{}: $.rejected_intervals[{}].step {} is not a step of the "
                      "sequence (0...{})",
                      source,
                      i,
                      interval.step,
                      run.steps.size() - 1));
    }
    run.steps[static_cast<size_t>(interval.step)].rejected_s +=
        interval.t_end_s - interval.t_start_s;
  }
  for (size_t i = 0; i < meta.units.size(); ++i) {
    run.units.push_back(UnitRecord(meta.units[i], source, i));
  }
  run.meta_json = meta_json.dump();
  CheckRecordingRows(run_dir, run.status == "complete", options.accept_sample_time_defects);
  run.recording_sha256 = RecordingSha256(run_dir);
  return run;
}

ConstantsRecord ConstantsRecordFromFile(const std::filesystem::path& constants_json) {
  const ConstantsFile file = ReadConstantsFile(constants_json);
  RequireUnchangedRecordings(file, constants_json.string());  // never record what no longer stands
  ConstantsRecord record;
  record.serial = file.serial;
  record.kind = common::UnitKindName(file.kind);
  record.strategy = file.strategy;
  record.created_utc = file.created_utc;
  record.software_version = file.software_version;
  record.file_sha256 = common::FileSha256(constants_json);
  std::ifstream in(constants_json, std::ios::binary);
  record.json.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  record.provenance_json = ToJson(file).at("provenance").dump();
  return record;
}

}  // namespace adahrs::calib
