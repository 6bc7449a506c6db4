// How many descriptors hold a pseudo-terminal's slave device open, other than the rig's own: read
// from /proc/<pid>/fd of every process (each entry a link to the file it has open). The lockstep
// host recounts a port's clients this way whenever inotify says one opened or closed it: counting
// the events alone goes wrong when the kernel merges two identical events not yet read (two opens
// back to back arrive as one, and the later close then leaves the port counted as closed).
// The kernel reports an open before the new descriptor is in the process's table, a close after it
// left: read on a close's event, the count is exact; on an open's, it may miss the opener.
// Left out: clients of another user, whose /proc entries are not readable (the rig and its
// clients run as one user); descriptors passed between processes without a new open; a client
// that opens the port in the instant another closes it, missed by the close's count until its
// own close.
#pragma once

#include <optional>
#include <string>

namespace adahrs::rig_sim {

/// Descriptors of any process that resolve to `device_path`, except `own_fd` of this process;
/// nullopt when /proc cannot be read (the caller keeps counting events then).
std::optional<int> CountPtyClients(const std::string& device_path, int own_fd);

}  // namespace adahrs::rig_sim
