// Shared helpers of the executor tests that run against the rig process
// (tests/support/rig_process.h): a fresh run directory, sequence files, a progress sink that keeps
// the notes, the rig's reported table rate, and the calibration rows of a recording grouped per
// unit and TAG.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "calib/executor/progress.h"
#include "hil/instruments/instruments.h"
#include "hil/recording/recording_reader.h"
#include "tests/support/rig_process.h"

namespace adahrs::calib::testing {

/// A fresh directory under the temporary directory, removed by the destructor.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("adahrs_exec_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// Writes a sequence document with `steps` for `unit_kind` ("imu"/"ads"); returns its path.
inline std::string WriteSequence(const std::filesystem::path& dir,
                                 const std::string& unit_kind,
                                 const nlohmann::json& steps) {
  const std::filesystem::path path = dir / "sequence.json";
  std::ofstream(path) << nlohmann::json{
      {"format_version", 1},
      {"name", "executor test"},
      {"description", "a short sequence for the executor tests"},
      {"unit_kind", unit_kind},
      {"steps", steps}}.dump(2);
  return path.string();
}

/// The station's operator plus a disturbance: after mounting orientation `code`, it sends
/// `command` on the rig's control port (every time) and keeps the reply in `reply`, which the
/// test owns (the operator dies with the run).
class DisturbingOperator : public hil::Operator {
 public:
  DisturbingOperator(std::unique_ptr<hil::Operator> inner,
                     const adahrs::testing::RigProcess& rig,
                     int code,
                     std::string command,
                     std::string& reply)
      : inner_(std::move(inner)),
        rig_(rig),
        code_(code),
        command_(std::move(command)),
        reply_(reply) {}
  void Mount(const std::vector<std::string>& roles, int code) override {
    inner_->Mount(roles, code);
    if (code == code_) reply_ = rig_.Control(command_);
  }
  void Prompt(const std::string& text) override { inner_->Prompt(text); }

  /// A NewRunOptions::wrap_operator that installs this disturbance.
  static auto Wrapper(const adahrs::testing::RigProcess& rig,
                      int code,
                      std::string command,
                      std::string& reply) {
    return [&rig, code, command, &reply](
               std::unique_ptr<hil::Operator> inner) -> std::unique_ptr<hil::Operator> {
      return std::make_unique<DisturbingOperator>(std::move(inner), rig, code, command, reply);
    };
  }

 private:
  std::unique_ptr<hil::Operator> inner_;
  const adahrs::testing::RigProcess& rig_;
  int code_;
  std::string command_;
  std::string& reply_;
};

class RecordingProgress : public ProgressSink {
 public:
  void Report(const ProgressReport& r) override {
    last = r;
    reports.push_back(r);
  }
  void Note(const std::string& text) override { notes.push_back(text); }
  ProgressReport last;
  std::vector<ProgressReport> reports;
  std::vector<std::string> notes;
};

/// The table rate the rig's physics has now (`env` on the control port), deg/s.
inline double RigTableRateDps(const adahrs::testing::RigProcess& rig) {
  const std::string env = rig.Control("env");
  const std::string key = "table_rate_dps=";
  const size_t at = env.find(key);
  if (at == std::string::npos) throw std::runtime_error("rig env reply without table rate: " + env);
  return std::stod(env.substr(at + key.size()));
}

/// Calibration rows (tag != 0, outside rejected intervals) of `rec`, per (unit, tag).
inline std::map<std::pair<std::string, int>, std::vector<hil::ImuRecordRow>> TaggedImuRows(
    const hil::Recording& rec) {
  std::map<std::pair<std::string, int>, std::vector<hil::ImuRecordRow>> out;
  for (const hil::ImuRecordRow& r : rec.imu) {
    if (r.tag != 0 && !hil::IsRejected(rec, r.t_s)) out[{r.unit, r.tag}].push_back(r);
  }
  return out;
}

/// Packets missing from the 8-bit sequence counters of the rows of each unit, in file order.
inline std::map<std::string, int> SequenceGaps(const hil::Recording& rec) {
  std::map<std::string, int> gaps;
  std::map<std::string, int> previous;
  for (const hil::ImuRecordRow& r : rec.imu) {
    auto [it, first] = previous.try_emplace(r.unit, static_cast<int>(r.seq));
    gaps[r.unit] += first ? 0 : (static_cast<int>(r.seq) - it->second - 1 + 256) % 256;
    it->second = static_cast<int>(r.seq);
  }
  return gaps;
}

}  // namespace adahrs::calib::testing
