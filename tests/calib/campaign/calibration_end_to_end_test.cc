// The full reference IMU sensor-calibration sequence for the rig's 4 IMUs and the ADS calibration
// sequence for its ADS unit, run concurrently on two benches (two station files over one rig
// started as a separate process, tests/support/rig_process.h) by the real pipeline
// (calib/campaign/bench_runs.h -> StartRun), the rig in lockstep: its clock waits for the
// pipeline's readers, so a busy machine makes the run slower, never lossy. The wall time is
// printed, not judged (docs/performance.md has it).
// Truth checked, none of it from the code under test:
//   - zero lost packets three ways: the links' sequence-counter loss counts (RunSummary), the
//     units listed in meta.json each having rows, and the recorded `seq` column stepping by
//     exactly 1 (mod 256, the unit protocol's one-byte counter) between consecutive rows of a unit;
//   - every acquiring step complete: rows with the step's index and TAG outside rejected intervals
//     number exactly the packets the sequence file asks for (the sum of its acquisitions, from the
//     sequence expansion), for every unit (docs/recording-format.md: tagged rows are exactly the
//     acquisitions);
//   - the units' sample clock (docs/recording-format.md "Sample time"): with no packet lost, each
//     row is the unit's next frame, so frame - first frame is the row's index, exactly (a phantom
//     counter turn is a step of 257), and |t_sample_s - t_s| stays within the lockstep line's
//     buffering: the rig runs at most 100 + 10 frames past what a reader has read and 100 frames
//     in a tick (docs/rig.md "Port counts file"); 1.2 s.
// Runs alone (SERIAL in tests/CMakeLists.txt): the run takes both cores for a minute or more.
// Under ASan/UBSan the build checks memory and arithmetic, not speed: the same code paths run the
// --quick variants of both sequences (calib/campaign/quick_sequences.h) at 200x with every loss
// and completeness check.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <string>
#include <vector>
#include "adahrs_build_paths.h"

#include <gtest/gtest.h>

#include "calib/campaign/bench_runs.h"
#include "calib/campaign/quick_sequences.h"
#include "calib/sequence/execution_plan.h"
#include "calib/sequence/sequence_json.h"
#include "hil/recording/frame_count.h"
#include "hil/recording/recording_reader.h"
#include "tests/support/rig_process.h"

namespace adahrs::calib {
namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;
constexpr double kTimeScale = 200.0;
#else
constexpr bool kSanitized = false;
// The rig's top speed: its frame thread sustains ~900x on this 2-core host (docs/performance.md).
constexpr double kTimeScale = 1000.0;
#endif

const std::string kSequenceDir = std::string(ADAHRS_SOURCE_DIR) + "/calib/sequences/";

// A station of the rig limited to one bench: instruments of `keep_kinds`, units of `unit_kind`.
std::string BenchStation(const testing::RigProcess& rig,
                         const std::string& file,
                         const std::vector<std::string>& keep_kinds,
                         const std::string& unit_kind) {
  return rig.WriteStation(file, [&](nlohmann::json& station) {
    nlohmann::json instruments = nlohmann::json::object();
    for (const auto& [role, entry] : station["instruments"].items()) {
      for (const std::string& kind : keep_kinds) {
        if (entry["type"] == kind) instruments[role] = entry;
      }
    }
    station["instruments"] = instruments;
    nlohmann::json units = nlohmann::json::array();
    for (const nlohmann::json& unit : station["units"]) {
      if (unit["kind"] == unit_kind) units.push_back(unit);
    }
    station["units"] = units;
  });
}

class SilentProgress : public ProgressSink {
 public:
  void Report(const ProgressReport&) override {}
  void Note(const std::string& text) override { std::printf("note: %s\n", text.c_str()); }
};

// Packets the sequence asks for in each step (sum of its acquisitions), by step index.
std::map<int, int64_t> PacketsPerStep(const std::string& sequence_file) {
  const ParsedSequence parsed = ParseSequenceFile(sequence_file);
  std::map<int, int64_t> packets;
  for (const PlannedAction& a : ExpandSequence(parsed.sequence, SequenceLimits{}).actions) {
    if (const auto* acquire = std::get_if<AcquirePackets>(&a.action)) {
      packets[static_cast<int>(a.step)] += acquire->packets;
    }
  }
  return packets;
}

std::map<int, uint8_t> TagPerStep(const std::string& sequence_file) {
  const ParsedSequence parsed = ParseSequenceFile(sequence_file);
  std::map<int, uint8_t> tags;
  for (const PlannedAction& a : ExpandSequence(parsed.sequence, SequenceLimits{}).actions) {
    tags[static_cast<int>(a.step)] = a.tag;
  }
  return tags;
}

// Per unit: frame steps other than 1 between consecutive rows, and the largest |t_sample_s - t_s|.
template <typename Row>
void CheckSampleClock(const std::vector<Row>& rows) {
  constexpr double kLineBuffering_s = 1.2;
  struct Clock {
    int64_t rows = 0;
    int64_t last_frame = 0;
    int64_t steps_off = 0;
    double lo_s = 0.0;
    double hi_s = 0.0;
  };
  std::map<std::string, Clock> clocks;
  for (const Row& row : rows) {
    const double offset_s = hil::SampleTimeS(row.frame) - row.t_s;
    Clock& c = clocks[row.unit];
    if (c.rows++ == 0) {
      c.lo_s = c.hi_s = offset_s;
    } else {
      if (row.frame - c.last_frame != 1) ++c.steps_off;
      c.lo_s = std::min(c.lo_s, offset_s);
      c.hi_s = std::max(c.hi_s, offset_s);
    }
    c.last_frame = row.frame;
  }
  for (const auto& [serial, c] : clocks) {
    std::printf("%s: %lld rows, t_sample_s - t_s from %+.3f to %+.3f s\n",
                serial.c_str(),
                static_cast<long long>(c.rows),
                c.lo_s,
                c.hi_s);
    EXPECT_EQ(c.steps_off, 0) << serial << ": rows whose frame is not the previous row's + 1";
    // t_s is written to 0.1 ms.
    EXPECT_LE(std::max(-c.lo_s, c.hi_s), kLineBuffering_s + 1e-4) << serial;
  }
}

// Checks seq continuity and per-step completeness for rows of one kind.
template <typename Row>
void CheckRows(const hil::Recording& recording,
               const std::vector<Row>& rows,
               const std::string& sequence_file,
               const std::string& kind) {
  const std::map<int, int64_t> expected = PacketsPerStep(sequence_file);
  const std::map<int, uint8_t> tags = TagPerStep(sequence_file);
  std::map<std::string, uint32_t> last_seq;
  std::map<std::string, int64_t> gaps;
  std::map<std::string, std::map<int, int64_t>> tagged;
  for (const Row& row : rows) {
    if (auto it = last_seq.find(row.unit); it != last_seq.end()) {
      if (row.seq != (it->second + 1) % 256) ++gaps[row.unit];
    }
    last_seq[row.unit] = row.seq;
    if (row.tag != 0 && row.tag == tags.at(row.step) && !hil::IsRejected(recording, row.t_s)) {
      ++tagged[row.unit][row.step];
    }
  }
  for (const hil::RecordingUnit& unit : recording.meta.units) {
    if (!unit.kind || common::UnitKindName(*unit.kind) != kind) continue;
    const std::string& serial = unit.serial;
    ASSERT_TRUE(last_seq.count(serial)) << serial << " has no rows";
    EXPECT_EQ(gaps[serial], 0) << serial << ": seq column jumps (lost packets)";
    for (const auto& [step, packets] : expected) {
      EXPECT_EQ(tagged[serial][step], packets) << serial << " step " << step;
    }
  }
}

TEST(CalibrationEndToEndTest, FourImusAndOneAdsCalibratedConcurrentlyInLockstepWithoutLoss) {
  testing::RigProcess rig(kTimeScale, std::nullopt, /*lockstep=*/true);
  const std::string imu_station =
      BenchStation(rig, "station-imu.json", {"aerosmith_atl", "watlow_f4"}, "imu");
  const std::string ads_station =
      BenchStation(rig, "station-ads.json", {"watlow_942", "druck_adts_prologix"}, "ads");
  std::string imu_sequence = kSequenceDir + "imu_sensor_calibration.json";
  std::string ads_sequence = kSequenceDir + "ads_calibration.json";
  if (kSanitized) {
    const CampaignSequences quick = WriteQuickSequences({{imu_sequence},
                                                         ads_sequence,
                                                         kSequenceDir + "imu_acceptance.json",
                                                         kSequenceDir + "ads_acceptance.json"},
                                                        rig.dir() / "quick");
    imu_sequence = quick.imu_calibration.front();
    ads_sequence = quick.ads_calibration;
  }
  SilentProgress imu_progress, ads_progress;
  const std::vector<BenchPlan> benches = {
      {"IMU bench", imu_station, {{imu_sequence, rig.dir() / "imu_run"}}, &imu_progress},
      {"ADS bench", ads_station, {{ads_sequence, rig.dir() / "ads_run"}}, &ads_progress}};
  const std::atomic<bool> stop{false};

  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::vector<RunSummary>> summaries =
      RunBenchesConcurrently(benches, ExecutorOptions{}, stop);
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const hil::Recording imu = hil::ReadRecording(rig.dir() / "imu_run");
  const hil::Recording ads = hil::ReadRecording(rig.dir() / "ads_run");
  std::printf(
      "wall %.1f s at %gx: IMU sensor calibration %.0f simulated s, %zu rows; ADS "
      "calibration %.0f simulated s, %zu rows\n",
      wall_s,
      kTimeScale,
      imu.imu.empty() ? 0.0 : imu.imu.back().t_s,
      imu.imu.size(),
      ads.ads.empty() ? 0.0 : ads.ads.back().t_s,
      ads.ads.size());
  ASSERT_EQ(summaries.size(), 2u);
  for (const std::vector<RunSummary>& bench : summaries) {
    ASSERT_EQ(bench.size(), 1u);
    EXPECT_EQ(bench[0].status, "complete");
    EXPECT_EQ(bench[0].lost, 0u) << bench[0].run_dir;
  }
  EXPECT_EQ(imu.meta.units.size(), 4u);
  EXPECT_EQ(ads.meta.units.size(), 1u);
  CheckRows(imu, imu.imu, imu_sequence, "imu");
  CheckRows(ads, ads.ads, ads_sequence, "ads");
  CheckSampleClock(imu.imu);
  CheckSampleClock(ads.ads);
}

}  // namespace
}  // namespace adahrs::calib
