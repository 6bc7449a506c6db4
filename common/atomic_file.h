// Writing a whole file so that a reader, a crash or a power loss sees either the old file or the
// new one complete, never a part: the text goes to `<name>.tmp` in the same directory, is flushed
// and fsync'd, and is renamed over `<name>`; the directory is then fsync'd so the rename survives
// a power loss. On any failure the temporary is removed and the old file is left as it was.
// Left out: two writers of one path at once (they share the temporary's name); the new file's
// permissions are 0666 less the umask, not the old file's.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string_view>

namespace adahrs::common {

/// A file that could not be written; the message names the file and the step that failed.
class AtomicWriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Replaces `path` with `text` (above). Throws AtomicWriteError naming `path` on failure.
void WriteFileAtomically(const std::filesystem::path& path, std::string_view text);

}  // namespace adahrs::common
