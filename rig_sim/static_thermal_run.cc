#include "rig_sim/static_thermal_run.h"

#include <cmath>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "common/gravity.h"
#include "common/random.h"
#include "common/units.h"
#include "hil/recording/recording_writer.h"
#include "hil/utc_time.h"
#include "rig_sim/fixture_orientation.h"
#include "sensor_sim/ads_unit.h"
#include "sensor_sim/imu_unit.h"

namespace adahrs::rig_sim {
namespace {

constexpr double kFramePeriod_s = 0.01;

void WriteTruth(const std::filesystem::path& dir,
                const std::string& serial,
                const char* kind,
                uint64_t seed,
                sensor_sim::ModelProfile profile,
                const nlohmann::json& params) {
  std::filesystem::create_directories(dir);
  std::ofstream out(dir / (serial + ".json"));
  out << nlohmann::json{{"serial", serial},
                        {"kind", kind},
                        {"seed", seed},
                        {"model_profile", sensor_sim::ToString(profile)},
                        {"params", params}}
             .dump(2)
      << "\n";
  if (!out) throw std::runtime_error((dir / (serial + ".json")).string() + ": write failed");
}

// The sequence counter a unit would put in this frame's packet: the unit protocol's counter is one
// byte and wraps 255 → 0 (docs/unit-protocol.md), so recordings made here read like real ones.
uint32_t UnitSequence(uint64_t frame) { return static_cast<uint8_t>(frame); }

// The programmed set point walks from `from_c` toward the step's target at its ramp rate.
double SetPoint(double from_c, const ThermalProfileStep& step, double t_in_step_s) {
  const double span_c = step.target_c - from_c;
  const double moved_c = step.ramp_c_per_min / 60.0 * t_in_step_s;
  return std::abs(span_c) <= moved_c ? step.target_c : from_c + std::copysign(moved_c, span_c);
}

// The profile as a sequence of the sequence language (docs/sequences.md): a target_temperature
// step per profile step. The language has no ramp on a target step (the chamber ramps at its own
// rate), so the simulated ramps go beside it in meta.json.
nlohmann::json ProfileSequence(const StaticThermalRunConfig& config) {
  nlohmann::json steps = nlohmann::json::array();
  for (size_t i = 0; i < config.steps.size(); ++i) {
    const auto& s = config.steps[i];
    steps.push_back({{"kind", "target_temperature"},
                     {"tag", i + 1},
                     {"target_c", s.target_c},
                     {"band_c", config.soak_band_c},
                     {"soak_s", s.soak_s}});
  }
  return {{"format_version", 1},
          {"name", "static_thermal"},
          {"description",
           fmt::format("adahrs simulate static-thermal: units static in orientation "
                       "{}, the chamber through {} set points",
                       config.orientation,
                       config.steps.size())},
          {"unit_kind", config.imu_units > 0 ? "imu" : "ads"},
          {"steps", steps}};
}

// meta.json as the executor writes it (docs/recording-format.md), so fit, records and report take
// the simulator's recordings as they take a rig's, plus what only a simulation knows.
hil::RecordingMeta RunMeta(const StaticThermalRunConfig& config,
                           const std::filesystem::path& run_dir,
                           double g_local_mps2,
                           std::vector<hil::RecordingUnit> units) {
  nlohmann::json ramps = nlohmann::json::array();
  for (const auto& s : config.steps) ramps.push_back(s.ramp_c_per_min);
  const std::string started_utc = hil::UtcNowIso8601();
  const std::filesystem::path name =
      std::filesystem::absolute(run_dir).lexically_normal().filename();
  hil::RecordingMeta m;
  m.run_id = (name.empty() ? std::string("static-thermal") : name.string()) + "-" + started_utc;
  m.started_utc = started_utc;
  m.status = "running";
  m.station = nlohmann::json{{"name", "simulated static thermal bench"},
                             {"latitude_deg", config.latitude_deg},
                             {"height_m", config.height_m},
                             {"local_gravity_mps2", g_local_mps2},
                             {"time_scale", 0}};
  m.sequence = ProfileSequence(config);
  m.sequence_file = "(adahrs simulate static-thermal)";
  m.time_base = "seconds since the batch was powered on";
  m.sample_rate_hz = 1.0 / kFramePeriod_s;
  m.local_gravity_mps2 = g_local_mps2;
  m.units = std::move(units);
  m.has_units = true;
  m.instruments.emplace();
  m.has_rejected_intervals = true;
  m.extra = {{"orientation", config.orientation},
             {"model_profile", sensor_sim::ToString(config.profile)},
             {"simulated_chamber_ramps_c_per_min", ramps},
             {"log_every", config.log_every}};
  return m;
}

hil::RecordingUnit RecordedUnit(const std::string& serial, const char* kind, int index) {
  hil::RecordingUnit u;
  u.role = fmt::format("{}{}", kind, index + 1);
  u.kind = common::ParseUnitKind(kind);
  u.serial = serial;
  u.serial_number = index + 1;
  u.firmware = "simulated";
  u.slot = index + 1;
  u.constants_version = 0;
  u.mode = 0;
  return u;
}

void CheckConfig(const StaticThermalRunConfig& config) {
  if (config.imu_units < 0 || config.imu_units > 4) {
    throw std::invalid_argument(fmt::format("imu_units {} not in 0..4", config.imu_units));
  }
  if (config.ads_units < 0 || config.ads_units > 4) {
    throw std::invalid_argument(fmt::format("ads_units {} not in 0..4", config.ads_units));
  }
  if (config.steps.empty()) throw std::invalid_argument("the thermal profile has no steps");
  if (config.log_every < 1) throw std::invalid_argument("log_every must be at least 1");
}

// The batch on the bench: its units, drawn from the run's seed with their truth files written,
// their stimulus (static in the fixture, at the set pressures) and the rows they log.
class StaticBatch {
 public:
  StaticBatch(const StaticThermalRunConfig& config,
              const std::filesystem::path& run_dir,
              const Eigen::Vector3d& f_B_g) {
    Draw<sensor_sim::ImuUnitParams>(config, run_dir, "imu", "IMU", config.imu_units, 1000, imus_);
    Draw<sensor_sim::AdsUnitParams>(config, run_dir, "ads", "ADS", config.ads_units, 2000, adss_);
    imu_in_.f_B_g = f_B_g;
    ads_in_.ps_pa = config.ads_ps_pa;
    ads_in_.qc_pa = config.ads_qc_pa;
    imu_row_.orientation = config.orientation;
    ads_row_.ps_ref_pa = config.ads_ps_pa;
    ads_row_.qc_ref_pa = config.ads_qc_pa;
  }

  /// meta.json's "units".
  const std::vector<hil::RecordingUnit>& units() const { return units_; }

  /// Steps every unit one frame in the chamber air `air_c`; writes their rows when `log`.
  void Frame(double air_c, uint64_t frame, size_t step, bool log, hil::RecordingWriter& writer) {
    const double t_s = static_cast<double>(frame) * kFramePeriod_s;
    imu_in_.air_temp_c = air_c;
    ads_in_.air_temp_c = air_c;
    ads_in_.oat_c = air_c;
    for (sensor_sim::ImuUnit& imu : imus_) {
      const sensor_sim::ImuRawFrame raw = imu.Step(imu_in_);
      if (!log) continue;
      Stamp(imu_row_, imu.params().serial, t_s, frame, step, air_c);
      for (int ch = 0; ch < 6; ++ch) {
        imu_row_.accel_ticks[2 * ch] = raw.accel[ch].t1_cnt;
        imu_row_.accel_ticks[2 * ch + 1] = raw.accel[ch].t2_cnt;
      }
      imu_row_.gyro_cnt = raw.gyro_cnt;
      imu_row_.temp_cnt = raw.temp_cnt;
      writer.Append(imu_row_);
    }
    for (sensor_sim::AdsUnit& ads : adss_) {
      const sensor_sim::AdsRawFrame raw = ads.Step(ads_in_);
      if (!log) continue;
      Stamp(ads_row_, ads.params().serial, t_s, frame, step, air_c);
      ads_row_.ps_cnt = raw.ps_cnt;
      ads_row_.pt_cnt = raw.pt_cnt;
      ads_row_.ps_temp_cnt = raw.ps_temp_cnt;
      ads_row_.pt_temp_cnt = raw.pt_temp_cnt;
      ads_row_.oat_cnt = raw.oat_cnt;
      writer.Append(ads_row_);
    }
  }

 private:
  // Draws `count` units of one kind (serials PREFIX-0001…, each seed from the batch seed's stream
  // `first_stream` + index), writes their truth files and lists them in units_.
  template <typename Params, typename Unit>
  void Draw(const StaticThermalRunConfig& config,
            const std::filesystem::path& run_dir,
            const char* kind,
            const char* prefix,
            int count,
            uint64_t first_stream,
            std::vector<Unit>& units) {
    for (int i = 0; i < count; ++i) {
      const std::string serial = fmt::format("{}-{:04d}", prefix, i + 1);
      const uint64_t seed = common::Rng::Derive(config.seed, first_stream + i);
      const auto params = Params::Draw(serial, seed, config.profile);
      WriteTruth(run_dir / "truth", serial, kind, seed, config.profile, params.ToJson());
      units.emplace_back(params, common::Rng::Derive(seed, 1), config.start_c);
      units_.push_back(RecordedUnit(serial, kind, i));
    }
  }

  // The columns every row has: time, unit, packet counter, profile step and chamber air.
  template <typename Row>
  static void Stamp(
      Row& row, const std::string& serial, double t_s, uint64_t frame, size_t step, double air_c) {
    row.t_s = t_s;
    row.unit = serial;
    row.seq = UnitSequence(frame);
    row.frame = static_cast<int64_t>(frame);
    row.step = static_cast<int>(step);
    row.tag = static_cast<uint8_t>(step + 1);
    row.chamber_c = air_c;
  }

  std::vector<sensor_sim::ImuUnit> imus_;
  std::vector<sensor_sim::AdsUnit> adss_;
  std::vector<hil::RecordingUnit> units_;
  sensor_sim::ImuStimulus imu_in_;
  sensor_sim::AdsStimulus ads_in_;
  hil::ImuRecordRow imu_row_;
  hil::AdsRecordRow ads_row_;
};

}  // namespace

StaticThermalRunConfig StaticThermalRunConfig::Demo() {
  StaticThermalRunConfig c;
  c.log_every = 10;
  c.steps = {{-20.0, 2.0, 1200.0}, {65.0, 2.0, 1200.0}, {25.0, 2.0, 600.0}};
  return c;
}

StaticThermalRunSummary RunStaticThermal(const StaticThermalRunConfig& config,
                                         const std::filesystem::path& run_dir,
                                         const std::function<void(int, double)>& on_step) {
  CheckConfig(config);
  const double g_local_mps2 = common::NormalGravityMps2(config.latitude_deg, config.height_m);
  const Eigen::Vector3d f_B_g =
      UpAxis_B(config.orientation) * (g_local_mps2 / common::kStandardGravity_mps2);
  StaticBatch batch(config, run_dir, f_B_g);
  hil::RecordingWriter writer(run_dir, config.storage);
  hil::RecordingMeta meta = RunMeta(config, run_dir, g_local_mps2, batch.units());
  writer.WriteMeta(meta);

  ChamberAir chamber(config.chamber, config.start_c);
  double from_c = config.start_c;
  uint64_t frame = 0;
  for (size_t step = 0; step < config.steps.size(); ++step) {
    const ThermalProfileStep& s = config.steps[step];
    double t_in_step_s = 0.0, soaked_s = 0.0;
    while (soaked_s < s.soak_s) {
      const double air_c = chamber.Step(SetPoint(from_c, s, t_in_step_s), kFramePeriod_s);
      t_in_step_s += kFramePeriod_s;
      if (std::abs(air_c - s.target_c) <= config.soak_band_c) soaked_s += kFramePeriod_s;
      ++frame;
      batch.Frame(air_c, frame, step, frame % static_cast<uint64_t>(config.log_every) == 0, writer);
    }
    from_c = s.target_c;
    writer.Flush(true);
    if (on_step) on_step(static_cast<int>(step), static_cast<double>(frame) * kFramePeriod_s);
  }
  meta.status = "complete";
  writer.WriteMeta(meta);
  StaticThermalRunSummary summary;
  summary.frames = frame;
  summary.duration_s = static_cast<double>(frame) * kFramePeriod_s;
  summary.imu_rows = writer.imu_rows();
  summary.ads_rows = writer.ads_rows();
  return summary;
}

}  // namespace adahrs::rig_sim
