// Untrusted bytes made safe to quote in a message (a file's cell or line, an instrument's reply, a
// JSON key): a terminal shows them as written, with nothing it would act on. CR, LF and TAB become
// \r, \n, \t; the backslash \\; other control bytes (C0, DEL, C1) and bytes that are not UTF-8
// become \xNN. Printable ASCII and well-formed UTF-8 (°, …) are kept. Left out: bidirectional and
// zero-width code points, which are printable by this rule.
#pragma once

#include <string>
#include <string_view>

namespace adahrs::common {

/// `bytes` with every non-printable byte escaped (above); idempotent only on printable text.
std::string PrintableText(std::string_view bytes);

/// A whole message for a terminal: as PrintableText, except that LF stays a line break (messages
/// that list one problem per line) and a backslash stays one (so values PrintableText quoted are
/// not escaped twice). For the last step before stderr, not for quoting a value.
std::string PrintableMessage(std::string_view message);

}  // namespace adahrs::common
