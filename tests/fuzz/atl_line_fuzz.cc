// Fuzzes the rate table's ATL line protocol (hil/codecs/atl_codec.h) with the rig's command
// table: server side, the framer on the byte stream, ParseAtlLine and the error reply of every
// line; client side, the reply reader on the same bytes. Never throws; nothing is caught.
#include <cstddef>
#include <cstdint>
#include <span>

#include "hil/codecs/atl_codec.h"

namespace hil = adahrs::hil;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const hil::AtlCommandTable table = hil::AtlCommandTable::Load(ADAHRS_ATL_TABLE);
  hil::AtlLineFramer framer(table.framing().max_line_chars);
  for (size_t i = 0; i < size; ++i) {
    auto line = framer.Push(data[i]);
    if (!line) continue;
    const hil::AtlParsed parsed = hil::ParseAtlLine(table, *line);
    if (parsed.status != hil::AtlParseStatus::kOk) {
      (void)hil::FormatAtlError(hil::AtlErrorTemplateFor(table, parsed.status), parsed, line->text);
    }
  }
  hil::AtlReplyReader replies(table.framing());
  (void)replies.Push(std::span<const uint8_t>(data, size));
  return 0;
}
