// The virtual Druck ADTS 405 air data test set: its SCPI command set as the ADTS 405 programs use
// it (shared/protocols.md §4.2-4.4, DRV) and the physics of its two pressure controllers (§4.7,
// DOC ADTS 405 Mk2 manual ch. 8). GPIB transport (the Prologix adapter) is
// rig_sim/prologix_adts_device.h; this class sees program messages only. In control each channel
// slews linearly towards its aim in the quantity the rate was given in (altitude via
// common/atmosphere.h, CAS via common/air_data.h, or pressure), without overshoot, plus
// Gauss-Markov stability noise (tau noise_tau_s, ±3 sigma = ±0.038 mbar Ps, ±0.045 mbar Qc).
// Status bit 1 (stable) rises stable_delay_s (15 s) after bits 8 and 10. Aims and rates beyond the
// limits are refused with SCPI error −222 in the error queue, never clamped.
// Units: Ps and Qc = Pt − Ps in Pa; altitude ft, ft/min; CAS kt, kt/min; seconds.
// Commands, status bits, limits and physics: docs/rig/adts.md.
// Left out: leaks and auto leak recovery, limit sets, the dynamic (sinusoidal) test, EPR/TAS/Mach
// aims (measured only), the supersonic branch (qc_max_pa ≤ qc at 661.5 kt), the ADTS's own
// measurement uncertainty, volume effects on the rates, QFE/QNH.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/random.h"
#include "hil/codecs/scpi.h"

namespace adahrs::rig_sim {

struct Adts405Params {
  double ps_min_pa = 7500.0;                    ///< ≈ 60 000 ft
  double ps_max_pa = 135500.0;                  ///< the 1355 mbar Ps range (§4.7)
  double qc_max_pa = 90000.0;                   ///< subsonic (< 90 476 Pa = qc at a0)
  double max_alt_rate_ft_per_min = 100000.0;    ///< §4.7
  double max_cas_rate_kt_per_min = 2000.0;      ///< §4.7
  double max_pressure_rate_pa_per_min = 1.0e6;  ///< 10 000 mbar/min (§4.7)
  double initial_alt_rate_ft_per_min = 6000.0;  ///< smooth-control figure (§4.7)
  double initial_cas_rate_kt_per_min = 200.0;
  double ps_stability_pa = 3.8;  ///< ±0.038 mbar (§4.7), taken as 3σ
  double qc_stability_pa = 4.5;  ///< ±0.045 mbar (§4.7), taken as 3σ
  double noise_tau_s = 1.0;
  double ground_ps_pa = 101325.0;  ///< the lab's barometric pressure (vent)
  double ground_band_pa = 50.0;    ///< |Ps − ground| and |Qc| below this: safe at ground
  double stable_delay_s = 15.0;    ///< §4.4
  bool oper_event_latched = true;  ///< STAT:OPER:EVEN? as a latched SCPI event register
  std::string idn = "DRUCK,ADTS405,0000000,V1.00";
  uint64_t seed = 405;
};

class Adts405 {
 public:
  static constexpr double kTick_s = 0.01;
  enum class Control { kOff, kOn, kHold };

  explicit Adts405(const Adts405Params& params);

  /// Executes one program message (terminator removed) at the current time. Returns the response
  /// message (without terminator) when it held queries, else nullopt.
  std::optional<std::string> Execute(std::string_view message);
  /// Advances the controllers in 10 ms ticks up to `now_s`.
  void AdvanceTo(double now_s);

  /// IEEE 488.2 status byte: bit 2 error queue not empty, bit 4 message available (as the caller
  /// says), bit 5 event status summary (ESR & ESE), bit 6 master summary (the others & SRE).
  int StatusByte(bool message_available = false) const;
  /// The pressures delivered to the ports (with the controller noise while controlling).
  double ps_pa() const { return ps_pa_ + (control_ == Control::kOff ? 0.0 : ps_noise_pa_); }
  double qc_pa() const { return qc_pa_ + (control_ == Control::kOff ? 0.0 : qc_noise_pa_); }
  int condition() const { return condition_; }
  /// Commands not recognised, verbatim (the last 100), to capture a real client's traffic.
  const std::deque<std::string>& unrecognised() const { return unrecognised_; }
  /// Physical fault: the stable-at-aim bit never rises.
  void SetNeverStable(bool on) { never_stable_ = on; }
  /// Queues a SCPI error (also used by the transport for −410 query interrupted).
  void PushError(int code);
  void SetEnableRegister(const std::string& arg, int* reg, int mask);

 private:
  enum class Rate { kAltitude, kAirspeed, kPressure };
  struct Channel {
    double aim_pa;
    Rate rate_kind;
    double rate_per_s;  // ft/s, kt/s or Pa/s
  };

  // The command table (kCommands in adts405.cc), shaped like the ATL table (hil::AtlCommandSpec):
  // each command's header and its two forms, the bare form (an action) and the `?` form (a
  // query), each with the number of arguments it takes and the member that performs it.
  using Args = std::vector<std::string>;
  using Reply = std::optional<std::string>;
  struct Action {
    size_t args;
    void (Adts405::*run)(const Args&);
  };
  struct Query {
    size_t args;
    Reply (Adts405::*run)(const Args&);
  };
  struct CommandSpec {
    bool common;                              ///< `*XXX`
    std::array<std::string_view, 3> headers;  ///< patterns ("SOURce", "PRESsure"), then ""
    std::optional<Action> action;
    std::optional<Query> query;
  };
  static const CommandSpec kCommands[];

  Reply ExecuteOne(const hil::ScpiCommand& command, const std::string& text);
  static const CommandSpec* FindCommand(const hil::ScpiCommand& command);
  bool WantArgs(const Args& args, size_t n);
  void Unrecognised(const std::string& text);

  // IEEE 488.2 common commands.
  Reply Identity(const Args&);
  Reply OperationComplete(const Args&);
  Reply EventStatus(const Args&);
  Reply StatusByteQuery(const Args&);
  Reply Ese(const Args&);
  Reply Sre(const Args&);
  void SetEse(const Args& args);
  void SetSre(const Args& args);
  void ClearStatus(const Args&);
  void Reset(const Args&);
  // SOURce: the controllers.
  Reply ControlQuery(const Args&);
  void SetControl(const Args& args);
  Reply Aim(const Args& args);
  void SetAim(const Args& args);
  Reply RateQuery(const Args& args);
  void SetRate(const Args& args);
  Reply AtGround(const Args&);
  void GoToGround(const Args&);
  // MEASure, STATus, UNIT, SYSTem.
  Reply Measure(const Args& args);
  Reply OperationEvent(const Args&);
  Reply OperationCondition(const Args&);
  Reply PresUnit(const Args&);
  void SetPresUnit(const Args& args);
  Reply AltUnit(const Args&);
  void SetAltUnit(const Args& args);
  Reply SpeedUnit(const Args&);
  void SetSpeedUnit(const Args& args);
  Reply NextError(const Args&);

  void Tick();
  void Slew(Channel& channel, double& value_pa, bool is_ps);
  void UpdateCondition();
  std::optional<double> PressureUnitToPa(double value) const;

  Adts405Params params_;
  common::Rng rng_;
  Control control_ = Control::kOff;
  double ps_pa_, qc_pa_ = 0.0;
  double ps_noise_pa_ = 0.0, qc_noise_pa_ = 0.0;
  Channel ps_, qc_;
  std::string pressure_unit_ = "MBAR";
  bool altitude_in_m_ = false;
  std::string speed_unit_ = "KTS";
  int condition_ = 0;
  int event_ = 0;
  int esr_ = 0;
  int ese_ = 0;  ///< *ESE, 0 at power-on; *CLS and *RST keep it (IEEE 488.2 §10.10)
  int sre_ = 0;  ///< *SRE, bit 6 ignored; 0 at power-on
  double both_at_set_point_since_s_ = -1.0;
  bool never_stable_ = false;
  std::deque<int> errors_;
  std::deque<std::string> unrecognised_;
  int64_t ticks_ = 0;
};

}  // namespace adahrs::rig_sim
