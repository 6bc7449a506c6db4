#include "hil/drivers/unit_link.h"

#include <algorithm>
#include <array>

#include <fmt/format.h>

#include "common/unit_kind.h"

namespace adahrs::hil {
namespace {

namespace fm = firmware_model;
using Kind = InstrumentError::Kind;

constexpr size_t kReadChunkBytes = 4096;
// The shortest wait of a read (a zero wait would cancel the read before Asio performs it).
constexpr std::chrono::milliseconds kDrainWait{1};

std::unique_ptr<SerialPort> OpenPort(const UnitEntry& entry) {
  try {
    return std::make_unique<SerialPort>(entry.port, entry.role);
  } catch (const TransportError& e) {
    throw InstrumentError(Kind::kNoReply, entry.role, entry.port.path, "open", "", e.what());
  }
}

std::string ResponseText(const hil::MaintenanceResponse& response) {
  return fmt::format("command 0x{:02x} seq {} {}{}",
                     static_cast<int>(response.command),
                     response.sequence,
                     hil::ResultCodeName(response.result),
                     response.data.empty() ? "" : " data " + hil::HexTrace(response.data));
}

}  // namespace

UnitLink::UnitLink(const UnitEntry& entry,
                   const Clock& clock,
                   const std::filesystem::path& clock_file)
    : entry_(entry), clock_(clock), port_(OpenPort(entry)) {
  if (!clock_file.empty()) counter_ = RigPortCounter::Open(clock_file, entry.port.path);
}

std::optional<LineTiming> UnitLink::line_timing() const {
  if (counter_) return LineTiming{kLockstepLineBuffering_s, 0.0};
  if (clock_.may_pause() || clock_.time_scale() != 1.0) return std::nullopt;
  constexpr double kBitsPerByte = 10.0;  // 8N1
  return LineTiming{kSerialLineBufferBytes * kBitsPerByte / entry_.port.baud + 0.01,
                    kSerialLineDrift_ppm};
}

std::chrono::milliseconds UnitLink::ReplyTimeout() const {
  return WallReplyTimeout(clock_, entry_.timeout_ms);
}

void UnitLink::Fail(Kind kind,
                    const std::string& command,
                    const std::string& reply,
                    const std::string& detail) const {
  throw InstrumentError(kind, entry_.role, entry_.port.path, command, reply, detail);
}

void UnitLink::Accept(const fm::Frame& frame,
                      double t_s,
                      std::vector<hil::MaintenanceResponse>* responses) {
  const auto type = static_cast<fm::PacketType>(frame.type);
  const fm::PacketType expected =
      entry_.kind == UnitKind::kImu ? fm::PacketType::kImuData : fm::PacketType::kAdsData;
  if (type == fm::PacketType::kMaintenanceResponse) {
    if (responses == nullptr) return;  // an answer to a request that already gave up
    try {
      responses->push_back(hil::ParseMaintenanceResponse(frame));
    } catch (const hil::ProtocolError& e) {
      Fail(Kind::kBadReply,
           "maintenance response",
           hil::HexTrace(std::span<const uint8_t>(frame.payload, frame.payload_length)),
           e.what());
    }
    return;
  }
  if (type != expected) {
    Fail(Kind::kWrongIdentity,
         "data packet",
         fmt::format("packet type 0x{:02x}", static_cast<int>(frame.type)),
         fmt::format("the station holds an {} unit here", common::UnitKindName(entry_.kind)));
  }
  ReceivedPacket packet;
  packet.seq = frame.sequence;
  packet.tag = frame.tag;
  packet.t_s = t_s;
  try {
    if (entry_.kind == UnitKind::kImu) {
      packet.data = hil::ParseImuData(frame);
    } else {
      packet.data = hil::ParseAdsData(frame);
    }
  } catch (const hil::ProtocolError&) {
    // A data frame that passed its CRC but whose payload no unit sends: bytes cut from a stream
    // that overran and spliced into a frame whose CRC matches by chance (1 in 65,536). Its
    // contents cannot be trusted, so it is dropped and counted; its sequence number is not
    // trusted either, so the gap to the next good packet counts it as lost.
    ++malformed_data_packets_;
    return;
  }
  if (counter_ && counter_->attached()) {
    if (const std::optional<uint64_t> index = PacketIndexBelow(packet.seq, produced_)) {
      packet.index = static_cast<int64_t>(*index);
      consumed_ = std::max(consumed_, *index + 1);
    }
  }
  tracker_.Observe(packet.seq);
  queue_.push_back(std::move(packet));
}

void UnitLink::RestartStream() {
  if (counter_) {
    // The rig drops its backlog for this link and starts its count at its own count before it
    // acknowledges, so what the line brings after the flush below was counted within the budget
    // of this link's count.
    counting_ = counter_->Attach(kAttachWait_s);
    if (!counting_) {
      Fail(Kind::kNoReply,
           "attach",
           "",
           fmt::format("the lockstep rig did not take up the restarted stream within {} s",
                       kAttachWait_s));
    }
    consumed_ = counter_->Consumed();
  }
  port_->DiscardInput();
  queue_.clear();
  tracker_ = hil::SequenceTracker{};
}

void UnitLink::EndStream() {
  counting_ = false;
  if (counter_) counter_->Detach();
}

size_t UnitLink::ReadInto(std::chrono::milliseconds timeout,
                          std::vector<hil::MaintenanceResponse>* responses) {
  std::array<uint8_t, kReadChunkBytes> chunk{};
  size_t n = 0;
  try {
    n = port_->ReadSome(chunk, timeout);
  } catch (const TransportError& e) {
    Fail(Kind::kNoReply, "read", "", e.what());
  }
  if (n == 0) return 0;
  const double t_s = clock_.NowS();
  if (counting_ && !counter_->attached()) {
    counting_ = false;
    Fail(Kind::kNoReply,
         "read",
         "",
         fmt::format("the lockstep rig released this link's packet count: it lagged its unit "
                     "without reading for {} s, so sample times from here on are not exact",
                     kLockstepReleaseAfter_s));
  }
  // Loaded after the read: every packet read is counted in it, and the rig, held on this link's
  // count, has run less than a counter turn past them.
  if (counter_ && counter_->attached()) produced_ = counter_->Produced();
  for (const fm::Frame& frame : reader_.Push(std::span<const uint8_t>(chunk.data(), n))) {
    Accept(frame, t_s, responses);
  }
  if (counter_ && counter_->attached()) counter_->Consume(consumed_);
  return n;
}

hil::MaintenanceResponse UnitLink::Transact(const std::string& command_text,
                                            fm::MaintenanceCommand command,
                                            const BuildRequest& build) {
  const std::chrono::milliseconds timeout = ReplyTimeout();
  std::vector<uint8_t> sequences;
  for (int attempt = 0; attempt < kUnitRequestAttempts; ++attempt) {
    std::vector<uint8_t> request;
    try {
      request = build();
    } catch (const hil::ProtocolError& e) {
      Fail(Kind::kRefused, command_text, "", e.what());
    }
    sequences.push_back(client_.last_sequence());
    try {
      port_->Write(request, timeout);
    } catch (const TransportError& e) {
      Fail(Kind::kNoReply, command_text, "", e.what());
    }
    const double timeout_s = entry_.timeout_ms / 1000.0;
    const ReplyDeadline patience(
        clock_, kUnitBacklogPatience * timeout_s, kUnitBacklogPatience * timeout);
    ReplyDeadline quiet(clock_, timeout_s, timeout);
    while (!quiet.Passed() && !patience.Passed()) {
      std::vector<hil::MaintenanceResponse> responses;
      if (ReadInto(std::min(quiet.WaitLeft(), patience.WaitLeft()), &responses) > 0) {
        quiet.Restart();
      }
      for (const hil::MaintenanceResponse& response : responses) {
        // Responses to other requests (answers that came after their request gave up) are stale.
        if (response.command != command ||
            std::find(sequences.begin(), sequences.end(), response.sequence) == sequences.end()) {
          continue;
        }
        if (response.result != fm::ResultCode::kAck) {
          Fail(Kind::kRefused,
               command_text,
               ResponseText(response),
               hil::ResultCodeName(response.result));
        }
        return response;
      }
    }
  }
  Fail(Kind::kNoReply,
       command_text,
       "",
       fmt::format("{} attempts of {} ms wall each", kUnitRequestAttempts, timeout.count()));
}

hil::IdentifyInfo UnitLink::Identify() {
  const hil::MaintenanceResponse response = Transact(
      "IDENTIFY", fm::MaintenanceCommand::kIdentify, [this] { return client_.Identify(); });
  hil::IdentifyInfo info{};
  try {
    info = hil::ParseIdentify(response);
  } catch (const hil::ProtocolError& e) {
    Fail(Kind::kBadReply, "IDENTIFY", ResponseText(response), e.what());
  }
  if (info.unit_kind != entry_.kind) {
    Fail(Kind::kWrongIdentity,
         "IDENTIFY",
         ResponseText(response),
         fmt::format("the station holds an {} unit on this port, the unit says kind {}",
                     common::UnitKindName(entry_.kind),
                     static_cast<int>(info.unit_kind)));
  }
  return info;
}

void UnitLink::SetTag(uint8_t tag) {
  Transact(fmt::format("SET_TAG {}", tag), fm::MaintenanceCommand::kSetTag, [this, tag] {
    return client_.SetTag(tag);
  });
}

void UnitLink::SetImuMode(fm::ImuCompensationMode mode) {
  Transact(fmt::format("SET_MODE {}", static_cast<int>(mode)),
           fm::MaintenanceCommand::kSetMode,
           [this, mode] { return client_.SetImuMode(mode); });
}

void UnitLink::SetAdsMode(fm::AdsCompensationMode mode) {
  Transact(fmt::format("SET_MODE {}", static_cast<int>(mode)),
           fm::MaintenanceCommand::kSetMode,
           [this, mode] { return client_.SetAdsMode(mode); });
}

void UnitLink::WriteBlock(uint8_t block_id, std::span<const int16_t> words) {
  Transact(fmt::format("WRITE_BLOCK {} ({} words)", block_id, words.size()),
           fm::MaintenanceCommand::kWriteBlock,
           [this, block_id, words] { return client_.WriteBlock(block_id, words); });
}

std::vector<int16_t> UnitLink::ReadBlock(uint8_t block_id) {
  const std::string text = fmt::format("READ_BLOCK {}", block_id);
  const hil::MaintenanceResponse response =
      Transact(text, fm::MaintenanceCommand::kReadBlock, [this, block_id] {
        return client_.ReadBlock(block_id);
      });
  try {
    hil::BlockReadback readback = hil::ParseReadBlock(response);
    if (readback.block_id != block_id) {
      Fail(Kind::kBadReply,
           text,
           ResponseText(response),
           fmt::format("answers block {}", readback.block_id));
    }
    return std::move(readback.words);
  } catch (const hil::ProtocolError& e) {
    Fail(Kind::kBadReply, text, ResponseText(response), e.what());
  }
}

hil::CommitInfo UnitLink::Commit() {
  const hil::MaintenanceResponse response =
      Transact("COMMIT", fm::MaintenanceCommand::kCommit, [this] { return client_.Commit(); });
  try {
    return hil::ParseCommit(response);
  } catch (const hil::ProtocolError& e) {
    Fail(Kind::kBadReply, "COMMIT", ResponseText(response), e.what());
  }
}

hil::UnitCounters UnitLink::ReadCounters() {
  const hil::MaintenanceResponse response = Transact("READ_COUNTERS",
                                                     fm::MaintenanceCommand::kReadCounters,
                                                     [this] { return client_.ReadCounters(); });
  try {
    return hil::ParseCounters(response);
  } catch (const hil::ProtocolError& e) {
    Fail(Kind::kBadReply, "READ_COUNTERS", ResponseText(response), e.what());
  }
}

std::vector<ReceivedPacket> UnitLink::Poll(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    // With packets in hand only what is already waiting is taken; otherwise wait for the first.
    const std::chrono::milliseconds wait = queue_.empty() ? std::max(left, kDrainWait) : kDrainWait;
    if (ReadInto(wait, nullptr) == kReadChunkBytes) continue;  // a full chunk: more is waiting
    if (!queue_.empty() || left <= kDrainWait) break;
  }
  std::vector<ReceivedPacket> out;
  out.swap(queue_);
  return out;
}

}  // namespace adahrs::hil
