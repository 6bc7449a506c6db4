#include "hil/recording/recording_writer.h"

#include <optional>
#include <stdexcept>

#include "common/atomic_file.h"
#include "hil/recording/csv_lines.h"
#include "hil/recording/last_frames.h"
#include "hil/recording/row_text.h"

namespace adahrs::hil {
void RecordingWriter::WriteMetaJson(nlohmann::json meta) const {
  meta["format_version"] = kRecordingFormatVersion;
  WriteMeta(RecordingMeta::FromJson(meta, (run_dir_ / kMetaJsonName).string()));
}

namespace {

// The header line of an existing file, empty if it has none.
std::string FirstLine(const std::filesystem::path& path) {
  CsvLines lines(path);
  std::string_view line;
  bool complete = false;
  return lines.Next(line, complete) ? std::string(line) : std::string();
}

// The file of `csv_name` in `run_dir`: the one there already (a resumed run keeps its form),
// else a new one stored as `storage`, with its header line.
std::unique_ptr<CsvFileWriter> OpenCsv(const std::filesystem::path& run_dir,
                                       std::string_view csv_name,
                                       std::string_view header,
                                       RecordingStorage storage,
                                       int gzip_level) {
  std::filesystem::path path = StoredCsvPath(run_dir, csv_name);
  const bool is_new = !std::filesystem::exists(path) || std::filesystem::file_size(path) == 0;
  if (!std::filesystem::exists(path)) path = CsvPathFor(run_dir, csv_name, storage);
  if (!is_new && FirstLine(path) != header) {
    throw std::runtime_error(path.string() + ":1: cannot append: the header is not the version " +
                             std::to_string(kRecordingFormatVersion) + " header '" +
                             std::string(header) + "'");
  }
  auto file = std::make_unique<CsvFileWriter>(path, gzip_level);
  if (is_new) {
    file->Append(header);
    file->Append("\n");
  }
  return file;
}

}  // namespace

RecordingWriter::RecordingWriter(const std::filesystem::path& run_dir,
                                 RecordingStorage storage,
                                 int gzip_level)
    : run_dir_(run_dir) {
  std::filesystem::create_directories(run_dir_);
  imu_ = OpenCsv(run_dir_, kImuCsvName, kImuCsvHeader, storage, gzip_level);
  ads_ = OpenCsv(run_dir_, kAdsCsvName, kAdsCsvHeader, storage, gzip_level);
  for (const CsvFileWriter* file : {imu_.get(), ads_.get()}) {
    for (const auto& [serial, last] : LastFrames(file->path()))
      frames_[serial] = FrameCounter(last);
  }
}

int64_t RecordingWriter::Frame(
    const std::string& unit, uint32_t seq, double t_s, int64_t frame, int64_t packet_index) {
  auto it = frames_.find(unit);
  if (it == frames_.end()) it = frames_.emplace(unit, FrameCounter()).first;
  if (frame < 0) {
    return it->second.Next(
        seq, t_s, packet_index >= 0 ? std::optional<int64_t>(packet_index) : std::nullopt);
  }
  it->second = FrameCounter(FrameState{frame, seq, t_s});
  return frame;
}

void RecordingWriter::WriteMeta(RecordingMeta meta) const {
  meta.format_version = kRecordingFormatVersion;
  common::WriteFileAtomically(run_dir_ / kMetaJsonName, meta.ToJson().dump(2) + "\n");
}

namespace {

// The columns every row ends with: frame, t_sample_s (docs/recording-format.md).
void AppendSampleTime(int64_t frame, RowText* row) {
  row->Comma();
  row->Integer(frame);
  row->Comma();
  row->Fixed(SampleTimeS(frame), 2);
  row->Char('\n');
}

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
  AppendSampleTime(Frame(r.unit, r.seq, r.t_s, r.frame, r.packet_index), &row);
  imu_->Append(std::string_view(row.data(), row.size()));
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
  for (int32_t counts : {r.ps_cnt, r.pt_cnt, r.ps_temp_cnt, r.pt_temp_cnt, r.oat_cnt}) {
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
  AppendSampleTime(Frame(r.unit, r.seq, r.t_s, r.frame, r.packet_index), &row);
  ads_->Append(std::string_view(row.data(), row.size()));
  ++ads_rows_;
}

void RecordingWriter::Flush(bool durable) {
  imu_->Flush();
  ads_->Flush();
  if (durable) SyncFlushed();
}

void RecordingWriter::FlushIfDue() {
  imu_->FlushIfDue();
  ads_->FlushIfDue();
}

void RecordingWriter::SyncFlushed() const {
  imu_->Sync();
  ads_->Sync();
}

}  // namespace adahrs::hil
