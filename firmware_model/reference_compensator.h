// Double-precision implementation of the same compensation equations as the target compensator,
// straight from the pipeline's constants in raw units (calibration_constants.h). Used only to
// validate the fixed-point model; outputs are in the units of compensated_frame.h (duty, counts,
// g, deg/s, m/s^2, ft, kt) as doubles; an ADS surface's ISA / CAS law is the exact formula of
// air_data_law.h, not the target's table. Not modelled: any quantisation (that is the point), and
// the target's hold of the thermal drift beyond its normalised temperature range (the exporter's
// choice, constants_exporter.h): outside it the reference keeps evaluating the polynomial.
#pragma once

#include <array>

#include "firmware_model/calibration_constants.h"
#include "firmware_model/unit_firmware.h"

namespace adahrs::firmware_model {

/// The nine IMU outputs of `mode`, in the physical units of compensated_frame.h.
std::array<double, 9> ImuReference(const ImuCalibrationConstants& constants,
                                   ImuCompensationMode mode,
                                   const ImuRawFrame& raw);

/// The compensation's laws one at a time, as ImuReference applies them (calibration_constants.h):
/// xi(t), a channel's thermal drift at its temperature sensor's count `temp_cnt`;
double ThermalDrift(const ThermalFit& fit, double temp_cnt);
/// F(t), the format-3 scale factor of channel `channel` at `raw`'s temperature (1 when inactive);
double ScaleTemperatureFactor(const ImuCalibrationConstants& constants,
                              int channel,
                              const ImuRawFrame& raw);
/// the gyro cubic l0 + l1 d + l2 d^2 + l3 d^3 of gyro `axis` (0..2) at d = (T - null) F(t), deg/s.
double GyroCubic(const ImuCalibrationConstants& constants, int axis, double d);

/// The hysteresis states the reference is given (it runs no operator: the target's are checked
/// against the simulator's law on their own, tests/firmware_model/preisach_q15_test.cc).
struct AdsReferenceStates {
  double static_pressure = 0.0;
  double static_thermal = 0.0;
  double pitot_pressure = 0.0;
  double pitot_thermal = 0.0;
};

/// Altitude (ft) and airspeed (kt) from the surfaces and their hysteresis terms at `states`; in
/// kRaw mode the ps and pt codes.
std::array<double, 2> AdsReference(const AdsCalibrationConstants& constants,
                                   AdsCompensationMode mode,
                                   const AdsRawFrame& raw,
                                   const AdsReferenceStates& states = {});

/// The linearised code s(y) of a bridge-voltage code (calibration_constants.h); y itself when the
/// linearisation is off.
double LinearisedBridgeCode(const BridgeLinearisation& linearisation, double y_code);
/// Evaluates one surface at raw codes (x, y), through its linearisation of y: its z (ft, kt, or
/// Pa under a law), no hysteresis.
double EvaluateSurfaceFit(const SurfaceFit& surface, double x_code, double y_code);
/// The output of a surface, its hysteresis terms at states (s_pressure, s_thermal) with the gains
/// at the die temperature of the (linearised) y_code, and its law (air_data_law.h, exact in
/// double): ft or kt.
double SurfaceOutput(const SurfaceFit& surface,
                     double x_code,
                     double y_code,
                     double s_pressure = 0.0,
                     double s_thermal = 0.0);

/// Converts a fixed-point frame to the same physical units (value = word * 2^(exponent - 31)).
std::array<double, 9> ImuFrameToDouble(ImuCompensationMode mode, const ImuCompensatedFrame& frame);
std::array<double, 2> AdsFrameToDouble(AdsCompensationMode mode, const AdsCompensatedFrame& frame);

}  // namespace adahrs::firmware_model
