#include "calib/executor/unit_logger.h"

#include <stdexcept>
#include <variant>
#include <vector>

#include "hil/recording/packet_columns.h"

namespace adahrs::calib {
namespace {

// How long one poll waits for the first packet: short, so queued requests run promptly.
constexpr std::chrono::milliseconds kPollWait{5};

}  // namespace

UnitLogger::UnitLogger(hil::UnitLink& link,
                       std::string serial,
                       SharedRecording& recording,
                       const RunAnnotations& annotations)
    : link_(link),
      role_(link.entry().role),
      serial_(std::move(serial)),
      recording_(recording),
      annotations_(annotations) {}

UnitLogger::~UnitLogger() { Stop(); }

void UnitLogger::Start() {
  link_.RestartStream();  // the recording starts here
  {
    std::lock_guard lock(mutex_);
    running_ = true;
  }
  thread_ = std::thread([this] { Loop(); });
}

void UnitLogger::Stop() {
  stop_ = true;
  if (thread_.joinable()) {
    thread_.join();
    link_.EndStream();  // a lockstep rig no longer waits for a link nobody reads
  }
  FailPendingRequests();
}

std::future<void> UnitLogger::Submit(std::function<void(hil::UnitLink&)> request) {
  std::lock_guard lock(mutex_);
  if (error_) std::rethrow_exception(error_);
  if (!running_) throw std::logic_error(role_ + ": unit logger is not running; request refused");
  requests_.push_back({std::move(request), {}});
  return requests_.back().done.get_future();
}

std::future<void> UnitLogger::StartAcquisition(uint8_t tag, int64_t quota) {
  return Submit([this, tag, quota](hil::UnitLink& link) {
    {
      std::lock_guard lock(mutex_);
      armed_ = true;
      armed_tag_ = tag;
      quota_ = quota;
      acquired_ = 0;
    }
    link.SetTag(tag);
  });
}

std::future<void> UnitLogger::EndAcquisition() {
  return Submit([](hil::UnitLink& link) { link.SetTag(0); });
}

std::future<void> UnitLogger::BeginAverage(int64_t packets) {
  return Submit([this, packets](hil::UnitLink& link) {
    // The response comes after every packet sent before the unit handled the request: record
    // those first, then average what follows.
    link.ReadCounters();
    Record(link.Poll(std::chrono::milliseconds(0)));
    std::lock_guard lock(mutex_);
    average_wanted_ = packets;
    sum_ = RawAverage{};
  });
}

std::optional<RawAverage> UnitLogger::TakeAverage() {
  std::lock_guard lock(mutex_);
  if (average_wanted_ <= 0 || sum_.packets < average_wanted_) return std::nullopt;
  RawAverage mean = sum_;
  for (double& d : mean.duty_offset) d /= static_cast<double>(mean.packets);
  for (double& g : mean.gyro_cnt) g /= static_cast<double>(mean.packets);
  average_wanted_ = 0;
  return mean;
}

void UnitLogger::CheckHealthy() const {
  std::lock_guard lock(mutex_);
  if (error_) std::rethrow_exception(error_);
}

void UnitLogger::Loop() {
  try {
    while (!stop_) {
      RunPendingRequests();
      Record(link_.Poll(kPollWait));
      lost_ = link_.lost_packets();
    }
  } catch (...) {
    std::lock_guard lock(mutex_);
    error_ = std::current_exception();
  }
  {
    std::lock_guard lock(mutex_);
    running_ = false;
  }
  FailPendingRequests();
}

void UnitLogger::RunPendingRequests() {
  for (;;) {
    Request request;
    {
      std::lock_guard lock(mutex_);
      if (requests_.empty()) return;
      request = std::move(requests_.front());
      requests_.pop_front();
    }
    try {
      request.run(link_);
      request.done.set_value();
    } catch (...) {
      request.done.set_exception(std::current_exception());
    }
  }
}

void UnitLogger::FailPendingRequests() {
  std::lock_guard lock(mutex_);
  while (!requests_.empty()) {
    const std::exception_ptr why =
        error_ ? error_
               : std::make_exception_ptr(std::runtime_error(role_ + ": unit logger stopped"));
    requests_.front().done.set_exception(why);
    requests_.pop_front();
  }
}

uint8_t UnitLogger::RowTag(uint8_t packet_tag) {
  if (packet_tag == 0 || !armed_ || packet_tag != armed_tag_) return 0;
  if (quota_ >= 0 && acquired_.load() >= quota_) return 0;
  ++acquired_;
  return packet_tag;
}

void UnitLogger::Accumulate(const firmware_model::ImuDataPayload& data) {
  if (average_wanted_ <= 0 || sum_.packets >= average_wanted_) return;
  for (int ch = 0; ch < 6; ++ch) {
    if (data.raw.t2_cnt[ch] == 0) continue;  // no period captured: duty undefined
    sum_.duty_offset[ch] += static_cast<double>(data.raw.t1_cnt[ch]) / data.raw.t2_cnt[ch] - 0.5;
  }
  for (int i = 0; i < 3; ++i) sum_.gyro_cnt[i] += data.raw.gyro_cnt[i];
  ++sum_.packets;
}

void UnitLogger::Record(const std::vector<hil::ReceivedPacket>& packets) {
  if (packets.empty()) return;
  const RowAnnotations a = annotations_.Get();
  std::vector<hil::ImuRecordRow> imu_rows;
  std::vector<hil::AdsRecordRow> ads_rows;
  {
    std::lock_guard lock(mutex_);
    for (const hil::ReceivedPacket& p : packets) {
      const uint8_t tag = RowTag(p.tag);
      if (const auto* imu = std::get_if<firmware_model::ImuDataPayload>(&p.data)) {
        hil::ImuRecordRow& row = imu_rows.emplace_back();
        row.t_s = p.t_s;
        row.unit = serial_;
        row.seq = p.seq;
        row.packet_index = p.index;
        row.step = a.step;
        row.tag = tag;
        row.orientation = a.orientation;
        row.chamber_c = a.chamber_c;
        row.table_rate_dps = a.table_rate_dps;
        hil::SetPacketColumns(*imu, row);
        Accumulate(*imu);
      } else {
        hil::AdsRecordRow& row = ads_rows.emplace_back();
        row.t_s = p.t_s;
        row.unit = serial_;
        row.seq = p.seq;
        row.packet_index = p.index;
        row.step = a.step;
        row.tag = tag;
        row.chamber_c = a.chamber_c;
        row.ps_ref_pa = a.ps_ref_pa;
        row.qc_ref_pa = a.qc_ref_pa;
        hil::SetPacketColumns(std::get<firmware_model::AdsDataPayload>(p.data), row);
      }
    }
  }
  recording_.Append(std::span<const hil::ImuRecordRow>(imu_rows));
  recording_.Append(std::span<const hil::AdsRecordRow>(ads_rows));
  rows_ += packets.size();
}

}  // namespace adahrs::calib
