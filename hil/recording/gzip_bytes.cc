#include "hil/recording/gzip_bytes.h"

#include <libdeflate.h>

#include <memory>
#include <stdexcept>

namespace adahrs::hil {

std::string GzipBytes(std::string_view text, int level) {
  const std::unique_ptr<libdeflate_compressor, decltype(&libdeflate_free_compressor)> compressor(
      libdeflate_alloc_compressor(level), &libdeflate_free_compressor);
  if (!compressor)
    throw std::runtime_error("libdeflate: no compressor at level " + std::to_string(level));
  std::string out(libdeflate_gzip_compress_bound(compressor.get(), text.size()), '\0');
  const size_t n =
      libdeflate_gzip_compress(compressor.get(), text.data(), text.size(), out.data(), out.size());
  if (n == 0) throw std::runtime_error("libdeflate: the compressed text did not fit its bound");
  out.resize(n);
  return out;
}

}  // namespace adahrs::hil
