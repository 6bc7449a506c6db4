#include "hil/rig_port_counts.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <system_error>
#include <thread>

#include <fmt/format.h>

namespace adahrs::hil {
namespace {

constexpr char kMagic[8] = {'A', 'D', 'A', 'H', 'R', 'S', 'P', 'T'};
constexpr uint32_t kVersion = 1;
constexpr size_t kHeaderBytes = 64;
constexpr size_t kSlotBytes = 128;
constexpr size_t kPathBytes = 96;
constexpr size_t kProducedOffset = 96;
constexpr size_t kConsumedOffset = 104;
constexpr size_t kReaderOffset = 112;
constexpr size_t kAckOffset = 120;
constexpr uint64_t kCounterModulo = 256;

std::atomic_ref<uint64_t> Word(char* slot, size_t offset) {
  return std::atomic_ref<uint64_t>(*reinterpret_cast<uint64_t*>(slot + offset));
}

char* Slot(void* map, size_t slot) {
  return static_cast<char*>(map) + kHeaderBytes + slot * kSlotBytes;
}

}  // namespace

std::filesystem::path PortCountsPath(const std::filesystem::path& clock_file) {
  std::filesystem::path path = clock_file;
  path += ".ports";
  return path;
}

std::optional<uint64_t> PacketIndexBelow(uint32_t seq, uint64_t produced) {
  const uint64_t residue = seq % kCounterModulo;
  if (produced <= residue) return std::nullopt;
  const uint64_t last = produced - 1;
  return last - ((last - residue) % kCounterModulo);
}

RigPortCountsWriter::RigPortCountsWriter(const std::filesystem::path& path,
                                         const std::vector<std::string>& ports) {
  for (const std::string& port : ports) {
    if (port.size() >= kPathBytes) {
      throw std::invalid_argument(fmt::format(
          "{}: port path {} is longer than {} bytes", path.string(), port, kPathBytes - 1));
    }
  }
  map_ = SharedFileMap::Create(path, kHeaderBytes + ports.size() * kSlotBytes);
  char* bytes = map_.data();
  const auto slots = static_cast<uint32_t>(ports.size());
  std::memcpy(bytes + 8, &kVersion, sizeof kVersion);
  std::memcpy(bytes + 12, &slots, sizeof slots);
  for (size_t i = 0; i < ports.size(); ++i)
    std::memcpy(Slot(bytes, i), ports[i].data(), ports[i].size());
  // The magic last: a reader never accepts a half-written file.
  std::atomic_thread_fence(std::memory_order_release);
  std::memcpy(bytes, kMagic, sizeof kMagic);
}

void RigPortCountsWriter::PublishProduced(size_t slot, uint64_t produced) {
  Word(Slot(map_.data(), slot), kProducedOffset).store(produced, std::memory_order_release);
}

RigPortCountsWriter::Reader RigPortCountsWriter::ReaderOf(size_t slot) const {
  char* s = Slot(map_.data(), slot);
  Reader reader;
  reader.token = Word(s, kReaderOffset).load(std::memory_order_acquire);
  reader.consumed = Word(s, kConsumedOffset).load(std::memory_order_acquire);
  return reader;
}

void RigPortCountsWriter::Acknowledge(size_t slot, uint64_t token, uint64_t start) {
  char* s = Slot(map_.data(), slot);
  Word(s, kConsumedOffset).store(start, std::memory_order_release);
  Word(s, kAckOffset).store(token, std::memory_order_release);
}

void RigPortCountsWriter::Release(size_t slot, uint64_t token) {
  uint64_t expected = token;
  Word(Slot(map_.data(), slot), kReaderOffset)
      .compare_exchange_strong(expected, 0, std::memory_order_acq_rel);
}

std::unique_ptr<RigPortCounter> RigPortCounter::Open(const std::filesystem::path& clock_file,
                                                     const std::string& port_path) {
  const std::filesystem::path path = PortCountsPath(clock_file);
  std::optional<SharedFileMap> map = SharedFileMap::Open(path, /*writable=*/true);
  if (!map) return nullptr;
  uint32_t version = 0, slots = 0;
  if (map->size() >= kHeaderBytes) {
    std::memcpy(&version, map->data() + 8, sizeof version);
    std::memcpy(&slots, map->data() + 12, sizeof slots);
  }
  if (map->size() < kHeaderBytes || std::memcmp(map->data(), kMagic, sizeof kMagic) != 0 ||
      version != kVersion || kHeaderBytes + slots * kSlotBytes > map->size()) {
    throw std::runtime_error(fmt::format(
        "rig port counts {}: not an ADAHRSPT version {} file", path.string(), kVersion));
  }
  // A station may name the port by a link to it (the rig's ports/<role>).
  std::error_code ec;
  const std::filesystem::path resolved = std::filesystem::canonical(port_path, ec);
  const std::string wanted = ec ? port_path : resolved.string();
  for (uint32_t i = 0; i < slots; ++i) {
    char* slot = Slot(map->data(), i);
    if (::strnlen(slot, kPathBytes) == wanted.size() &&
        std::memcmp(slot, wanted.data(), wanted.size()) == 0) {
      return std::unique_ptr<RigPortCounter>(new RigPortCounter(std::move(*map), slot));
    }
  }
  return nullptr;
}

RigPortCounter::~RigPortCounter() { Detach(); }

uint64_t RigPortCounter::Produced() const {
  return Word(slot_, kProducedOffset).load(std::memory_order_acquire);
}

bool RigPortCounter::Attach(double wall_s) {
  Detach();
  // A token of this process and this attachment, so that a counter of the same port closed
  // later does not release the slot another one claimed since, and each attachment is new.
  static std::atomic<uint64_t> attachments{0};
  token_ = (static_cast<uint64_t>(::getpid()) << 24) | (++attachments & 0xFFFFFFu);
  Word(slot_, kReaderOffset).store(token_, std::memory_order_release);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(wall_s);
  while (Word(slot_, kAckOffset).load(std::memory_order_acquire) != token_) {
    if (std::chrono::steady_clock::now() > deadline) {
      Detach();
      return false;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  return true;
}

uint64_t RigPortCounter::Consumed() const {
  return Word(slot_, kConsumedOffset).load(std::memory_order_acquire);
}

void RigPortCounter::Consume(uint64_t consumed) {
  if (attached()) Word(slot_, kConsumedOffset).store(consumed, std::memory_order_release);
}

bool RigPortCounter::attached() const {
  return token_ != 0 && Word(slot_, kReaderOffset).load(std::memory_order_acquire) == token_;
}

void RigPortCounter::Detach() {
  if (token_ == 0) return;
  uint64_t expected = token_;
  Word(slot_, kReaderOffset).compare_exchange_strong(expected, 0, std::memory_order_acq_rel);
  token_ = 0;
}

}  // namespace adahrs::hil
