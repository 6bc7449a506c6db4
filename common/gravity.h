// WGS-84 normal gravity: the magnitude of gravity (gravitation plus centrifugal) of the WGS-84
// ellipsoid at a point, Somigliana's closed formula on the ellipsoid and the second-order
// free-air (height) correction above it (NIMA TR8350.2, 3rd ed., eqs. 4-1 and 4-3; the
// Somigliana constants are shared/physics.md §6 row 12, V [GRAV]):
//
//   γ0(φ) = γe·(1 + k·sin²φ) / sqrt(1 − e²·sin²φ)
//   γ(φ, h) = γ0·[1 − (2/a)·(1 + f + m − 2f·sin²φ)·h + (3/a²)·h²]
//
// φ geodetic latitude, h height above the ellipsoid (m). The linear term is the free-air
// gradient, −3.086e-6 s⁻² at 45° (about ±0.1 % from equator to pole).
//
// Use it for the local gravity of a lab instead of 9.80665 m/s² (physics.md §6 row 12).
// Not modelled: gravity anomalies and deflection of the vertical (typically 10…100 µm/s²,
// i.e. up to 1e-5 relative), the geoid–ellipsoid separation (a height datum question left to
// the caller), tides (≤ 3 µm/s²).
#pragma once

namespace adahrs::common {

/// Normal gravity magnitude (m/s²) at geodetic latitude `geodetic_latitude_deg` in [−90, 90]
/// and ellipsoidal height `height_m` in [−1000, 20000] m; throws std::domain_error outside.
double NormalGravityMps2(double geodetic_latitude_deg, double height_m);

}  // namespace adahrs::common
