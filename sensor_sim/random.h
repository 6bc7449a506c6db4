// Deterministic random numbers for the simulator: xoshiro256++ (Blackman & Vigna, 2019) seeded
// through splitmix64, with Gaussian draws by the Marsaglia polar method. Same seed, same stream,
// on every platform: nothing here depends on the standard library's distribution implementations.
// Streams for independent purposes (one unit's parameter draw, one sensor's noise) are derived
// with `Rng::Derive(seed, stream_id)` so adding a stream never shifts another.
#pragma once

#include <cmath>
#include <cstdint>

namespace adahrs::sensor_sim {

class Rng {
 public:
  explicit Rng(uint64_t seed) {
    uint64_t x = seed;
    for (uint64_t& word : state_) word = SplitMix64(x);
  }

  /// A seed for an independent stream `stream_id` of `seed`.
  static uint64_t Derive(uint64_t seed, uint64_t stream_id) {
    uint64_t x = seed ^ (0x9E3779B97F4A7C15ULL * (stream_id + 1));
    return SplitMix64(x);
  }

  uint64_t NextU64() {
    const uint64_t result = Rotl(state_[0] + state_[3], 23) + state_[0];
    const uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = Rotl(state_[3], 45);
    return result;
  }

  /// Uniform in [0, 1) with 53 random bits.
  double Uniform() { return static_cast<double>(NextU64() >> 11) * 0x1.0p-53; }

  /// Uniform in [lo, hi).
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }

  /// Standard normal N(0, 1).
  double Normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u, v, s;
    do {
      u = 2.0 * Uniform() - 1.0;
      v = 2.0 * Uniform() - 1.0;
      s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    const double m = std::sqrt(-2.0 * std::log(s) / s);
    spare_ = v * m;
    has_spare_ = true;
    return u * m;
  }

  /// A per-unit draw of a datasheet quantity given as nominal ± tolerance: normal with the
  /// tolerance at 3 sigma, truncated at the tolerance (a datasheet min/max is a screening limit).
  double Tolerance(double nominal, double tolerance) {
    if (tolerance <= 0.0) return nominal;
    double z;
    do {
      z = Normal();
    } while (std::fabs(z) > 3.0);
    return nominal + tolerance * z / 3.0;
  }

 private:
  static uint64_t Rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  static uint64_t SplitMix64(uint64_t& x) {
    uint64_t z = (x += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }

  uint64_t state_[4];
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace adahrs::sensor_sim
