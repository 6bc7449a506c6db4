// Physics of a single-axis rate table under its controller (Ideal Aerosmith 1621-class platter,
// Aero 8xx controller): the model behind the virtual ATL table (rate_table_device.h). The platter
// rate follows a piecewise-linear reference through a first-order closed rate loop (tau =
// rate_loop_tau_s), integrated exactly; modes rate (JOG, STO), position (P, HOM: a braking curve
// that ends exactly on target), sine (SGO), servo off (coast-down), interlock open (brake to rest).
// A once-per-revolution encoder error (rate_ripple_ratio) makes the true rate differ from the
// controller's reports. Time is quantised to a fixed 1 ms tick (kTick_s), so the timeline is the
// same whatever the pattern of AdvanceTo calls. Fault: "stalled" (no encoder motion).
// Frames and units: the platter turns about the table axis (L's z, up); angle_deg from the table's
// zero and rate_dps positive counter-clockwise seen from above; simulated seconds.
// Loop equations, settling time, modes and ripple: docs/rig/rate-table.md ("Physics").
// Left out: wobble and axis tilt, encoder quantisation, torque saturation beyond the acceleration
// limit, thermal drift of the rate loop, the real controller's position-loop overshoot, Earth rate.
#pragma once

namespace adahrs::rig_sim {

/// Parameters; every number is an estimate (E) of a 1621-class table unless the doc page says
/// otherwise (no datasheet was available; see docs/rig/rate-table.md).
struct RateTableParams {
  double max_rate_dps = 360.0;          ///< drive limit; commands beyond it are refused
  double max_accel_dps2 = 500.0;        ///< drive limit for ACL; also the interlock braking rate
  double accel_dps2 = 100.0;            ///< acceleration setting at power-on
  double rate_loop_tau_s = 0.05;        ///< closed rate-loop time constant
  double move_rate_dps = 60.0;          ///< top speed of position moves (P, HOM)
  double rate_ripple_ratio = 1e-5;      ///< once-per-revolution relative rate ripple
  double at_rate_band_dps = 0.01;       ///< |rate − commanded| for "at rate"
  double in_position_band_deg = 0.001;  ///< |angle − target| for "in position"
  double coast_tau_s = 30.0;            ///< spin-down time constant with the servo off
};

/// Why a command was not accepted.
enum class RateTableRefusal { kNone, kServoOff, kInterlockOpen, kBeyondLimit };

struct RateTableStatus {
  bool servo_on = false;
  bool at_rate = false;      ///< rate mode, reference at the command, platter inside the band
  bool in_position = false;  ///< position mode, platter inside the band at rest
  bool moving = false;       ///< |rate| above the at-rate band
  bool interlock_open = false;
  bool stalled = false;
};

class RateTable {
 public:
  static constexpr double kTick_s = 0.001;

  /// Throws std::invalid_argument naming the parameter and its value when one is not usable.
  RateTable(const RateTableParams& params, double initial_angle_deg);

  /// Runs every whole tick up to `time_s` (earlier times are ignored).
  void AdvanceTo(double time_s);
  double time_s() const { return static_cast<double>(ticks_) * kTick_s; }

  /// Rate mode at `rate_dps`; refused beyond ±max_rate_dps, with the servo off or the interlock
  /// open.
  RateTableRefusal Jog(double rate_dps);
  /// Rate mode at 0 (always accepted; with the servo off it changes nothing).
  RateTableRefusal Stop();
  /// Position move to `angle_deg` (any real; taken modulo 360), the shortest way round.
  RateTableRefusal MoveTo(double angle_deg);
  /// Acceleration setting, refused outside (0, max_accel_dps2].
  RateTableRefusal SetAcceleration(double accel_dps2);
  /// Servo on (bumpless: holds the present rate, then obeys commands) or off (coast).
  RateTableRefusal SetServo(bool on);
  /// Sine motion; refused when the peak rate or acceleration exceeds the limits.
  RateTableRefusal StartSine(double amplitude_deg, double frequency_hz, int cycles);

  void SetInterlockOpen(bool open);
  void SetStalled(bool stalled);

  /// True platter rate (with the ripple), for the rig's world.
  double platter_rate_dps() const;
  /// True platter angle in [0, 360), for the rig's world.
  double platter_angle_deg() const;
  /// The controller's encoder rate (what it reports and regulates).
  double measured_rate_dps() const { return stalled_ ? 0.0 : rate_smooth_dps_; }
  /// The controller's encoder angle in [0, 360).
  double measured_angle_deg() const;
  /// The encoder angle, not wrapped (initial angle plus total rotation).
  double unwrapped_angle_deg() const { return angle_smooth_deg_; }
  double commanded_rate_dps() const { return commanded_rate_dps_; }
  double acceleration_dps2() const { return accel_dps2_; }
  RateTableStatus status() const;

 private:
  enum class Mode { kRate, kPosition, kSine, kCoast };

  void Tick();
  // Follows a linear reference r0 + s·t for `dt_s` (the exact lag solution above).
  void FollowSegment(double r0_dps, double slope_dps2, double dt_s);
  bool Quiescent() const;
  // θ + tau·y: where the platter comes to rest if the reference stops here now (see above).
  double LeadAngle() const;

  RateTableParams params_;
  long long ticks_ = 0;
  Mode mode_ = Mode::kRate;
  bool servo_on_ = true;
  bool interlock_open_ = false;
  bool braking_ = false;  // interlock stop at max_accel_dps2
  bool stalled_ = false;
  double accel_dps2_;
  double commanded_rate_dps_ = 0.0;
  double ref_rate_dps_ = 0.0;
  double ref_angle_deg_;           // unwrapped
  double target_angle_deg_ = 0.0;  // unwrapped
  double sine_start_deg_ = 0.0;
  double sine_amplitude_deg_ = 0.0;
  double sine_frequency_hz_ = 0.0;
  double sine_duration_s_ = 0.0;
  double sine_elapsed_s_ = 0.0;
  double rate_smooth_dps_ = 0.0;  // y, the encoder rate
  double angle_smooth_deg_;       // θe, the encoder angle, unwrapped
};

}  // namespace adahrs::rig_sim
