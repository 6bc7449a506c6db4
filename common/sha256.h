// SHA-256 (FIPS 180-4) through OpenSSL's libcrypto, as 64 lowercase hex digits: of bytes, of
// files read in turn (one digest over their concatenation). The one place the house hashes what it
// certifies: recordings (constants provenance, records), specification files, records inputs.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace adahrs::common {

/// An incremental SHA-256. Errors (OpenSSL's, or a file that cannot be read) throw
/// std::runtime_error naming the file when there is one.
class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;

  void Update(std::string_view bytes);
  /// Appends every byte of `file`, read in 64 KiB blocks.
  void UpdateFile(const std::filesystem::path& file);
  /// The digest of everything appended; the hasher is spent afterwards.
  std::string HexDigest();

 private:
  struct Context;
  std::unique_ptr<Context> context_;
};

/// SHA-256 of `bytes`.
std::string Sha256Hex(std::string_view bytes);
/// SHA-256 of the bytes of `file`.
std::string FileSha256(const std::filesystem::path& file);

}  // namespace adahrs::common
