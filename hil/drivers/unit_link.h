// The PC's link to one unit (IMU or ADS) on its serial port (docs/unit-protocol.md): maintenance
// requests answered by one response each, and the unit's 100 Hz data packets, which keep streaming
// on the same line while a request waits. Every data packet that arrives, before, during or after
// a request, is kept for the next Poll(): nothing is dropped on the PC side, and losses on the line
// show as gaps of the 8-bit sequence counter (lost_packets()). A request is tried
// kUnitRequestAttempts times, each a new frame and sequence; a response echoing any attempt is
// accepted; an attempt waits for silence behind the data backlog (up to kUnitBacklogPatience reply
// timeouts, never below kMinWallReplyTimeout of wall time), then kNoReply. A NAK is kRefused; an
// unparsable reply kBadReply; the other unit kind kWrongIdentity. A COMMIT retried after a lost
// ACK commits twice (visible in constants_version). Not thread-safe.
// Units: packet times in clock seconds at arrival; timeouts in the station's clock ms.
// Retries, backlog, errors: docs/drivers.md ("Units: UnitLink", "Timeouts and retries").
// Left out: RESET (the executor never power-cycles a unit mid-run), baud-rate detection.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "hil/clock.h"
#include "hil/codecs/unit_protocol_client.h"
#include "hil/drivers/instrument_port.h"
#include "hil/instruments/instrument_error.h"
#include "hil/rig_port_counts.h"
#include "hil/station.h"
#include "hil/transport/serial_port.h"

namespace adahrs::hil {

/// Attempts of one maintenance request before kNoReply (the first try and two retries).
inline constexpr int kUnitRequestAttempts = 3;
/// Longest wait of one attempt while data keeps arriving, in reply timeouts.
inline constexpr int kUnitBacklogPatience = 3;
/// Longest wall wait for a lockstep rig to take up a restarted stream; without it the link's
/// packets carry no index.
inline constexpr double kAttachWait_s = 2.0;

/// How a link's packets reach the PC, as a recording states it (docs/recording-format.md "Sample
/// time"): the longest a packet waits between its sample and its arrival, s, and how fast the
/// unit's clock may run apart from the PC's, ppm.
struct LineTiming {
  double buffering_s = 0.0;
  double drift_ppm = 0.0;
};
/// A serial line's buffers: the PC's receive buffer (Linux N_TTY_BUF_SIZE) and the unit's
/// transmit buffer (as the simulated unit's, rig_sim/unit_device.h; the real size is not
/// documented); the unit's crystal and the PC's clock within 50 ppm each.
inline constexpr double kSerialLineBufferBytes = 4096.0 + 512.0;
inline constexpr double kSerialLineDrift_ppm = 100.0;

/// One data packet as received.
struct ReceivedPacket {
  uint8_t seq = 0;   ///< the unit's 8-bit data sequence counter
  uint8_t tag = 0;   ///< the step TAG the unit held when it sent the packet
  double t_s = 0.0;  ///< clock time of arrival, s
  /// The packet's index on the lockstep rig's count of the unit's packets (rig_port_counts.h),
  /// exact; -1 when the rig publishes no count (a real line, a free-running rig).
  int64_t index = -1;
  std::variant<firmware_model::ImuDataPayload, firmware_model::AdsDataPayload> data;
};

class UnitLink {
 public:
  /// Opens the unit's port; throws InstrumentError (kNoReply) naming role and port if it cannot.
  /// With the station's `clock_file`, a lockstep rig's port counts for the port are read and
  /// this link's published from RestartStream to EndStream (ReceivedPacket::index; the rig waits
  /// for this link meanwhile).
  UnitLink(const UnitEntry& entry,
           const Clock& clock,
           const std::filesystem::path& clock_file = {});
  UnitLink(const UnitLink&) = delete;
  UnitLink& operator=(const UnitLink&) = delete;

  const UnitEntry& entry() const { return entry_; }
  /// On a lockstep rig that publishes its port counts: kLockstepLineBuffering_s, no drift. On
  /// the wall clock unscaled (a serial line): its buffers at the line's rate plus a frame, 100
  /// ppm. nullopt on a scaled clock without counts (a free-running virtual rig, whose backlog
  /// has no bound the pipeline knows).
  std::optional<LineTiming> line_timing() const;

  /// IDENTIFY; throws kWrongIdentity when the unit is of the other kind than the station says.
  hil::IdentifyInfo Identify();
  void SetTag(uint8_t tag);
  void SetImuMode(firmware_model::ImuCompensationMode mode);
  void SetAdsMode(firmware_model::AdsCompensationMode mode);
  void WriteBlock(uint8_t block_id, std::span<const int16_t> words);
  std::vector<int16_t> ReadBlock(uint8_t block_id);
  hil::CommitInfo Commit();
  hil::UnitCounters ReadCounters();

  /// Data packets received since the last call (including those that arrived while a
  /// maintenance request waited for its response: nothing is dropped), waiting up to `timeout`
  /// (wall clock) for the first.
  std::vector<ReceivedPacket> Poll(std::chrono::milliseconds timeout);

  /// Packets missing from the sequence counter since the link was opened.
  uint64_t lost_packets() const { return tracker_.lost_total(); }
  /// Starts the stream afresh: drops what the line holds and what was received but not polled,
  /// and counts loss from the next packet on (a recording that starts now misses nothing before
  /// it; a lockstep rig may have discarded what it sent while nobody read). With the rig's port
  /// counts, attaches to them first; throws InstrumentError (kNoReply) if the rig does not take
  /// the attachment up within kAttachWait_s. A read that finds the rig released this link's count
  /// (it lagged without reading for hil::kLockstepReleaseAfter_s) throws the same: its packets can
  /// no longer be placed.
  void RestartStream();
  /// Stops publishing this link's packet count: a lockstep rig no longer waits for it to read.
  void EndStream();

  /// Data frames whose CRC held but whose payload no unit sends (wrong length for its mode, mode
  /// byte out of range), dropped since the link was opened; each also shows as a lost packet.
  uint64_t malformed_data_packets() const { return malformed_data_packets_; }

  /// Frames the link's decoder refused (bad CRC, length, type) since it was opened.
  const firmware_model::DecoderCounters& decoder_counters() const { return reader_.counters(); }

  /// Every byte sent and received goes to `sink` (nullptr: off).
  void SetTrace(TraceSink sink) { port_->SetTrace(std::move(sink)); }

 private:
  using BuildRequest = std::function<std::vector<uint8_t>()>;
  hil::MaintenanceResponse Transact(const std::string& command_text,
                                    firmware_model::MaintenanceCommand command,
                                    const BuildRequest& build);
  // Reads what arrives within `timeout` into the packet queue; responses go to `responses`.
  size_t ReadInto(std::chrono::milliseconds timeout,
                  std::vector<hil::MaintenanceResponse>* responses);
  void Accept(const firmware_model::Frame& frame,
              double t_s,
              std::vector<hil::MaintenanceResponse>* responses);
  [[noreturn]] void Fail(InstrumentError::Kind kind,
                         const std::string& command,
                         const std::string& reply,
                         const std::string& detail) const;
  std::chrono::milliseconds ReplyTimeout() const;

  UnitEntry entry_;
  const Clock& clock_;
  std::unique_ptr<SerialPort> port_;
  hil::UnitProtocolClient client_;
  hil::StreamReader reader_;
  hil::SequenceTracker tracker_;
  uint64_t malformed_data_packets_ = 0;
  std::vector<ReceivedPacket> queue_;
  std::unique_ptr<RigPortCounter> counter_;  // nullptr: no lockstep rig's counts
  uint64_t produced_ = 0;                    // the rig's count, loaded after the latest read
  uint64_t consumed_ = 0;                    // the last indexed packet's index + 1
  bool counting_ = false;                    // attached to the rig's count since RestartStream
};

}  // namespace adahrs::hil
