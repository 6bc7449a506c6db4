// How many simulated units a statistical test draws. Under AddressSanitizer and
// UndefinedBehaviorSanitizer (scripts/test --sanitize) the code runs several times slower; that
// pass looks for memory and undefined-behaviour errors on the same code paths, so the longest
// statistical tests draw fewer units there and the release pass holds their statistics.
#pragma once

namespace adahrs::testing {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif

// `release` units in the release build, `sanitized` under the sanitizers.
constexpr int Units(int release, int sanitized) { return kSanitized ? sanitized : release; }

}  // namespace adahrs::testing
