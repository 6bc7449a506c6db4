// Helpers shared by the libFuzzer targets (tests/fuzz/*_fuzz.cc, README.md "Fuzzing"): the
// parsers that read files get each input as a file in a scratch run directory of this process.
// Each target catches only the refusal its parser documents; anything else escapes to libFuzzer
// (an uncaught exception aborts and is reported like a crash). Left out: multi-file inputs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace adahrs::fuzz {

/// A directory of this process under TMPDIR (or /tmp), created on first use, kept for the run.
const std::filesystem::path& ScratchDir();

/// Writes `size` bytes of `data` to ScratchDir()/`name` (replacing it) and returns its path.
std::filesystem::path WriteScratchFile(std::string_view name, const uint8_t* data, size_t size);

/// Copies `source` to ScratchDir()/`name` (replacing it).
void CopyToScratch(const std::filesystem::path& source, std::string_view name);

}  // namespace adahrs::fuzz
