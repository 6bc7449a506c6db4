// The lockstep rig's per-port packet counts, shared through a small memory-mapped file beside the
// clock file (rig_clock.h; docs/rig.md "Port counts file"). For each unit port the rig publishes
// how many data packets the unit has queued for its line, counted on the unit's own 8-bit
// packet counter unwrapped (the index of the last packet + 1); the port's reader publishes the
// same count up to the last packet it has read. The rig holds its clock while a reader lags more
// than kLockstepPacketBudget packets, so a reader that has just read a packet and then loads the
// rig's count knows that count is less than a counter turn (256) ahead of the packet: the
// packet's index is the largest one with its counter value not above the count, exactly.
//
// A reader attaches (RestartStream) by writing its token; the rig then drops the port's backlog
// (bytes of packets counted before: the stream starts afresh, as a flush of the line), sets the
// slot's consumed count to its own count at that moment (the stream's start: a count the reader
// took before it asked would leave it lagging everything the rig ran while it waited, and held
// with nothing to read) and acknowledges the token, after which everything the reader reads is
// within the budget. A reader
// that lags without reading for kLockstepReleaseAfter_s is released (its token cleared): it finds
// itself detached when it reads again and refuses to index packets it can no longer place.
//
// Layout, host byte order (both ends on one machine): a 64-byte header ("ADAHRSPT", u32 version
// 1, u32 slot count), then per port a 128-byte slot: char[96] slave path (NUL-terminated),
// u64 produced (rig), u64 consumed (reader), u64 reader token (pid and counter; 0: none
// attached), u64 token the rig acknowledged. Words are stored with release, loaded with acquire.
// Left out: two readers of one port at once (the last to attach owns the slot).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "hil/shared_file_map.h"

namespace adahrs::hil {

/// Packets a reader may lag behind its unit before a lockstep rig holds its clock: with the
/// frames the rig runs between two looks (10), well under a counter turn of 256.
inline constexpr uint64_t kLockstepPacketBudget = 100;

/// Wall time a reader may lag more than the budget without reading before the rig releases its
/// slot (RigPortCountsWriter::Release): a reader that stopped must not hold the clock for good,
/// but a live one blocked for seconds on a loaded machine must not lose its count (5 s did, once,
/// for a campaign's IMU logger at load 5 on the 2-core VM).
inline constexpr double kLockstepReleaseAfter_s = 30.0;

/// The most a packet's sample time and its arrival time on a lockstep rig's clock differ for a
/// reader that publishes its count: behind, the budget and the frames between the rig's looks
/// (1.1 s); ahead, the frames of one tick, which the rig caps at those 10 (0.1 s). Either way, and
/// also the most two packets' waits differ (1.2 s); rounded up to the 10 ms of a frame.
inline constexpr double kLockstepLineBuffering_s = 1.2;

/// The port counts file that belongs to the clock file `clock_file`.
std::filesystem::path PortCountsPath(const std::filesystem::path& clock_file);

/// The largest packet index with counter value `seq` (mod 256) below `produced` (the rig's count
/// loaded after the packet was read); nullopt if there is none (produced ≤ seq mod 256).
std::optional<uint64_t> PacketIndexBelow(uint32_t seq, uint64_t produced);

/// The rig's side: creates (or truncates) the file with one slot per port path.
class RigPortCountsWriter {
 public:
  /// Throws std::system_error naming the path if the file cannot be created or mapped, and
  /// std::invalid_argument if a port path does not fit a slot.
  RigPortCountsWriter(const std::filesystem::path& path, const std::vector<std::string>& ports);

  void PublishProduced(size_t slot, uint64_t produced);
  /// The slot's reader token (0: none attached) and the count it has read up to.
  struct Reader {
    uint64_t token = 0;
    uint64_t consumed = 0;
  };
  Reader ReaderOf(size_t slot) const;
  /// Tells the reader holding `token` that its stream starts afresh from packet count `start`
  /// (the rig's count as it dropped the backlog), which becomes the slot's consumed count.
  void Acknowledge(size_t slot, uint64_t token, uint64_t start);
  /// Releases the slot from the reader holding `token` (one that stopped reading): that reader
  /// then finds itself detached, and its packets carry no index.
  void Release(size_t slot, uint64_t token);

 private:
  SharedFileMap map_;
};

/// A reader's side for one port.
class RigPortCounter {
 public:
  /// The counter of `port_path` (or of the device a link there names) in the port counts file
  /// of `clock_file`; nullptr if that file does not exist or does not list the port (a rig that
  /// publishes no counts). Throws std::runtime_error naming the file if it exists but is not a port
  /// counts file.
  static std::unique_ptr<RigPortCounter> Open(const std::filesystem::path& clock_file,
                                              const std::string& port_path);
  ~RigPortCounter();
  RigPortCounter(const RigPortCounter&) = delete;
  RigPortCounter& operator=(const RigPortCounter&) = delete;

  /// The rig's count for this port (acquire).
  uint64_t Produced() const;
  /// Claims the slot and waits up to `wall_s` for the rig to acknowledge: from then on the rig
  /// waits for this reader, and Consumed() is the count the stream starts from. False (and
  /// detached) if it did not.
  bool Attach(double wall_s);
  /// The slot's consumed count: the stream's start after Attach, then what this reader published.
  uint64_t Consumed() const;
  /// Publishes the count read so far (release); only while attached.
  void Consume(uint64_t consumed);
  /// Releases the slot: the rig no longer waits for this reader.
  void Detach();
  /// True while the slot is this counter's (no later counter of the port claimed it).
  bool attached() const;

 private:
  RigPortCounter(SharedFileMap map, char* slot) : map_(std::move(map)), slot_(slot) {}
  SharedFileMap map_;
  char* slot_;
  uint64_t token_ = 0;  // this counter's claim on the slot, 0 when none
};

}  // namespace adahrs::hil
