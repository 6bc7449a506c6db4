// Fuzzes the Watlow 942 line codec (hil/codecs/watlow942_codec.h): the splitter on the byte
// stream, the decoder on every line and on the whole input. Never throws; nothing is caught.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hil/codecs/watlow942_codec.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  adahrs::hil::Watlow942LineSplitter splitter;
  for (size_t i = 0; i < size; ++i) {
    if (auto line = splitter.Feed(data[i])) (void)adahrs::hil::DecodeWatlow942Line(line->text);
  }
  (void)adahrs::hil::DecodeWatlow942Line(
      std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
