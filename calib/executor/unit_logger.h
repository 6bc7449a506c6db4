// One thread per unit link that polls continuously and appends every received packet as a row of
// the recording (format v3, hil/recording): nothing is dropped, whatever its TAG. Each row is
// annotated with the current step, the commanded orientation and the latest instrument readings
// (run_annotations.h). A UnitLink is not thread-safe, so every request to the unit (SET_TAG,
// SET_MODE, IDENTIFY…) is queued to this thread with Call() and runs between polls.
// StartAcquisition(tag, quota) sets the unit's TAG; the first `quota` packets carrying it are
// recorded with that TAG, any later one or any TAG no acquisition asked for with TAG 0, so the rows
// tagged T are exactly the acquisitions' packets. Raw averages for the interlocks start after a
// READ_COUNTERS round trip, leaving out packets still in transit. Loss: the 8-bit sequence counter.
// Which rows are a step's data: docs/recording-format.md; requests and averages: docs/executor.md
// ("Unit requests", "Interlocks").
// Left out: retrying a failed poll (a transport error stops the thread; CheckHealthy rethrows it).
#pragma once

#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <future>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "calib/executor/run_annotations.h"
#include "calib/executor/shared_recording.h"
#include "hil/drivers/unit_link.h"

namespace adahrs::calib {

/// Mean raw values of an IMU over a number of packets.
struct RawAverage {
  std::array<double, 6> duty_offset{};  ///< T1/T2 - 0.5 of az1 ax1 ay1 az2 ax2 ay2 (0 at 0 g)
  std::array<double, 3> gyro_cnt{};     ///< gx gy gz counts
  int64_t packets = 0;
};

class UnitLogger {
 public:
  /// `link`, `recording` and `annotations` must outlive the logger. `serial` is the unit's serial
  /// text written in every row.
  UnitLogger(hil::UnitLink& link,
             std::string serial,
             SharedRecording& recording,
             const RunAnnotations& annotations);
  ~UnitLogger();
  UnitLogger(const UnitLogger&) = delete;
  UnitLogger& operator=(const UnitLogger&) = delete;

  /// Starts the polling thread.
  void Start();
  /// Stops and joins the thread (idempotent); pending requests fail.
  void Stop();

  /// Queues `request` to run on the logger thread between polls; the future rethrows what it
  /// threw. Throws the thread's own error if it has stopped.
  std::future<void> Submit(std::function<void(hil::UnitLink&)> request);
  /// Submit() and wait.
  void Call(std::function<void(hil::UnitLink&)> request) { Submit(std::move(request)).get(); }

  /// Sets the unit's TAG to `tag` and counts the packets that carry it from zero, recording at
  /// most `quota` of them with the TAG (quota < 0: no limit). The future throws what the link
  /// threw.
  std::future<void> StartAcquisition(uint8_t tag, int64_t quota);
  /// Sets the unit's TAG back to 0; packets still carrying the old TAG count until the quota.
  std::future<void> EndAcquisition();
  /// Packets counted since StartAcquisition().
  int64_t acquired() const { return acquired_.load(); }

  /// Averages the raw values of the `packets` IMU packets that follow a READ_COUNTERS round trip
  /// (queued like a request); the future throws what the link threw.
  std::future<void> BeginAverage(int64_t packets);
  /// The average once complete, else nullopt.
  std::optional<RawAverage> TakeAverage();

  /// Rethrows the error that stopped the polling thread, if any.
  void CheckHealthy() const;

  const std::string& role() const { return role_; }
  const std::string& serial() const { return serial_; }
  uint64_t rows() const { return rows_.load(); }
  uint64_t lost() const { return lost_.load(); }

 private:
  struct Request {
    std::function<void(hil::UnitLink&)> run;
    std::promise<void> done;
  };
  void Loop();
  void RunPendingRequests();
  void FailPendingRequests();
  void Record(const std::vector<hil::ReceivedPacket>& packets);
  uint8_t RowTag(uint8_t packet_tag);
  void Accumulate(const firmware_model::ImuDataPayload& data);

  hil::UnitLink& link_;
  std::string role_;
  std::string serial_;
  SharedRecording& recording_;
  const RunAnnotations& annotations_;

  std::thread thread_;
  std::atomic<bool> stop_{false};
  mutable std::mutex mutex_;  // guards requests_, error_, the acquisition and the average
  std::deque<Request> requests_;
  std::exception_ptr error_;
  bool running_ = false;

  bool armed_ = false;
  uint8_t armed_tag_ = 0;
  int64_t quota_ = -1;
  std::atomic<int64_t> acquired_{0};

  int64_t average_wanted_ = 0;
  RawAverage sum_;

  std::atomic<uint64_t> rows_{0};
  std::atomic<uint64_t> lost_{0};
};

}  // namespace adahrs::calib
