#include "diagnosis/imu_effects.h"

#include <cmath>

#include <fmt/format.h>

#include "common/imu_layout.h"

namespace adahrs::diagnosis {
namespace {

int OwnAxis(int ch) { return common::kImuChannels[ch].axis; }

std::string PlusMinus(const FindingComponent& x) {
  return fmt::format("{:.3g} ± {:.2g} {}", x.magnitude, x.standard_error, x.unit);
}

std::string PhysUnit(int ch) { return common::IsGyroChannel(ch) ? "deg/s" : "mg"; }

ImuEffect DieLag() {
  ImuEffect e;
  e.effect = Effect::kDieLag;
  e.name = "die_thermal_lag";
  // A gyro's thermometer is its own die's TEMP pin: no lag can open between the two.
  e.on_accel = true;
  e.components = [](int) { return std::vector<std::string>{"delay"}; };
  e.columns = [](const EffectInputs& in, double* x) {
    x[0] = -in.dudt_per_c * in.cell.dtemp_dt_c_per_s[common::kImuChannels[in.channel].thermometer];
  };
  e.unit = [](size_t, int, double) { return EffectUnit{1.0, "s"}; };
  e.words = [](const std::string& name, const std::string& thermometer, const auto& c, auto) {
    return fmt::format(
        "{} follows its thermometer ({}) {} late: die thermal lag between the sensor and its "
        "thermometer is missing from the model",
        name,
        thermometer,
        PlusMinus(c[0]));
  };
  return e;
}

ImuEffect ScaleTempco() {
  ImuEffect e;
  e.effect = Effect::kScaleTempco;
  e.name = "scale_factor_tempco";
  e.on_accel = e.on_gyro = true;
  e.components = [](int) { return std::vector<std::string>{"tc1", "tc2"}; };
  e.columns = [](const EffectInputs& in, double* x) {
    x[0] = in.stim_part * in.dt_c;
    x[1] = in.stim_part * in.dt_c * in.dt_c;
  };
  e.unit = [](size_t i, int, double) {
    return EffectUnit{1e6, i == 0 ? "ppm/degC" : "ppm/degC^2"};
  };
  e.words = [](const std::string& name, const std::string&, const auto& c, auto) {
    return fmt::format(
        "{}'s scale factor changes {} and {}: scale factor vs temperature is missing from "
        "the model",
        name,
        PlusMinus(c[0]),
        PlusMinus(c[1]));
  };
  return e;
}

ImuEffect CrossAxisTempco() {
  ImuEffect e;
  e.effect = Effect::kCrossAxisTempco;
  e.name = "residual_cross_axis_coupling";
  e.on_gyro = true;
  e.needs_cross_excitation = true;
  e.components = [](int ch) {
    std::vector<std::string> off_axes;
    for (int j = 0; j < 3; ++j) {
      if (j != OwnAxis(ch)) off_axes.push_back(std::string(1, "xyz"[j]));
    }
    return off_axes;
  };
  e.columns = [](const EffectInputs& in, double* x) {
    int n = 0;
    for (int j = 0; j < 3; ++j) {
      if (j != OwnAxis(in.channel)) x[n++] = in.sensitivity * in.stim[j] * in.dt_c;
    }
  };
  e.unit = [](size_t, int, double) { return EffectUnit{1e6, "ppm/degC"}; };
  e.words = [](const std::string& name, const std::string&, const auto& c, auto) {
    return fmt::format(
        "{}'s response to its cross axes changes with temperature ({} {}, {} {}, of the input "
        "along that axis): residual cross-axis coupling is missing from the model",
        name,
        c[0].name,
        PlusMinus(c[0]),
        c[1].name,
        PlusMinus(c[1]));
  };
  return e;
}

ImuEffect GSensitivity() {
  ImuEffect e;
  e.effect = Effect::kGSensitivity;
  e.name = "gyro_g_sensitivity";
  e.on_gyro = true;
  e.components = [](int) { return std::vector<std::string>{"x", "y", "z"}; };
  e.columns = [](const EffectInputs& in, double* x) {
    for (int j = 0; j < 3; ++j) x[j] = in.cell.f_B_g[j];
  };
  e.unit = [](size_t, int, double phys) { return EffectUnit{phys, "deg/s/g"}; };
  e.words = [](const std::string& name, const std::string&, const auto& c, auto) {
    size_t big = 0;
    for (size_t i = 1; i < c.size(); ++i) {
      if (std::abs(c[i].magnitude) > std::abs(c[big].magnitude)) big = i;
    }
    return fmt::format(
        "{} responds {:.3g} ± {:.2g} deg/s per g along {}{} (x {:.3g}, y {:.3g}, z {:.3g} "
        "deg/s/g): gyro g-sensitivity is missing from the model",
        name,
        std::abs(c[big].magnitude),
        c[big].standard_error,
        c[big].magnitude >= 0 ? "+" : "-",
        "XYZ"[big],
        c[0].magnitude,
        c[1].magnitude,
        c[2].magnitude);
  };
  return e;
}

ImuEffect ThermalHysteresis() {
  ImuEffect e;
  e.effect = Effect::kThermalHysteresis;
  e.name = "thermal_hysteresis";
  // An accelerometer's thermometer is another die: the lag's transients after each ramp carry the
  // sense of the last change, and a hysteresis could not be told from them.
  e.on_gyro = true;
  e.needs_hysteresis_option = true;
  e.slow = true;
  e.components = [](int) { return std::vector<std::string>{"half_loop"}; };
  e.columns = [](const EffectInputs& in, double* x) {
    x[0] = in.cell.last_change_sense[common::kImuChannels[in.channel].thermometer];
  };
  e.unit = [](size_t, int ch, double phys) { return EffectUnit{phys, PhysUnit(ch)}; };
  e.words = [](const std::string& name, const std::string&, const auto& c, auto) {
    return fmt::format(
        "{} reads {} higher after heating than after cooling (half the loop): thermal "
        "hysteresis is missing from the model",
        name,
        PlusMinus(c[0]));
  };
  return e;
}

ImuEffect WarmUp() {
  ImuEffect e;
  e.effect = Effect::kWarmUp;
  e.name = "self_heating_warm_up";
  e.on_accel = true;  // a gyro's thermometer is on its die: no warm-up opens between them
  e.taus_s = {150.0, 300.0, 600.0, 1200.0};
  e.slow = true;
  e.components = [](int) { return std::vector<std::string>{"initial_excess"}; };
  e.columns = [](const EffectInputs& in, double* x) {
    x[0] = in.dudt_per_c * std::exp(-in.cell.t_since_start_s / *in.tau_s);
  };
  e.unit = [](size_t, int, double) { return EffectUnit{1.0, "degC"}; };
  e.words = [](const std::string& name,
               const std::string& thermometer,
               const auto& c,
               std::optional<double> tau_s) {
    return fmt::format(
        "{}'s die starts {} above its thermometer ({}) at power-on and settles with tau ≈ "
        "{:.0f} s: self-heating warm-up is missing from the model",
        name,
        PlusMinus(c[0]),
        thermometer,
        *tau_s);
  };
  return e;
}

ImuEffect AccelNonlinearity() {
  ImuEffect e;
  e.effect = Effect::kAccelNonlinearity;
  e.name = "accel_nonlinearity";
  e.on_accel = true;
  e.slow = true;  // f_axis^2 is 0 or 1 under gravity: a contrast between few input levels
  e.quantised_input = true;
  e.components = [](int) { return std::vector<std::string>{"k2"}; };
  e.columns = [](const EffectInputs& in, double* x) {
    const double f = in.cell.f_B_g[OwnAxis(in.channel)];
    x[0] = in.sensitivity * f * f;
  };
  e.unit = [](size_t, int, double) { return EffectUnit{1000.0, "mg/g^2"}; };
  e.words = [](const std::string& name, const std::string&, const auto& c, auto) {
    return fmt::format(
        "{} deviates {} of its input squared: second-order accelerometer nonlinearity is "
        "missing from the model",
        name,
        PlusMinus(c[0]));
  };
  return e;
}

}  // namespace

const std::vector<ImuEffect>& ImuEffects() {
  static const std::vector<ImuEffect> effects = {DieLag(),
                                                 ScaleTempco(),
                                                 CrossAxisTempco(),
                                                 GSensitivity(),
                                                 ThermalHysteresis(),
                                                 WarmUp(),
                                                 AccelNonlinearity()};
  return effects;
}

const ImuEffect& EffectRow(Effect effect) {
  for (const ImuEffect& e : ImuEffects()) {
    if (e.effect == effect) return e;
  }
  return ImuEffects().front();  // unreachable: every Effect has a row
}

}  // namespace adahrs::diagnosis
