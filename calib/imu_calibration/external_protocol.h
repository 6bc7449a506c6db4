// The names and version of the external strategy protocol (docs/strategies-external.md): what
// the request's and the reply's "protocol" and "protocol_version" keys hold.
#pragma once

namespace adahrs::calib {

inline constexpr int kExternalProtocolVersion = 1;
inline constexpr const char* kExternalRequestName = "adahrs-strategy-request";
inline constexpr const char* kExternalReplyName = "adahrs-strategy-reply";

}  // namespace adahrs::calib
