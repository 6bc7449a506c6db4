// A calibration run of one simulated ADS unit in process: the unit (sensor_sim::AdsUnit: the
// pressure bridges with their die temperatures and hysteresis, the ADS1254, the OAT divider) is
// driven through a sequence's execution plan (ExpandSequence) — chamber set points, the air data
// test set's altitude and airspeed — and every packet is handed to a sink as the executor records
// it (docs/recording-format.md): TAG = the step's TAG while acquiring, 0 for the second of packets
// logged while the test set settles (WaitAdtsStable); the reference columns are the applied
// pressures (an exact test set), the chamber column the commanded air temperature; each column at
// the resolution ads.csv writes it, so the rows equal those a reader gets back from the recording.
// Time: 100 frames/s. The chamber air reaches its set point at once and the soak runs frame by
// frame without logging (the die's thermal lag is simulated); the test set moves the pressures as
// monotone jumps (the bridges' hysteresis is rate independent, so the branches are the same).
// `AdsRunRecording` collects the rows into an in-memory hil::Recording of one unit, the input
// SelectAdsCalibrationPoints reads from disk.
// Left out: interlock checks, the chamber's own ramp, the test set's slew and uncertainty, packet
// loss, thermal profile steps (an ADS sequence has none).
#pragma once

#include <cstdint>
#include <functional>

#include "calib/sequence/sequence.h"
#include "hil/recording/recording_reader.h"
#include "sensor_sim/ads_unit.h"

namespace adahrs::proving {

struct AdsRunSimulatorOptions {
  double initial_air_temp_c = 25.0;
  double settle_s = 1.0;  ///< untagged packets logged per WaitAdtsStable
};

using AdsRowSink = std::function<void(const hil::AdsRecordRow&)>;

class AdsRunSimulator {
 public:
  /// Powers the unit on in the initial air, its noise seeded with `noise_seed`.
  AdsRunSimulator(const sensor_sim::AdsUnitParams& params,
                  uint64_t noise_seed,
                  AdsRunSimulatorOptions options = {});

  /// Runs `sequence` (its plan expanded against the default limits; SequenceError if invalid),
  /// handing every logged packet to `sink` in time order.
  void Run(const calib::Sequence& sequence, const AdsRowSink& sink);

 private:
  void Frames(int64_t n, int step, uint8_t tag, const AdsRowSink* sink);

  sensor_sim::AdsUnitParams params_;
  sensor_sim::AdsUnit unit_;
  AdsRunSimulatorOptions options_;
  sensor_sim::AdsStimulus stimulus_;
  double t_s_ = 0.0;
  uint32_t seq_ = 0;
};

/// The run of `sequence` on a unit with `params` as a recording in memory: meta.json's units (one
/// ADS), sequence name and no rejected interval, and the ads.csv rows.
hil::Recording AdsRunRecording(const calib::Sequence& sequence,
                               const sensor_sim::AdsUnitParams& params,
                               uint64_t noise_seed,
                               AdsRunSimulatorOptions options = {});

}  // namespace adahrs::proving
