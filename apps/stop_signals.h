// How a long command (run, campaign, demo) is stopped: Ctrl-C (SIGINT), `kill` (SIGTERM) and a
// closed terminal session (SIGHUP) all stop it the same safe way. The handler only records the
// signal and sets the flag the executor and the campaign poll (they leave the instruments safe
// and the run resumable); the command then exits with 128 + the signal's number. SA_RESTART: a
// serial read in progress goes on, the flag is seen at the next poll.
#pragma once

#include <atomic>

namespace adahrs::apps {

/// Installs the handlers; returns the flag they set.
const std::atomic<bool>& InstallStopSignals();

/// The stop signal received last; SIGINT if none was (a stop requested otherwise).
int StopSignal();

/// "SIGINT", "SIGTERM", "SIGHUP", or "a signal".
const char* StopSignalName();

/// 128 + StopSignal(): the exit status of a stopped command.
int StopExitStatus();

}  // namespace adahrs::apps
