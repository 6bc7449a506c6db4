// A whole text compressed as one gzip member (RFC 1952, libdeflate), for files kept compressed
// beside others (an external strategy's request and reply); zcat, Python's gzip and zlib read it.
#pragma once

#include <string>
#include <string_view>

namespace adahrs::hil {

/// `text` as one gzip member at deflate `level` (1...12); throws std::runtime_error when
/// libdeflate cannot allocate its compressor.
std::string GzipBytes(std::string_view text, int level = 6);

}  // namespace adahrs::hil
