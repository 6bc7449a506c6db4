// A file mapped shared into memory: how the lockstep rig and the pipeline on the same machine
// share its clock (rig_clock.h) and its port counts (rig_port_counts.h). Owns the mapping; the
// file's layout is its users'. Left out: files larger than the address space, remote files.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>

namespace adahrs::hil {

class SharedFileMap {
 public:
  SharedFileMap() = default;
  ~SharedFileMap();
  SharedFileMap(SharedFileMap&& other) noexcept;
  SharedFileMap& operator=(SharedFileMap&& other) noexcept;
  SharedFileMap(const SharedFileMap&) = delete;
  SharedFileMap& operator=(const SharedFileMap&) = delete;

  /// Creates (or truncates) `path` to `bytes` zero bytes and maps it read-write; throws
  /// std::system_error naming the path and what failed (create, size, map).
  static SharedFileMap Create(const std::filesystem::path& path, size_t bytes);
  /// Maps the whole of the existing file `path`, read-write or read-only; nullopt if it cannot be
  /// opened (errno says why). A file of 0 bytes gives an empty map; throws std::system_error naming
  /// the path if a larger one cannot be mapped.
  static std::optional<SharedFileMap> Open(const std::filesystem::path& path, bool writable);

  char* data() const { return data_; }
  size_t size() const { return size_; }

 private:
  SharedFileMap(char* data, size_t size) : data_(data), size_(size) {}
  char* data_ = nullptr;
  size_t size_ = 0;
};

}  // namespace adahrs::hil
