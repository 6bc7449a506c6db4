#include "hil/recording/recording_writer.h"

#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace adahrs::hil {
namespace {

// The header line of an existing file, empty if it has none.
std::string FirstLine(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

constexpr size_t kStdioBufferBytes = size_t{1} << 20;

std::FILE* OpenCsv(const std::filesystem::path& path, std::string_view header, char* buffer) {
  const bool is_new = !std::filesystem::exists(path) || std::filesystem::file_size(path) == 0;
  if (!is_new && FirstLine(path) != header) {
    throw std::runtime_error(path.string() + ":1: cannot append: the header is not the version " +
                             std::to_string(kRecordingFormatVersion) + " header '" +
                             std::string(header) + "'");
  }
  std::FILE* f = std::fopen(path.c_str(), "a");
  if (f == nullptr) {
    throw std::runtime_error(path.string() +
                             ": cannot open for appending: " + std::strerror(errno));
  }
  std::setvbuf(f, buffer, _IOFBF, kStdioBufferBytes);
  if (is_new) std::fprintf(f, "%.*s\n", static_cast<int>(header.size()), header.data());
  return f;
}

// ",<value>" in the shortest form that reads back to the same double (a Q31 word scaled by a
// power of two is exact in a double, so the CSV loses nothing).
void PutReal(std::FILE* f, double value) {
  char text[32];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, value);
  std::fputc(',', f);
  std::fwrite(text, 1, static_cast<size_t>(end - text), f);
}

void Check(int rc, const std::filesystem::path& path, const char* what) {
  if (rc < 0) throw std::runtime_error(path.string() + ": " + what + ": " + std::strerror(errno));
}

}  // namespace

RecordingWriter::RecordingWriter(const std::filesystem::path& run_dir)
    : run_dir_(run_dir),
      imu_buffer_(std::make_unique<char[]>(kStdioBufferBytes)),
      ads_buffer_(std::make_unique<char[]>(kStdioBufferBytes)) {
  std::filesystem::create_directories(run_dir_);
  imu_ = OpenCsv(run_dir_ / kImuCsvName, kImuCsvHeader, imu_buffer_.get());
  try {
    ads_ = OpenCsv(run_dir_ / kAdsCsvName, kAdsCsvHeader, ads_buffer_.get());
  } catch (...) {
    std::fclose(imu_);
    throw;
  }
}

RecordingWriter::~RecordingWriter() {
  std::fclose(imu_);
  std::fclose(ads_);
}

void RecordingWriter::WriteMeta(nlohmann::json meta) const {
  meta["format_version"] = kRecordingFormatVersion;
  const std::filesystem::path final_path = run_dir_ / kMetaJsonName;
  const std::filesystem::path tmp_path = run_dir_ / (std::string(kMetaJsonName) + ".tmp");
  {
    std::ofstream out(tmp_path);
    out << meta.dump(2) << "\n";
    if (!out) throw std::runtime_error(tmp_path.string() + ": write failed");
  }
  std::filesystem::rename(tmp_path, final_path);
}

void RecordingWriter::Append(const ImuRecordRow& r) {
  std::fprintf(imu_,
               "%.4f,%s,%u,%d,%u,%d,%.3f,%.4f",
               r.t_s,
               r.unit.c_str(),
               r.seq,
               r.step,
               static_cast<unsigned>(r.tag),
               r.orientation,
               r.chamber_c,
               r.table_rate_dps);
  for (uint16_t ticks : r.accel_ticks) std::fprintf(imu_, ",%u", static_cast<unsigned>(ticks));
  for (int32_t cnt : r.gyro_cnt) std::fprintf(imu_, ",%d", cnt);
  for (uint16_t cnt : r.temp_cnt) std::fprintf(imu_, ",%u", static_cast<unsigned>(cnt));
  std::fprintf(imu_, ",%u", static_cast<unsigned>(r.mode));
  if (r.comp) {
    for (double v : *r.comp) PutReal(imu_, v);
    std::fprintf(imu_, ",%u\n", r.comp_flags);
  } else {
    std::fputs(",,,,,,,,,,\n", imu_);
  }
  ++imu_rows_;
}

void RecordingWriter::Append(const AdsRecordRow& r) {
  if (r.alt_ft.has_value() != r.cas_kt.has_value()) {
    throw std::invalid_argument("ads row of " + r.unit + " at t_s " + std::to_string(r.t_s) +
                                ": alt_ft and cas_kt must be both present or both absent");
  }
  std::fprintf(ads_,
               "%.4f,%s,%u,%d,%u,%.3f,%.2f,%.2f,%d,%d,%d,%d,%d,%u",
               r.t_s,
               r.unit.c_str(),
               r.seq,
               r.step,
               static_cast<unsigned>(r.tag),
               r.chamber_c,
               r.ps_ref_pa,
               r.qc_ref_pa,
               r.ps_counts,
               r.pt_counts,
               r.ps_temp_counts,
               r.pt_temp_counts,
               r.oat_counts,
               static_cast<unsigned>(r.mode));
  if (r.alt_ft) {
    PutReal(ads_, *r.alt_ft);
    PutReal(ads_, *r.cas_kt);
    std::fprintf(ads_, ",%u\n", r.comp_flags);
  } else {
    std::fputs(",,,\n", ads_);
  }
  ++ads_rows_;
}

void RecordingWriter::Flush(bool durable) {
  for (auto [file, name] : {std::pair{imu_, kImuCsvName}, std::pair{ads_, kAdsCsvName}}) {
    Check(std::fflush(file) == 0 ? 0 : -1, run_dir_ / name, "flush failed");
    if (durable) Check(::fsync(::fileno(file)), run_dir_ / name, "fsync failed");
  }
}

void RecordingWriter::SyncFlushed() const {
  Check(::fsync(::fileno(imu_)), run_dir_ / kImuCsvName, "fsync failed");
  Check(::fsync(::fileno(ads_)), run_dir_ / kAdsCsvName, "fsync failed");
}

}  // namespace adahrs::hil
