#include "hil/recording/recording_writer.h"

#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "hil/recording/row_text.h"

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

namespace {

// The columns every row starts with: t_s, unit, seq, step, tag (docs/recording-format.md).
template <class Row>
void AppendRowPrefix(const Row& r, RowText* row) {
  row->Fixed(r.t_s, 4);
  row->Comma();
  row->Text(r.unit);
  row->Comma();
  row->Integer(r.seq);
  row->Comma();
  row->Integer(r.step);
  row->Comma();
  row->Integer(static_cast<unsigned>(r.tag));
  row->Comma();
}

}  // namespace

void RecordingWriter::Append(const ImuRecordRow& r) {
  RowText row(row_buffer_, r.unit.size());
  AppendRowPrefix(r, &row);
  row.Integer(r.orientation);
  row.Comma();
  row.Fixed(r.chamber_c, 3);
  row.Comma();
  row.Fixed(r.table_rate_dps, 4);
  for (uint16_t ticks : r.accel_ticks) {
    row.Comma();
    row.Integer(static_cast<unsigned>(ticks));
  }
  for (int32_t cnt : r.gyro_cnt) {
    row.Comma();
    row.Integer(cnt);
  }
  for (uint16_t cnt : r.temp_cnt) {
    row.Comma();
    row.Integer(static_cast<unsigned>(cnt));
  }
  row.Comma();
  row.Integer(static_cast<unsigned>(r.mode));
  if (r.comp) {
    for (double v : *r.comp) {
      row.Comma();
      row.Shortest(v);
    }
    row.Comma();
    row.Integer(r.comp_flags);
  } else {
    row.Text(",,,,,,,,,,");
  }
  row.Char('\n');
  Write(imu_, row, kImuCsvName);
  ++imu_rows_;
}

void RecordingWriter::Append(const AdsRecordRow& r) {
  if (r.alt_ft.has_value() != r.cas_kt.has_value()) {
    throw std::invalid_argument("ads row of " + r.unit + " at t_s " + std::to_string(r.t_s) +
                                ": alt_ft and cas_kt must be both present or both absent");
  }
  RowText row(row_buffer_, r.unit.size());
  AppendRowPrefix(r, &row);
  row.Fixed(r.chamber_c, 3);
  row.Comma();
  row.Fixed(r.ps_ref_pa, 2);
  row.Comma();
  row.Fixed(r.qc_ref_pa, 2);
  for (int32_t counts :
       {r.ps_counts, r.pt_counts, r.ps_temp_counts, r.pt_temp_counts, r.oat_counts}) {
    row.Comma();
    row.Integer(counts);
  }
  row.Comma();
  row.Integer(static_cast<unsigned>(r.mode));
  if (r.alt_ft) {
    row.Comma();
    row.Shortest(*r.alt_ft);
    row.Comma();
    row.Shortest(*r.cas_kt);
    row.Comma();
    row.Integer(r.comp_flags);
  } else {
    row.Text(",,,");
  }
  row.Char('\n');
  Write(ads_, row, kAdsCsvName);
  ++ads_rows_;
}

void RecordingWriter::Write(std::FILE* file, const RowText& row, std::string_view name) {
  if (std::fwrite(row.data(), 1, row.size(), file) != row.size()) {
    Check(-1, run_dir_ / name, "write failed");
  }
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
