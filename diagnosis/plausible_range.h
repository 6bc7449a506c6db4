// When a candidate's detection limit says nothing: the smallest magnitude a recording would have
// found lies beyond the range the effect can physically have, so the recording gives the term no
// leverage (a lag or warm-up acts through the bias's temperature slope, and a slope of about zero
// leaves them nothing to act on; a scale tempco needs the stimulus at temperatures apart). Such a
// candidate is "not testable here" with the reason, never a detection limit.
// Ranges, in the components' units (docs/diagnose.md "Not testable here"): delay <= 3,600 s and
// <= the recording's duration; initial_excess <= 20 degC; ppm/degC <= 10,000; ppm/degC^2 <= 100.
// ADS bridges (Pa): a half loop <= 1 % and a departure from the polynomial <= 2 % of the pressure
// travel the points visit.
// Left out: the IMU's effects with no stated range (hysteresis, g-sensitivity, nonlinearity).
#pragma once

#include <string>
#include <vector>

#include "diagnosis/diagnosis_result.h"

namespace adahrs::diagnosis {

/// The largest magnitude a component of this name and unit can physically have; infinity when
/// none is stated. `duration_s` is the recording's length (a delay beyond it is not seen as one).
double PlausibleMagnitude(const std::string& component, const std::string& unit, double duration_s);

/// Empty when every component's smallest detectable magnitude in `limits` lies within its
/// plausible range; else the reason, beginning "not testable here: ".
std::string NotTestableReason(const std::vector<FindingComponent>& limits, double duration_s);

/// As NotTestableReason for an ADS bridge's components (Pa): a half loop beyond 1 %, any other
/// component beyond 2 % of `travel_pa`, the pressure range its points visit.
std::string NotTestableBridgeReason(const std::vector<FindingComponent>& limits, double travel_pa);

}  // namespace adahrs::diagnosis
