#include "proving/evaluation/ads_evaluation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

#include "calib/acceptance/ads_tolerance.h"
#include "common/air_data.h"
#include "common/atmosphere.h"
#include "firmware_model/constants_exporter.h"
#include "firmware_model/reference_compensator.h"
#include "firmware_model/unit_firmware.h"

namespace adahrs::proving {
namespace {

using firmware_model::AdsCompensationMode;

enum class PressureHistory { kNone, kRising, kFalling };
enum class ThermalHistory { kNone, kHeating, kCooling };
constexpr std::array<PressureHistory, 3> kPressureHistories = {
    PressureHistory::kNone, PressureHistory::kRising, PressureHistory::kFalling};
constexpr std::array<ThermalHistory, 3> kThermalHistories = {
    ThermalHistory::kNone, ThermalHistory::kHeating, ThermalHistory::kCooling};

// The true model as the evaluation runs it: converter and bridge noise off (the brief: noise
// off), the die at steady state at once (every grid point is a soak); every other effect, the
// hysteresis included, as drawn.
sensor_sim::AdsUnitParams Noiseless(sensor_sim::AdsUnitParams p) {
  p.static_bridge.effects.noise = false;
  p.pitot_bridge.effects.noise = false;
  p.adc.effects.noise = false;
  p.static_thermal.effects.lag = false;
  p.pitot_thermal.effects.lag = false;
  return p;
}

// Which input of the stimulus a quantity drives, and its true value at a grid value.
struct Quantity {
  const char* name;
  int output;                                 // compensated frame slot
  std::function<double(double)> pressure_pa;  // grid value -> applied pressure
  std::function<double(double)> tolerance;
  bool is_static;
};

sensor_sim::AdsStimulus Stimulus(const Quantity& q, double pressure_pa, double temp_c) {
  sensor_sim::AdsStimulus s;
  s.ps_pa = q.is_static ? pressure_pa : common::kIsaSeaLevelPressure_pa;
  s.qc_pa = q.is_static ? 0.0 : pressure_pa;
  s.air_temp_c = temp_c;
  s.oat_c = temp_c;
  return s;
}

// The unit's firmware over one history: the exported constants and the hysteresis operators'
// memory, fresh at the start (the unit powered through the whole history).
class Firmware {
 public:
  explicit Firmware(const firmware_model::AdsConstants& constants) : constants_(constants) {
    firmware_model::AdsHysteresisReset(&state_);
  }

  // Compensates the frame `unit` produces at `stimulus`; returns output `slot`.
  double Step(sensor_sim::AdsUnit& unit,
              const sensor_sim::AdsStimulus& stimulus,
              int slot,
              int* saturated) {
    const sensor_sim::AdsRawFrame f = unit.Step(stimulus);
    const firmware_model::AdsRawFrame raw{
        f.ps_cnt, f.pt_cnt, f.ps_temp_cnt, f.pt_temp_cnt, f.oat_cnt};
    firmware_model::DspEngine engine;
    firmware_model::AdsCompensatedFrame frame{};
    firmware_model::AdsCompensate(
        &engine, constants_, AdsCompensationMode::kSurface, raw, &state_, &frame);
    if (frame.flags != 0 && saturated != nullptr) ++*saturated;
    return firmware_model::AdsFrameToDouble(AdsCompensationMode::kSurface, frame)[slot];
  }

 private:
  const firmware_model::AdsConstants& constants_;
  firmware_model::AdsHysteresisState state_;
};

// Applies the thermal history at constant pressure `pressure_pa`, ending at `temp_c`; the
// firmware sees every step.
void ApplyThermalHistory(sensor_sim::AdsUnit& unit,
                         Firmware& firmware,
                         const Quantity& q,
                         ThermalHistory h,
                         double pressure_pa,
                         double temp_c) {
  if (h == ThermalHistory::kHeating) {
    firmware.Step(unit, Stimulus(q, pressure_pa, calib::kAdsMaxTempC), q.output, nullptr);
    firmware.Step(unit, Stimulus(q, pressure_pa, calib::kAdsMinTempC), q.output, nullptr);
  } else if (h == ThermalHistory::kCooling) {
    firmware.Step(unit, Stimulus(q, pressure_pa, calib::kAdsMinTempC), q.output, nullptr);
    firmware.Step(unit, Stimulus(q, pressure_pa, calib::kAdsMaxTempC), q.output, nullptr);
  }
  firmware.Step(unit, Stimulus(q, pressure_pa, temp_c), q.output, nullptr);
}

// Errors (compensated - true) at every grid value, for one temperature and one history pair.
std::vector<double> Sweep(const sensor_sim::AdsUnitParams& params,
                          const firmware_model::AdsConstants& constants,
                          const Quantity& q,
                          const std::vector<double>& values,
                          double temp_c,
                          PressureHistory ph,
                          ThermalHistory th,
                          int* saturated) {
  std::vector<double> errors(values.size());
  auto error_at = [&](sensor_sim::AdsUnit& unit, Firmware& firmware, size_t i) {
    errors[i] =
        firmware.Step(unit, Stimulus(q, q.pressure_pa(values[i]), temp_c), q.output, saturated) -
        values[i];
  };
  if (ph == PressureHistory::kNone) {
    for (size_t i = 0; i < values.size(); ++i) {
      sensor_sim::AdsUnit unit(params, 0, temp_c);
      Firmware firmware(constants);
      ApplyThermalHistory(unit, firmware, q, th, q.pressure_pa(values[i]), temp_c);
      error_at(unit, firmware, i);
    }
    return errors;
  }
  // Major loop: from one end of the envelope to the other, then back across the grid.
  const double p_first = q.pressure_pa(values.front());
  const double p_last = q.pressure_pa(values.back());
  const bool rising = ph == PressureHistory::kRising;
  const double p_low = std::min(p_first, p_last), p_high = std::max(p_first, p_last);
  sensor_sim::AdsUnit unit(params, 0, temp_c);
  Firmware firmware(constants);
  ApplyThermalHistory(unit, firmware, q, th, rising ? p_high : p_low, temp_c);
  firmware.Step(unit, Stimulus(q, rising ? p_low : p_high, temp_c), q.output, nullptr);
  std::vector<size_t> order(values.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const double pa = q.pressure_pa(values[a]), pb = q.pressure_pa(values[b]);
    return rising ? pa < pb : pa > pb;
  });
  for (size_t i : order) error_at(unit, firmware, i);
  return errors;
}

std::vector<double> Range(double from, double to, double step) {
  std::vector<double> out;
  const int n = static_cast<int>(std::floor((to - from) / step + 1e-9));
  for (int i = 0; i <= n; ++i) out.push_back(from + i * step);
  if (out.back() < to - 1e-9) out.push_back(to);
  return out;
}

int Severity(AdsVerdict v) {
  return v == AdsVerdict::kPass ? 0 : (v == AdsVerdict::kUnreachable ? 1 : 2);
}

AdsQuantityEvaluation Evaluate(const sensor_sim::AdsUnitParams& params,
                               const firmware_model::AdsConstants& constants,
                               const Quantity& q,
                               const std::vector<double>& values,
                               const std::vector<double>& temps_c,
                               const std::vector<calib::AdsTolerancePoint>& table,
                               bool static_surface) {
  AdsQuantityEvaluation out;
  out.quantity = q.name;
  for (double temp_c : temps_c) {
    std::vector<std::vector<double>> errors;  // [history][value]
    for (ThermalHistory th : kThermalHistories) {
      for (PressureHistory ph : kPressureHistories) {
        errors.push_back(
            Sweep(params, constants, q, values, temp_c, ph, th, &out.saturated_frames));
      }
    }
    for (size_t i = 0; i < values.size(); ++i) {
      AdsGridPoint g;
      g.value = values[i];
      g.temp_c = temp_c;
      g.tolerance = q.tolerance(values[i]);
      g.error_no_history = errors[0][i];
      double lo = errors[0][i], hi = errors[0][i];
      for (const std::vector<double>& e : errors) {
        lo = std::min(lo, e[i]);
        hi = std::max(hi, e[i]);
      }
      g.worst_with_history = std::max(std::abs(lo), std::abs(hi));
      g.loop_half_width = 0.5 * (hi - lo);
      g.verdict = g.worst_with_history <= g.tolerance                 ? AdsVerdict::kPass
                  : static_surface && g.loop_half_width > g.tolerance ? AdsVerdict::kUnreachable
                                                                      : AdsVerdict::kFail;
      out.worst_ratio_no_history =
          std::max(out.worst_ratio_no_history, std::abs(g.error_no_history) / g.tolerance);
      ++(g.verdict == AdsVerdict::kPass   ? out.pass
         : g.verdict == AdsVerdict::kFail ? out.fail
                                          : out.unreachable);
      out.grid.push_back(g);
    }
  }
  for (const calib::AdsTolerancePoint& t : table) {
    AdsTolerancePointResult r;
    r.at = t.at;
    r.tolerance = t.tolerance;
    for (const AdsGridPoint& g : out.grid) {
      if (std::abs(g.value - t.at) > 1e-6) continue;
      if (std::abs(g.error_no_history) >= r.worst_no_history) {
        r.worst_no_history = std::abs(g.error_no_history);
        r.worst_no_history_temp_c = g.temp_c;
      }
      r.worst_with_history = std::max(r.worst_with_history, g.worst_with_history);
      r.max_loop_half_width = std::max(r.max_loop_half_width, g.loop_half_width);
      if (Severity(g.verdict) > Severity(r.verdict)) r.verdict = g.verdict;
    }
    out.points.push_back(r);
  }
  return out;
}

nlohmann::json QuantityJson(const AdsQuantityEvaluation& q) {
  nlohmann::json points = nlohmann::json::array();
  for (const AdsTolerancePointResult& r : q.points) {
    points.push_back({{"at", r.at},
                      {"tolerance", r.tolerance},
                      {"worst_no_history", r.worst_no_history},
                      {"worst_no_history_temp_c", r.worst_no_history_temp_c},
                      {"worst_with_history", r.worst_with_history},
                      {"max_loop_half_width", r.max_loop_half_width},
                      {"verdict", ToString(r.verdict)}});
  }
  return {{"quantity", q.quantity},
          {"grid_points", q.grid.size()},
          {"pass", q.pass},
          {"fail", q.fail},
          {"unreachable", q.unreachable},
          {"worst_ratio_no_history", q.worst_ratio_no_history},
          {"saturated_frames", q.saturated_frames},
          {"tolerance_points", points}};
}

}  // namespace

const char* ToString(AdsVerdict verdict) {
  switch (verdict) {
    case AdsVerdict::kPass:
      return "pass";
    case AdsVerdict::kFail:
      return "fail";
    case AdsVerdict::kUnreachable:
      return "unreachable";
  }
  return "fail";
}

nlohmann::json AdsEvaluation::ToJson() const {
  return {{"altitude_ft", QuantityJson(altitude)}, {"airspeed_kt", QuantityJson(airspeed)}};
}

AdsEvaluation EvaluateAdsConstants(const firmware_model::AdsCalibrationConstants& constants,
                                   const sensor_sim::AdsUnitParams& truth,
                                   const AdsEvaluationOptions& options) {
  const sensor_sim::AdsUnitParams params = Noiseless(truth);
  const firmware_model::AdsConstants exported =
      firmware_model::ExportAdsConstants(constants).constants;
  const std::vector<double> temps_c =
      Range(calib::kAdsMinTempC, calib::kAdsMaxTempC, options.temp_step_c);
  const Quantity altitude{"altitude_ft",
                          0,
                          [](double ft) { return common::IsaStaticPressurePaFromFt(ft); },
                          [](double ft) { return calib::AltitudeToleranceFt(ft); },
                          true};
  const Quantity airspeed{"airspeed_kt",
                          1,
                          [](double kt) { return common::ImpactPressurePaFromKt(kt); },
                          [](double kt) { return calib::AirspeedToleranceKt(kt); },
                          false};
  AdsEvaluation out;
  out.altitude =
      Evaluate(params,
               exported,
               altitude,
               Range(calib::kAdsMinAltitudeFt, calib::kAdsMaxAltitudeFt, options.alt_step_ft),
               temps_c,
               calib::AltitudeTolerancePoints(),
               !constants.altitude_ft.hysteresis.active());
  out.airspeed =
      Evaluate(params,
               exported,
               airspeed,
               Range(calib::kAdsMinAirspeedKt, calib::kAdsMaxAirspeedKt, options.cas_step_kt),
               temps_c,
               calib::AirspeedTolerancePoints(),
               !constants.airspeed_kt.hysteresis.active());
  return out;
}

}  // namespace adahrs::proving
