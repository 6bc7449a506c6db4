// Test and benchmark helper: runs the rig's 4 IMU + 1 ADS units (default config, no instruments)
// at a time scale for a simulated duration while one client thread reads every unit port and
// counts packets and losses. The client walks the frames by their length field and checks sync,
// CRC (Boost.CRC, firmware_model::HostCrc16) and the sequence counter: on a clean stream that is
// all the full resynchronising decoder would do, at a fraction of its cost, so the measurement is
// of the rig, not of the client.
#pragma once

#include <poll.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <thread>
#include <vector>

#include "hil/codecs/unit_protocol_client.h"
#include "rig_sim/rig.h"
#include "rig_sim/unit_device.h"
#include "tests/rig_sim/pty_client.h"

namespace adahrs::rig_sim::testing {

// Frames of a clean stream, delimited by their length field (docs/unit-protocol.md §2).
class FrameWalker {
 public:
  void Push(const uint8_t* bytes, size_t count) {
    pending_.insert(pending_.end(), bytes, bytes + count);
    size_t pos = 0;
    while (pending_.size() - pos >= firmware_model::kFrameHeaderBytes) {
      const uint8_t* f = pending_.data() + pos;
      if (f[0] != firmware_model::kSyncByte0 || f[1] != firmware_model::kSyncByte1) {
        ++bad_frames;  // lost sync: count and step one byte
        ++pos;
        continue;
      }
      const size_t length =
          size_t{f[2]} + firmware_model::kFrameHeaderBytes + firmware_model::kFrameTrailerBytes;
      if (pending_.size() - pos < length) break;
      const uint16_t crc = static_cast<uint16_t>(f[length - 2] | (f[length - 1] << 8));
      if (hil::HostCrc16({f + 2, length - 4}) != crc) {
        ++bad_frames;
        ++pos;
        continue;
      }
      ++packets;
      tracker.Observe(f[4]);
      pos += length;
    }
    pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(pos));
  }
  uint64_t packets = 0;
  uint64_t bad_frames = 0;
  hil::SequenceTracker tracker;

 private:
  std::vector<uint8_t> pending_;
};

struct ThroughputResult {
  double simulated_s = 0.0;       ///< simulated time when `simulated_s` was reached
  double wall_s = 0.0;            ///< wall time to reach it
  std::vector<uint64_t> packets;  ///< per unit port
  uint64_t lost = 0;              ///< sequence gaps over all ports
  uint64_t bad_frames = 0;        ///< CRC, length or type errors over all ports
  uint64_t host_bytes_lost = 0;   ///< bytes the host could not hand to the ptys
};

/// Streams every unit of the default rig at `time_scale` (its top speed when `lockstep`: the
/// clock then waits for this reader) until `simulated_s` of rig time, reading every port.
inline ThroughputResult MeasureThroughput(double time_scale,
                                          double simulated_s,
                                          bool lockstep = false) {
  nlohmann::json j = DefaultRigConfig();
  j["time_scale"] = time_scale;
  j["lockstep"] = lockstep;
  j["instruments"] = nlohmann::json::object();
  const auto dir =
      std::filesystem::temp_directory_path() / ("adahrs_throughput_" + std::to_string(::getpid()));
  Rig rig(RigConfig::FromJson(j, "throughput"), dir);
  std::vector<std::string> roles;
  for (const auto& [role, path] : rig.ports()) {
    if (role != "control") roles.push_back(role);
  }
  std::vector<std::unique_ptr<PtyClient>> clients;
  for (const std::string& role : roles)
    clients.push_back(std::make_unique<PtyClient>(rig.ports().at(role)));
  std::vector<FrameWalker> walkers(roles.size());
  ThroughputResult result;
  result.packets.assign(roles.size(), 0);
  std::atomic<bool> stop{false};
  std::atomic<uint64_t> delivered{0};  // packets of the port that has received the fewest

  std::thread reader([&] {
    std::vector<pollfd> fds;
    for (const auto& c : clients) fds.push_back({c->fd(), POLLIN, 0});
    std::vector<uint8_t> buffer(1 << 16);
    int idle_polls = 0;
    while (!stop.load() || idle_polls < 3) {
      const int ready = ::poll(fds.data(), fds.size(), 10);
      idle_polls = ready <= 0 ? idle_polls + 1 : 0;
      for (size_t i = 0; i < fds.size(); ++i) {
        if (!(fds[i].revents & POLLIN)) continue;
        const ssize_t n = ::read(fds[i].fd, buffer.data(), buffer.size());
        if (n <= 0) continue;
        walkers[i].Push(buffer.data(), static_cast<size_t>(n));
      }
      uint64_t fewest = walkers[0].packets;
      for (const FrameWalker& w : walkers) fewest = std::min(fewest, w.packets);
      delivered = fewest;
    }
  });
  const auto start = std::chrono::steady_clock::now();
  rig.Start(dir / "manifest.json");
  while (rig.host().now_s() < simulated_s)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.simulated_s = rig.host().now_s();
  // Let the client read what the rig still holds for it (up to 10 s wall), then stop.
  const auto expected = static_cast<uint64_t>(simulated_s / kUnitSamplePeriod_s) - 1;
  for (int i = 0; i < 500 && delivered.load() < expected; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  rig.Stop();
  stop = true;
  reader.join();
  for (size_t i = 0; i < roles.size(); ++i) {
    result.packets[i] = walkers[i].packets;
    result.lost += walkers[i].tracker.lost_total();
    result.bad_frames += walkers[i].bad_frames;
  }
  result.host_bytes_lost = rig.host().bytes_lost();
  std::filesystem::remove_all(dir);
  return result;
}

}  // namespace adahrs::rig_sim::testing
