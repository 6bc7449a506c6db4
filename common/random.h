// Deterministic random numbers for the simulator: xoshiro256++ (Blackman & Vigna, 2019) seeded
// through splitmix64, with Gaussian draws by the ziggurat method (Marsaglia & Tsang, 2000, 128
// layers) taking the layer index and the value from separate bits of one 64-bit draw, which avoids
// the correlation Doornik (2005) found in the original. Same seed, same stream, on every platform:
// nothing here depends on the standard library's distribution implementations.
// Streams for independent purposes (one unit's parameter draw, one sensor's noise) are derived
// with `Rng::Derive(seed, stream_id)` so adding a stream never shifts another.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>

namespace adahrs::common {

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

  /// Standard normal N(0, 1). Inline is only the common case (the draw lands inside its layer's
  /// box, ~97 % of draws); the rest is out of line so that callers keep their values in registers
  /// across a draw instead of saving them around a possible libm call.
  double Normal() {
    const uint64_t bits = NextU64();
    const int layer = static_cast<int>(bits & 127);
    const auto hz = static_cast<int32_t>(bits >> 32);
    const ZigguratTables& t = Tables();
    if (std::abs(static_cast<int64_t>(hz)) < t.k[layer]) [[likely]]
      return hz * t.w[layer];
    return NormalOutsideBox(layer, hz);
  }

  /// Two independent standard normals from one 64-bit draw: each 32-bit half is a ziggurat draw of
  /// its own, the layer from the half's low 7 bits and the value from its other 25 bits (the
  /// resolution of Marsaglia and Tsang's original 32-bit RNOR, without its overlap of layer and
  /// value bits). A half outside its box goes on as in Normal(), with fresh 64-bit draws. The noise
  /// models take their per-frame normals in pairs: one generator step for two normals.
  std::array<double, 2> NormalPair() {
    const uint64_t bits = NextU64();
    const ZigguratTables& t = Tables();
    std::array<double, 2> z;
    for (int half = 0; half < 2; ++half) {
      const auto word = static_cast<uint32_t>(bits >> (32 * half));
      const int layer = static_cast<int>(word & 127);
      const auto hz = static_cast<int32_t>(word & ~uint32_t{127});
      z[half] = std::abs(static_cast<int64_t>(hz)) < t.k[layer] ? hz * t.w[layer]
                                                                : NormalOutsideBox(layer, hz);
    }
    return z;
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
  // Normal() for a draw outside its layer's box: the tail or wedge test, then fresh draws until
  // one is accepted. Never inlined (see Normal()).
  [[gnu::noinline]] double NormalOutsideBox(int layer, int32_t hz) {
    const ZigguratTables& t = Tables();
    for (;;) {
      const double x = hz * t.w[layer];
      if (layer == 0) {
        // The tail beyond r, by Marsaglia's exponential rejection.
        double tail, y;
        do {
          tail = -std::log(1.0 - Uniform()) / kZigguratR;
          y = -std::log(1.0 - Uniform());
        } while (y + y < tail * tail);
        return hz > 0 ? kZigguratR + tail : -kZigguratR - tail;
      }
      // The wedge between the box and the density.
      if (t.f[layer] + Uniform() * (t.f[layer - 1] - t.f[layer]) < std::exp(-0.5 * x * x)) {
        return x;
      }
      const uint64_t bits = NextU64();
      layer = static_cast<int>(bits & 127);
      hz = static_cast<int32_t>(bits >> 32);
      if (std::abs(static_cast<int64_t>(hz)) < t.k[layer]) return hz * t.w[layer];
    }
  }

  static uint64_t Rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  static uint64_t SplitMix64(uint64_t& x) {
    uint64_t z = (x += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }

  // Ziggurat of 128 layers of equal area v under exp(−x²/2); r is the start of the tail.
  static constexpr double kZigguratR = 3.442619855899;
  static constexpr double kZigguratV = 9.91256303526217e-3;
  struct ZigguratTables {
    int64_t k[128];
    double w[128];
    double f[128];
  };
  static const ZigguratTables& Tables() {
    static const ZigguratTables tables = [] {
      ZigguratTables t{};
      constexpr double m = 2147483648.0;  // 2^31: hz is a signed 32-bit integer
      double d = kZigguratR, prev = kZigguratR;
      const double q = kZigguratV / std::exp(-0.5 * d * d);
      t.k[0] = static_cast<int64_t>((d / q) * m);
      t.k[1] = 0;
      t.w[0] = q / m;
      t.w[127] = d / m;
      t.f[0] = 1.0;
      t.f[127] = std::exp(-0.5 * d * d);
      for (int i = 126; i >= 1; --i) {
        d = std::sqrt(-2.0 * std::log(kZigguratV / d + std::exp(-0.5 * d * d)));
        t.k[i + 1] = static_cast<int64_t>((d / prev) * m);
        prev = d;
        t.f[i] = std::exp(-0.5 * d * d);
        t.w[i] = d / m;
      }
      return t;
    }();
    return tables;
  }

  uint64_t state_[4];
};

}  // namespace adahrs::common
