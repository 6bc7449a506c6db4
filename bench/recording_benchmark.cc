// Writing and reading a recording (hil/recording): rows per second of RecordingWriter::Append and
// of StreamRecording on a synthetic imu.csv of realistic rows — four units, 100 Hz packets
// arriving in bursts that share t_s, noisy raw counts, every other step in thermal mode with nine
// compensated values. Each benchmark's argument is the storage: 0 plain CSV, else gzip at that
// deflate level (1 fastest … 9 smallest). Prints the bytes per row as a counter. The writes are
// timed on the wall clock with the CPU time of the whole process: a compressed file is compressed
// on a thread of its own beside the formatting one, so rows per second is the rate a logger keeps
// up with and the CPU time is both threads'.
#include <algorithm>
#include <filesystem>
#include <random>

#include <benchmark/benchmark.h>

#include "hil/recording/recording_reader.h"
#include "hil/recording/recording_writer.h"

namespace adahrs::hil {
namespace {

constexpr int kUnits = 4;

ImuRecordRow RealisticRow(int64_t index, std::mt19937& random) {
  std::normal_distribution<double> noise(0.0, 1.0);
  const int64_t frame = index / kUnits;
  ImuRecordRow r;
  r.t_s = 0.01 * static_cast<double>(frame - frame % 8);  // bursts of 8 packets per unit
  r.unit = "IMU-000" + std::to_string(index % kUnits + 1);
  r.seq = static_cast<uint32_t>(frame % 256);
  r.step = static_cast<int>(frame / 6000);
  r.tag = static_cast<uint8_t>(r.step % 2 == 0 ? 0 : 7);
  r.orientation = 11;
  r.chamber_c = 25.0 + 0.001 * std::round(1000.0 * 0.3 * noise(random));
  r.table_rate_dps = 0.0;
  for (size_t i = 0; i < 12; ++i) {
    r.accel_ticks[i] = static_cast<uint16_t>((i % 2 == 0 ? 20000 : 40000) + 3.0 * noise(random));
  }
  for (size_t i = 0; i < 3; ++i) {
    r.gyro_cnt[i] = static_cast<int32_t>(4194304 + 400.0 * noise(random));
    r.temp_cnt[i] = static_cast<uint16_t>(32000 + 4.0 * noise(random));
  }
  if (r.step % 2 == 1) {
    r.mode = 1;
    std::array<double, 9> comp{};
    for (size_t i = 0; i < 9; ++i) {
      comp[i] = std::ldexp(std::round(std::ldexp(0.01 * noise(random), 31)), -31);
    }
    r.comp = comp;
  }
  return r;
}

const std::vector<ImuRecordRow>& Rows() {
  static const std::vector<ImuRecordRow> rows = [] {
    std::mt19937 random(11);
    std::vector<ImuRecordRow> out;
    for (int64_t i = 0; i < 200000; ++i) out.push_back(RealisticRow(i, random));
    return out;
  }();
  return rows;
}

std::filesystem::path RunDir(const char* name) {
  return std::filesystem::temp_directory_path() / "adahrs_recording_benchmark" / name;
}

// Level 0: plain CSV; 1…9: gzip at that level.
void WriteRun(const std::filesystem::path& dir, int level) {
  std::filesystem::remove_all(dir);
  RecordingWriter writer(
      dir, level == 0 ? RecordingStorage::kPlainCsv : RecordingStorage::kGzip, std::max(level, 1));
  writer.WriteMetaJson({{"units", nlohmann::json::array()}});
  for (const ImuRecordRow& r : Rows()) writer.Append(r);
  writer.Flush(true);
}

void BM_WriteImuRows(benchmark::State& state) {
  const std::filesystem::path dir = RunDir("write");
  const int level = static_cast<int>(state.range(0));
  for (auto _ : state) WriteRun(dir, level);
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(Rows().size()));
  state.counters["bytes_per_row"] =
      static_cast<double>(std::filesystem::file_size(StoredCsvPath(dir, kImuCsvName))) /
      static_cast<double>(Rows().size());
}
BENCHMARK(BM_WriteImuRows)
    ->Arg(0)
    ->Arg(1)
    ->Arg(6)
    ->MeasureProcessCPUTime()
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_StreamImuRows(benchmark::State& state) {
  const std::filesystem::path dir = RunDir("read");
  WriteRun(dir, static_cast<int>(state.range(0)));
  int64_t rows = 0;
  for (auto _ : state) {
    StreamRecording(dir, {[&](ImuRecordRow&&, int) { ++rows; }, nullptr});
  }
  state.SetItemsProcessed(rows);
}
BENCHMARK(BM_StreamImuRows)->Arg(0)->Arg(1)->Arg(6)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace adahrs::hil

BENCHMARK_MAIN();
