#include "hil/rig_clock.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <thread>
#include <utility>

#include <fmt/format.h>

namespace adahrs::hil {
namespace {

constexpr char kMagic[8] = {'A', 'D', 'A', 'H', 'R', 'S', 'C', 'K'};
constexpr uint32_t kVersion = 1;
constexpr size_t kFileBytes = 64;
constexpr size_t kVersionOffset = 8;
constexpr size_t kFrameOffset = 16;
constexpr size_t kScaleOffset = 24;
constexpr size_t kFramesOffset = 32;
constexpr size_t kPidOffset = 40;

uint64_t& FramesWord(void* map) {
  return *reinterpret_cast<uint64_t*>(static_cast<char*>(map) + kFramesOffset);
}

}  // namespace

RigClockWriter::RigClockWriter(const std::filesystem::path& path, double frame_s, double time_scale)
    : path_(path), map_(SharedFileMap::Create(path, kFileBytes)) {
  char* bytes = map_.data();
  const int64_t pid = ::getpid();
  std::memcpy(bytes + kVersionOffset, &kVersion, sizeof kVersion);
  std::memcpy(bytes + kFrameOffset, &frame_s, sizeof frame_s);
  std::memcpy(bytes + kScaleOffset, &time_scale, sizeof time_scale);
  std::memcpy(bytes + kPidOffset, &pid, sizeof pid);
  Publish(0);
  // The magic last: a reader never accepts a half-written header.
  std::atomic_thread_fence(std::memory_order_release);
  std::memcpy(bytes, kMagic, sizeof kMagic);
}

void RigClockWriter::Publish(uint64_t frames_done) {
  std::atomic_ref<uint64_t>(FramesWord(map_.data())).store(frames_done, std::memory_order_release);
}

RigClock::RigClock(const std::filesystem::path& path, double stall_limit_wall_s)
    : path_(path), stall_limit_wall_s_(stall_limit_wall_s) {
  std::optional<SharedFileMap> map = SharedFileMap::Open(path, /*writable=*/false);
  if (!map) {
    throw std::runtime_error(fmt::format("rig clock {}: {}", path.string(), std::strerror(errno)));
  }
  if (map->size() < kFileBytes) {
    throw std::runtime_error(fmt::format("rig clock {}: {} bytes, not a {}-byte clock file",
                                         path.string(),
                                         map->size(),
                                         kFileBytes));
  }
  const char* bytes = map->data();
  uint32_t version = 0;
  std::memcpy(&version, bytes + kVersionOffset, sizeof version);
  std::memcpy(&frame_s_, bytes + kFrameOffset, sizeof frame_s_);
  std::memcpy(&time_scale_, bytes + kScaleOffset, sizeof time_scale_);
  if (std::memcmp(bytes, kMagic, sizeof kMagic) != 0 || version != kVersion ||
      !(frame_s_ > 0.0 && frame_s_ < 1.0) || !(time_scale_ >= 0.01)) {
    throw std::runtime_error(fmt::format(
        "rig clock {}: not an ADAHRSCK version {} clock file", path.string(), kVersion));
  }
  map_ = std::move(*map);
  // The last whole counter turn of the rig's frames: a unit on the rig counts its packets on
  // them from the rig's start, so a sample time taken from its counter keeps its phase here.
  start_s_ = static_cast<double>(Frames() / kCounterTurnFrames * kCounterTurnFrames) * frame_s_;
}

uint64_t RigClock::Frames() const {
  return std::atomic_ref<uint64_t>(FramesWord(map_.data())).load(std::memory_order_acquire);
}

double RigClock::RigTimeS() const { return static_cast<double>(Frames()) * frame_s_; }

double RigClock::NowS() const { return RigTimeS() - start_s_; }

void RigClock::SleepS(double duration_s) const {
  if (!(duration_s > 0.0)) return;
  const double target_s = RigTimeS() + duration_s;
  uint64_t seen = Frames();
  auto moved_at = std::chrono::steady_clock::now();
  while (true) {
    const uint64_t frames = Frames();
    const double remaining_s = target_s - static_cast<double>(frames) * frame_s_;
    if (remaining_s <= 0.0) return;
    const auto now = std::chrono::steady_clock::now();
    if (frames != seen) {
      seen = frames;
      moved_at = now;
    } else if (std::chrono::duration<double>(now - moved_at).count() > stall_limit_wall_s_) {
      throw std::runtime_error(fmt::format(
          "rig clock {} has stood at {:.2f} s for {:g} s of wall time: the rig has stopped",
          path_.string(),
          static_cast<double>(frames) * frame_s_,
          stall_limit_wall_s_));
    }
    // At the nominal speed the wait ends after remaining/scale; wake at least every 20 ms to
    // follow a rig that runs slower, and no more often than every 0.2 ms.
    const double wall_s = std::clamp(remaining_s / time_scale_, 2e-4, 0.02);
    std::this_thread::sleep_for(std::chrono::duration<double>(wall_s));
  }
}

}  // namespace adahrs::hil
