#include "calib/constants/recording_checksum.h"

#include <array>
#include <fstream>
#include <memory>
#include <stdexcept>

#include <openssl/evp.h>

#include "hil/recording/recording_files.h"
#include "hil/recording/recording_format.h"

namespace adahrs::calib {

std::string RecordingSha256(const std::filesystem::path& run_dir) {
  const std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(),
                                                                    &EVP_MD_CTX_free);
  if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1) {
    throw std::runtime_error("RecordingSha256: OpenSSL SHA-256 initialisation failed");
  }
  for (const std::filesystem::path& path : {run_dir / hil::kMetaJsonName,
                                            hil::StoredCsvPath(run_dir, hil::kImuCsvName),
                                            hil::StoredCsvPath(run_dir, hil::kAdsCsvName)}) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path.string() + ": cannot open for the recording checksum");
    std::array<char, 1 << 16> buffer;
    while (in) {
      in.read(buffer.data(), buffer.size());
      if (in.gcount() > 0 &&
          EVP_DigestUpdate(ctx.get(), buffer.data(), static_cast<size_t>(in.gcount())) != 1) {
        throw std::runtime_error(path.string() + ": SHA-256 update failed");
      }
    }
    if (in.bad()) throw std::runtime_error(path.string() + ": read error");
  }
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int length = 0;
  if (EVP_DigestFinal_ex(ctx.get(), digest.data(), &length) != 1) {
    throw std::runtime_error("RecordingSha256: SHA-256 finalisation failed");
  }
  static constexpr char kHex[] = "0123456789abcdef";
  std::string hex;
  for (unsigned int i = 0; i < length; ++i) {
    hex += kHex[digest[i] >> 4];
    hex += kHex[digest[i] & 0xF];
  }
  return hex;
}

}  // namespace adahrs::calib
