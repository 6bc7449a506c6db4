// A recording against two re-simulations of its stimulus (`adahrs simulate replay`): one with the
// unit model the diagnosis started from, one with the augmented model it wrote. Per unit, channel
// and acquisition (the rows of one step and TAG ≠ 0, and for an IMU one table rate to 0.1 °/s:
// a gyro step's TAG spans all its rates), the mean output difference recorded −
// replayed, in the channel's physical unit; per channel the RMS over acquisitions for either model
// and the RMS that the noise alone leaves (two independent means: the standard error of their
// difference from each acquisition's own row scatter). Held out when the recording is not one the
// diagnosis was fitted on (the acceptance run of the calibrated unit, say).
// Units: accelerometers in mg at the datasheet's 4 %/g of duty T1/T2, gyros in °/s at 20,971.52
// counts per °/s, bridges in Pa through the code-per-pascal slope of the recording's own
// acquisitions against the reference pressure (static for ps, impact for pt).
// Left out: rows of TAG 0 (not acquisition data), and acquisitions either run lacks.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace adahrs::diagnosis {

struct AcquisitionResidual {
  std::string label;      ///< "step 12 tag 3", "step 5 tag 6 at -25 dps"
  double base = 0.0;      ///< recorded − replayed with the base model, channel unit
  double model = 0.0;     ///< recorded − replayed with the augmented model
  double noise_se = 0.0;  ///< standard error of either difference from the rows' scatter
};

struct ChannelReplayFit {
  std::string channel;
  std::string unit;  ///< "mg", "deg/s" or "Pa"
  double rms_base = 0.0;
  double rms_model = 0.0;
  double rms_noise = 0.0;  ///< RMS of the acquisitions' standard errors: what noise alone leaves
  std::vector<AcquisitionResidual> acquisitions;
  nlohmann::json ToJson() const;
};

struct UnitReplayFit {
  std::string serial;
  std::vector<ChannelReplayFit> channels;
  nlohmann::json ToJson() const;
};

struct ReplayComparison {
  std::filesystem::path recording, base_replay, model_replay;
  bool held_out = false;  ///< the recording was not one the diagnosis fitted
  std::vector<UnitReplayFit> units;
  nlohmann::json ToJson() const;
};

/// Compares `recording` with its replays by the base and the augmented model. Units present in
/// all three are compared. Throws hil::RecordingError for an unreadable run and
/// std::runtime_error naming the replay when it shares no acquisition with the recording.
ReplayComparison CompareReplays(const std::filesystem::path& recording,
                                const std::filesystem::path& base_replay,
                                const std::filesystem::path& model_replay,
                                bool held_out);

/// Re-simulates run `run` with `unit_files` into the new directory `out` (the application hands in
/// rig_sim::ReplayRecording: the pipeline itself never simulates).
using ReplayFunction = std::function<void(const std::filesystem::path& run,
                                          const std::vector<std::filesystem::path>& unit_files,
                                          const std::filesystem::path& out)>;

/// Replays `run` with the base files into `work_dir`/base and with the augmented models into
/// `work_dir`/model (both replaced), and compares them with the recording.
ReplayComparison CheckByReplay(const std::filesystem::path& run,
                               const std::vector<std::filesystem::path>& base_files,
                               const std::vector<std::filesystem::path>& model_files,
                               const std::filesystem::path& work_dir,
                               bool held_out,
                               const ReplayFunction& replay);

}  // namespace adahrs::diagnosis
