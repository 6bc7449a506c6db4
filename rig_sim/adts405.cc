#include "rig_sim/adts405.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <utility>

#include "common/air_data.h"
#include "common/atmosphere.h"
#include "common/units.h"

namespace adahrs::rig_sim {

using hil::ScpiCommand;

namespace {

// Operation status bits of the ADTS 405 (protocols.md §4.4, DRV ADTSStatus.cs).
constexpr int kStableAtAim = 1 << 1;
constexpr int kSafeAtGround = 1 << 2;
constexpr int kRamping = 1 << 3;
constexpr int kPsAtSetPoint = 1 << 8;
constexpr int kPsRamping = 1 << 9;
constexpr int kPtAtSetPoint = 1 << 10;
constexpr int kPtRamping = 1 << 11;

// IEEE 488.2 standard event status bits and status byte bits.
constexpr int kEsrExecutionError = 1 << 4;
constexpr int kEsrCommandError = 1 << 5;
constexpr int kEsrQueryError = 1 << 2;
constexpr int kStbErrorQueue = 1 << 2;
constexpr int kStbMessageAvailable = 1 << 4;
constexpr int kStbEventSummary = 1 << 5;
constexpr int kStbMasterSummary = 1 << 6;

constexpr int kReplyDigits = 8;
constexpr size_t kMaxErrors = 10;
constexpr size_t kMaxUnrecognised = 100;

// Pressure units of UNIT:PRES (protocols.md §4.3) with their size in Pa: conventional mmHg
// 133.322387415 Pa, kgf/cm² 98066.5 Pa (exact), inH2O at 4 °C 249.082 Pa and at 60 °F 248.84 Pa
// (NIST SP 811 appendix B.8); mbar/hPa/Pa and psi/inHg by definition (common/units.h).
// `INH2O20`, `MMH2O4` and `%FS` are not emulated (refused with −224).
constexpr std::array<std::pair<std::string_view, double>, 9> kPressureUnits{{
    {"MBAR", 100.0},
    {"HPA", 100.0},
    {"PA", 1.0},
    {"INHG", common::kPaPerInHg},
    {"MMHG", 133.322387415},
    {"PSI", common::kPaPerPsi},
    {"KGCM2", 98066.5},
    {"INH2O4", 249.082},
    {"INH2O60F", 248.84},
}};

// Speed units of the provisional UNIT:SPE (protocols.md §4.5), in knots per unit.
constexpr double kKmPerNauticalMile = 1.852;
constexpr double kMetersPerStatuteMile = 1609.344;
constexpr double kMetersPerNauticalMile = 1852.0;

// Qc/Ps at Mach 1 in subsonic flow: (1 + 0.2)^3.5 − 1 (protocols.md §5).
const double kSonicQcOverPs = std::pow(1.2, 3.5) - 1.0;

std::string Upper(std::string_view s) {
  std::string u(s);
  for (char& c : u) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return u;
}

double CasKt(double qc_pa) {
  return qc_pa >= 0.0 ? common::CalibratedAirspeedKt(qc_pa) : -common::CalibratedAirspeedKt(-qc_pa);
}

double KtPerSpeedUnit(const std::string& unit) {
  if (unit == "KMH") return 1.0 / kKmPerNauticalMile;
  if (unit == "MPH") return kMetersPerStatuteMile / kMetersPerNauticalMile;
  return 1.0;
}

}  // namespace

Adts405::Adts405(const Adts405Params& params)
    : params_(params),
      rng_(params.seed),
      ps_pa_(params.ground_ps_pa),
      ps_{params.ground_ps_pa, Rate::kAltitude, params.initial_alt_rate_ft_per_min / 60.0},
      qc_{0.0, Rate::kAirspeed, params.initial_cas_rate_kt_per_min / 60.0} {
  UpdateCondition();
  event_ = 0;
}

void Adts405::PushError(int code) {
  if (errors_.size() < kMaxErrors) errors_.push_back(code);
  if (code <= -100 && code > -200) esr_ |= kEsrCommandError;
  if (code <= -200 && code > -300) esr_ |= kEsrExecutionError;
  if (code <= -400 && code > -500) esr_ |= kEsrQueryError;
}

int Adts405::StatusByte(bool message_available) const {
  const int stb = (errors_.empty() ? 0 : kStbErrorQueue) |
                  (message_available ? kStbMessageAvailable : 0) |
                  ((esr_ & ese_) ? kStbEventSummary : 0);
  return stb | ((stb & sre_) ? kStbMasterSummary : 0);
}

// *ESE n or *SRE n: an integer 0...255, else -224 and nothing changes.
void Adts405::SetEnableRegister(const std::string& arg, int* reg, int mask) {
  int value = -1;
  const auto [end, ec] = std::from_chars(arg.data(), arg.data() + arg.size(), value);
  if (ec != std::errc() || end != arg.data() + arg.size() || value < 0 || value > 255) {
    PushError(hil::kScpiIllegalParameterValue);
    return;
  }
  *reg = value & mask;
}

std::optional<std::string> Adts405::Execute(std::string_view message) {
  std::string response;
  bool any = false;
  for (const std::string& text : hil::SplitScpiProgram(message)) {
    const hil::ScpiParsed parsed = hil::ParseScpiCommand(text);
    if (!parsed.command) {
      PushError(parsed.error);
      continue;
    }
    if (auto reply = ExecuteOne(*parsed.command, text)) {
      response += (any ? ";" : "") + *reply;
      any = true;
    }
  }
  if (!any) return std::nullopt;
  return response;
}

// The command set (docs/rig/adts.md, shared/protocols.md §4.2-4.5). A form a command does not
// list is an undefined header (−113, logged in unrecognised()), except that a common command in a
// form it lacks (`*IDN`, `*CLS?`) is ignored without an error. A wrong number of arguments is
// −109 (too few) or −108 (too many), and the command is not performed.
const Adts405::CommandSpec Adts405::kCommands[] = {
    {true, {"IDN"}, {}, Query{0, &Adts405::Identity}},
    {true, {"OPC"}, {}, Query{0, &Adts405::OperationComplete}},
    {true, {"ESR"}, {}, Query{0, &Adts405::EventStatus}},
    {true, {"STB"}, {}, Query{0, &Adts405::StatusByteQuery}},
    {true, {"ESE"}, Action{1, &Adts405::SetEse}, Query{0, &Adts405::Ese}},
    {true, {"SRE"}, Action{1, &Adts405::SetSre}, Query{0, &Adts405::Sre}},
    {true, {"CLS"}, Action{0, &Adts405::ClearStatus}, {}},
    {true, {"RST"}, Action{0, &Adts405::Reset}, {}},
    {false, {"SOURce", "STATe"}, Action{1, &Adts405::SetControl}, Query{0, &Adts405::ControlQuery}},
    {false, {"SOURce", "PRESsure"}, Action{2, &Adts405::SetAim}, Query{1, &Adts405::Aim}},
    {false, {"SOURce", "RATE"}, Action{2, &Adts405::SetRate}, Query{1, &Adts405::RateQuery}},
    {false, {"SOURce", "GTGRound"}, Action{0, &Adts405::GoToGround}, Query{0, &Adts405::AtGround}},
    {false, {"MEASure", "PRESsure"}, {}, Query{1, &Adts405::Measure}},
    {false, {"STATus", "OPERation", "EVENt"}, {}, Query{0, &Adts405::OperationEvent}},
    {false, {"STATus", "OPERation", "CONDition"}, {}, Query{0, &Adts405::OperationCondition}},
    {false, {"STATus", "OPERation", "CON"}, {}, Query{0, &Adts405::OperationCondition}},  // DRV
    {false, {"UNIT", "PRESsure"}, Action{1, &Adts405::SetPresUnit}, Query{0, &Adts405::PresUnit}},
    {false, {"UNIT", "ALTitude"}, Action{1, &Adts405::SetAltUnit}, Query{0, &Adts405::AltUnit}},
    {false, {"UNIT", "SPEed"}, Action{1, &Adts405::SetSpeedUnit}, Query{0, &Adts405::SpeedUnit}},
    {false, {"SYSTem", "ERRor"}, {}, Query{0, &Adts405::NextError}},
};

const Adts405::CommandSpec* Adts405::FindCommand(const ScpiCommand& c) {
  for (const CommandSpec& spec : kCommands) {
    if (spec.common != c.common) continue;
    const auto& h = spec.headers;
    const auto end = std::find(h.begin(), h.end(), std::string_view());
    if (std::equal(h.begin(), end, c.headers.begin(), c.headers.end(), hil::ScpiHeaderMatches)) {
      return &spec;
    }
  }
  return nullptr;
}

Adts405::Reply Adts405::ExecuteOne(const ScpiCommand& c, const std::string& text) {
  const CommandSpec* spec = FindCommand(c);
  const bool has_form =
      spec != nullptr && (c.query ? spec->query.has_value() : spec->action.has_value());
  if (!has_form) {
    if (spec == nullptr || !spec->common) Unrecognised(text);
    return std::nullopt;
  }
  if (!c.query) {
    if (WantArgs(c.args, spec->action->args)) (this->*spec->action->run)(c.args);
    return std::nullopt;
  }
  if (!WantArgs(c.args, spec->query->args)) return std::nullopt;
  return (this->*spec->query->run)(c.args);
}

bool Adts405::WantArgs(const Args& args, size_t n) {
  if (args.size() == n) return true;
  PushError(args.size() < n ? hil::kScpiMissingParameter : hil::kScpiParameterNotAllowed);
  return false;
}

void Adts405::Unrecognised(const std::string& text) {
  PushError(hil::kScpiUndefinedHeader);
  if (unrecognised_.size() == kMaxUnrecognised) unrecognised_.pop_front();
  unrecognised_.push_back(text);
}

Adts405::Reply Adts405::Identity(const Args&) { return params_.idn; }
Adts405::Reply Adts405::OperationComplete(const Args&) { return "1"; }
Adts405::Reply Adts405::EventStatus(const Args&) { return std::to_string(std::exchange(esr_, 0)); }
Adts405::Reply Adts405::StatusByteQuery(const Args&) { return std::to_string(StatusByte()); }
Adts405::Reply Adts405::Ese(const Args&) { return std::to_string(ese_); }
Adts405::Reply Adts405::Sre(const Args&) { return std::to_string(sre_); }
void Adts405::SetEse(const Args& args) { SetEnableRegister(args[0], &ese_, 0xFF); }
void Adts405::SetSre(const Args& args) {
  SetEnableRegister(args[0], &sre_, 0xFF & ~kStbMasterSummary);
}

void Adts405::ClearStatus(const Args&) {
  errors_.clear();
  esr_ = 0;
  event_ = 0;
}

void Adts405::Reset(const Args&) {
  control_ = Control::kOff;
  pressure_unit_ = "MBAR";
  speed_unit_ = "KTS";
  altitude_in_m_ = false;
  ps_ = {ps_pa_, Rate::kAltitude, params_.initial_alt_rate_ft_per_min / 60.0};
  qc_ = {qc_pa_, Rate::kAirspeed, params_.initial_cas_rate_kt_per_min / 60.0};
}

Adts405::Reply Adts405::ControlQuery(const Args&) {
  return control_ == Control::kOn ? "ON" : control_ == Control::kOff ? "OFF" : "HOLD";
}

void Adts405::SetControl(const Args& args) {
  const std::string state = Upper(args[0]);
  if (state == "ON" || state == "1") {
    control_ = Control::kOn;
  } else if (state == "OFF" || state == "0") {
    control_ = Control::kOff;
  } else if (state == "HOLD") {
    control_ = Control::kHold;
  } else {
    PushError(hil::kScpiIllegalParameterValue);
  }
}

Adts405::Reply Adts405::AtGround(const Args&) { return (condition_ & kSafeAtGround) ? "1" : "0"; }

void Adts405::GoToGround(const Args&) {
  if (control_ != Control::kOn) {
    PushError(hil::kScpiSettingsConflict);  // go-to-ground needs control mode (§4.3)
    return;
  }
  ps_.aim_pa = params_.ground_ps_pa;
  qc_.aim_pa = 0.0;
}

Adts405::Reply Adts405::OperationEvent(const Args&) {
  if (!params_.oper_event_latched) return std::to_string(condition_);
  return std::to_string(std::exchange(event_, 0));
}

Adts405::Reply Adts405::OperationCondition(const Args&) { return std::to_string(condition_); }

Adts405::Reply Adts405::PresUnit(const Args&) { return pressure_unit_; }

void Adts405::SetPresUnit(const Args& args) {
  const std::string unit = Upper(args[0]);
  const bool known = std::any_of(
      kPressureUnits.begin(), kPressureUnits.end(), [&](const auto& u) { return u.first == unit; });
  if (known) {
    pressure_unit_ = unit;
  } else {
    PushError(hil::kScpiIllegalParameterValue);
  }
}

Adts405::Reply Adts405::AltUnit(const Args&) { return altitude_in_m_ ? "M" : "FT"; }

void Adts405::SetAltUnit(const Args& args) {
  const std::string unit = Upper(args[0]);
  if (unit == "FT" || unit == "M") {
    altitude_in_m_ = unit == "M";
  } else {
    PushError(hil::kScpiIllegalParameterValue);
  }
}

Adts405::Reply Adts405::SpeedUnit(const Args&) { return speed_unit_; }

void Adts405::SetSpeedUnit(const Args& args) {
  const std::string unit = Upper(args[0]);
  if (unit == "KTS" || unit == "KMH" || unit == "MPH") {
    speed_unit_ = unit;
  } else {
    PushError(hil::kScpiIllegalParameterValue);
  }
}

Adts405::Reply Adts405::NextError(const Args&) {
  const int code = errors_.empty() ? hil::kScpiNoError : errors_.front();
  if (!errors_.empty()) errors_.pop_front();
  return std::to_string(code) + ",\"" + std::string(hil::ScpiErrorMessage(code)) + "\"";
}

std::optional<double> Adts405::PressureUnitToPa(double value) const {
  for (const auto& [name, pa] : kPressureUnits) {
    if (name == pressure_unit_) return value * pa;
  }
  return std::nullopt;
}

Adts405::Reply Adts405::Measure(const Args& args) {
  const std::string p = Upper(args[0]);
  const double ps = ps_pa();
  const double qc = qc_pa();
  const double pa_per_unit = *PressureUnitToPa(1.0);
  double value;
  if (p == "PS") {
    value = ps / pa_per_unit;
  } else if (p == "QC") {
    value = qc / pa_per_unit;
  } else if (p == "PT") {
    value = (ps + qc) / pa_per_unit;
  } else if (p == "ALT") {
    const double alt_ft = common::IsaPressureAltitudeFt(ps);
    value = altitude_in_m_ ? common::FtToM(alt_ft) : alt_ft;
  } else if (p == "CAS") {
    value = CasKt(qc) / KtPerSpeedUnit(speed_unit_);
  } else if (p == "EPR") {
    value = (ps + qc) / ps;
  } else if (p == "MACH" || p == "TAS") {
    if (std::max(qc, 0.0) / ps > kSonicQcOverPs) {
      PushError(hil::kScpiDataOutOfRange);  // supersonic: not modelled
      return std::nullopt;
    }
    const double mach = common::MachNumber(std::max(qc, 0.0), ps);
    const double static_k = common::IsaTemperatureK(common::IsaPressureAltitudeM(ps));
    value = p == "MACH" ? mach
                        : common::MpsToKt(common::TrueAirspeedMps(mach, static_k)) /
                              KtPerSpeedUnit(speed_unit_);
  } else {
    PushError(hil::kScpiIllegalParameterValue);
    return std::nullopt;
  }
  return hil::FormatScpiNumber(value, kReplyDigits);
}

Adts405::Reply Adts405::Aim(const Args& args) {
  const std::string p = Upper(args[0]);
  const double pa_per_unit = *PressureUnitToPa(1.0);
  double value;
  if (p == "PS") {
    value = ps_.aim_pa / pa_per_unit;
  } else if (p == "QC") {
    value = qc_.aim_pa / pa_per_unit;
  } else if (p == "PT") {
    value = (ps_.aim_pa + qc_.aim_pa) / pa_per_unit;
  } else if (p == "ALT") {
    const double alt_ft = common::IsaPressureAltitudeFt(ps_.aim_pa);
    value = altitude_in_m_ ? common::FtToM(alt_ft) : alt_ft;
  } else if (p == "CAS") {
    value = CasKt(qc_.aim_pa) / KtPerSpeedUnit(speed_unit_);
  } else {
    PushError(hil::kScpiIllegalParameterValue);
    return std::nullopt;
  }
  return hil::FormatScpiNumber(value, kReplyDigits);
}

void Adts405::SetAim(const Args& args) {
  const std::string p = Upper(args[0]);
  const std::optional<double> value = hil::ParseScpiNumber(args[1]);
  if (!value) {
    PushError(hil::kScpiDataTypeError);
    return;
  }
  double ps_aim = ps_.aim_pa;
  double qc_aim = qc_.aim_pa;
  const double pa = *PressureUnitToPa(*value);
  if (p == "ALT") {
    const double alt_ft = altitude_in_m_ ? common::MToFt(*value) : *value;
    if (alt_ft < common::MToFt(common::kIsaMinAltitude_m) ||
        alt_ft > common::MToFt(common::kIsaMaxAltitude_m)) {
      PushError(hil::kScpiDataOutOfRange);
      return;
    }
    ps_aim = common::IsaStaticPressurePaFromFt(alt_ft);
  } else if (p == "CAS") {
    const double cas_kt = *value * KtPerSpeedUnit(speed_unit_);
    if (cas_kt < 0.0 || cas_kt > common::MpsToKt(common::SeaLevelSpeedOfSoundMps())) {
      PushError(hil::kScpiDataOutOfRange);
      return;
    }
    qc_aim = common::ImpactPressurePaFromKt(cas_kt);
  } else if (p == "PS") {
    ps_aim = pa;
  } else if (p == "PT") {
    qc_aim = pa - ps_aim;
  } else if (p == "QC") {
    qc_aim = pa;
  } else {
    PushError(hil::kScpiIllegalParameterValue);  // TAS, MACH, EPR aims are not emulated
    return;
  }
  const bool in_limits = ps_aim >= params_.ps_min_pa && ps_aim <= params_.ps_max_pa &&
                         qc_aim >= 0.0 && qc_aim <= params_.qc_max_pa &&
                         qc_aim / ps_aim <= kSonicQcOverPs;
  if (!in_limits) {
    PushError(hil::kScpiDataOutOfRange);
    return;
  }
  ps_.aim_pa = ps_aim;
  qc_.aim_pa = qc_aim;
}

void Adts405::SetRate(const Args& args) {
  const std::string p = Upper(args[0]);
  const std::optional<double> value = hil::ParseScpiNumber(args[1]);
  if (!value) {
    PushError(hil::kScpiDataTypeError);
    return;
  }
  double per_min = *value;
  double max_per_min;
  Rate kind;
  if (p == "ALT") {
    per_min = altitude_in_m_ ? common::MToFt(per_min) : per_min;
    max_per_min = params_.max_alt_rate_ft_per_min;
    kind = Rate::kAltitude;
  } else if (p == "CAS") {
    per_min *= KtPerSpeedUnit(speed_unit_);
    max_per_min = params_.max_cas_rate_kt_per_min;
    kind = Rate::kAirspeed;
  } else if (p == "PS" || p == "PT" || p == "QC") {
    per_min = *PressureUnitToPa(per_min);
    max_per_min = params_.max_pressure_rate_pa_per_min;
    kind = Rate::kPressure;
  } else {
    PushError(hil::kScpiIllegalParameterValue);
    return;
  }
  if (!(per_min > 0.0) || per_min > max_per_min) {
    PushError(hil::kScpiDataOutOfRange);
    return;
  }
  Channel& channel = (p == "ALT" || p == "PS") ? ps_ : qc_;
  channel.rate_kind = kind;
  channel.rate_per_s = per_min / 60.0;
}

Adts405::Reply Adts405::RateQuery(const Args& args) {
  const std::string p = Upper(args[0]);
  const bool ps_side = p == "ALT" || p == "PS";
  const Channel& channel = ps_side ? ps_ : qc_;
  const Rate wanted = p == "ALT" ? Rate::kAltitude : p == "CAS" ? Rate::kAirspeed : Rate::kPressure;
  if (!(ps_side || p == "CAS" || p == "PT" || p == "QC")) {
    PushError(hil::kScpiIllegalParameterValue);
    return std::nullopt;
  }
  if (channel.rate_kind != wanted) {
    PushError(hil::kScpiSettingsConflict);  // the rate was set in another quantity
    return std::nullopt;
  }
  double per_min = channel.rate_per_s * 60.0;
  if (wanted == Rate::kAltitude && altitude_in_m_) per_min = common::FtToM(per_min);
  if (wanted == Rate::kAirspeed) per_min /= KtPerSpeedUnit(speed_unit_);
  if (wanted == Rate::kPressure) per_min /= *PressureUnitToPa(1.0);
  return hil::FormatScpiNumber(per_min, kReplyDigits);
}

void Adts405::AdvanceTo(double now_s) {
  const auto target_ticks = static_cast<int64_t>(std::floor(now_s / kTick_s + 1e-6));
  while (ticks_ < target_ticks) {
    ++ticks_;
    Tick();
  }
}

void Adts405::Slew(Channel& channel, double& value_pa, bool is_ps) {
  const double step = channel.rate_per_s * kTick_s;
  if (channel.rate_kind == Rate::kPressure) {
    const double error = channel.aim_pa - value_pa;
    value_pa = std::abs(error) <= step ? channel.aim_pa : value_pa + std::copysign(step, error);
    return;
  }
  // Linear in altitude (ft) or in calibrated airspeed (kt), mapped back to pressure.
  const bool altitude = channel.rate_kind == Rate::kAltitude && is_ps;
  auto to_x = [&](double pa) {
    return altitude ? common::IsaPressureAltitudeFt(pa) : common::CalibratedAirspeedKt(pa);
  };
  auto to_pa = [&](double x) {
    return altitude ? common::IsaStaticPressurePaFromFt(x) : common::ImpactPressurePaFromKt(x);
  };
  const double error = to_x(channel.aim_pa) - to_x(value_pa);
  value_pa =
      std::abs(error) <= step ? channel.aim_pa : to_pa(to_x(value_pa) + std::copysign(step, error));
}

void Adts405::Tick() {
  if (control_ == Control::kOn) {
    Slew(ps_, ps_pa_, true);
    Slew(qc_, qc_pa_, false);
  }
  // First-order Gauss-Markov noise, exact discretisation: x ← a·x + σ·sqrt(1 − a²)·n.
  const double a = std::exp(-kTick_s / params_.noise_tau_s);
  const double drive = std::sqrt(1.0 - a * a);
  ps_noise_pa_ = a * ps_noise_pa_ + params_.ps_stability_pa / 3.0 * drive * rng_.Normal();
  qc_noise_pa_ = a * qc_noise_pa_ + params_.qc_stability_pa / 3.0 * drive * rng_.Normal();
  UpdateCondition();
}

void Adts405::UpdateCondition() {
  int cond = 0;
  if (control_ == Control::kOn) {
    cond |= ps_pa_ == ps_.aim_pa ? kPsAtSetPoint : kPsRamping;
    cond |= qc_pa_ == qc_.aim_pa ? kPtAtSetPoint : kPtRamping;
    if (cond & (kPsRamping | kPtRamping)) cond |= kRamping;
  }
  if (std::abs(ps_pa_ - params_.ground_ps_pa) < params_.ground_band_pa &&
      std::abs(qc_pa_) < params_.ground_band_pa) {
    cond |= kSafeAtGround;
  }
  const double now_s = static_cast<double>(ticks_) * kTick_s;
  if ((cond & kPsAtSetPoint) && (cond & kPtAtSetPoint)) {
    if (both_at_set_point_since_s_ < 0.0) both_at_set_point_since_s_ = now_s;
    if (!never_stable_ && now_s - both_at_set_point_since_s_ >= params_.stable_delay_s - 1e-9)
      cond |= kStableAtAim;
  } else {
    both_at_set_point_since_s_ = -1.0;
  }
  event_ |= cond & ~condition_;
  condition_ = cond;
}

}  // namespace adahrs::rig_sim
