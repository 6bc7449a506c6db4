#include "diagnosis/slow_noise.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace adahrs::diagnosis {
namespace {

constexpr size_t kMaxBlocks = 600;    // pairs grow as its square
constexpr double kLagBinRatio = 1.5;  // geometric lag bins from 1 s
constexpr double kBinZ = 2.0;         // a bin counts what lies 2 of its standard errors above 0

struct Block {
  int run = 0;
  double t_s = 0.0;
  double mean = 0.0;       // of the residual
  double white_var = 0.0;  // of that mean
  double weight = 0.0;     // sum of the cells' a_i
};

// Consecutive cells of one segment, at most `cells.size() / kMaxBlocks` (rounded up) per block.
std::vector<Block> MakeBlocks(const std::vector<SlowNoiseCell>& cells) {
  const size_t per = std::max<size_t>(1, (cells.size() + kMaxBlocks - 1) / kMaxBlocks);
  std::vector<Block> out;
  size_t n = 0;
  for (size_t i = 0; i < cells.size(); ++i) {
    const SlowNoiseCell& c = cells[i];
    const bool fresh =
        i == 0 || n == per || c.segment != cells[i - 1].segment || c.run != cells[i - 1].run;
    if (fresh) {
      out.push_back({c.run, 0.0, 0.0, 0.0, 0.0});
      n = 0;
    }
    Block& b = out.back();
    ++n;
    b.t_s += (c.t_s - b.t_s) / static_cast<double>(n);
    b.mean += (c.residual - b.mean) / static_cast<double>(n);
    b.white_var += c.white_var;  // divided by n^2 below
    b.weight += c.weight;
    if (i + 1 == cells.size() || n == per || cells[i + 1].segment != c.segment ||
        cells[i + 1].run != c.run)
      b.white_var /= static_cast<double>(n) * static_cast<double>(n);
  }
  return out;
}

size_t LagBin(double lag_s) {
  if (!(lag_s > 1.0)) return 0;
  return static_cast<size_t>(std::log(lag_s) / std::log(kLagBinRatio)) + 1;
}

// The wander's variogram per lag bin: mean squared difference of block means less their white
// variance, less 2 of its standard errors (so the maximum over many bins of white noise stays
// near 0), at least 0 and non-decreasing in lag (a wander's spread does not shrink with time).
std::vector<double> Variogram(const std::vector<Block>& blocks) {
  std::vector<double> sum, sum2, count;
  for (size_t i = 0; i < blocks.size(); ++i) {
    for (size_t j = i + 1; j < blocks.size(); ++j) {
      if (blocks[i].run != blocks[j].run) continue;
      const size_t bin = LagBin(std::abs(blocks[j].t_s - blocks[i].t_s));
      if (bin >= sum.size()) {
        sum.resize(bin + 1, 0.0);
        sum2.resize(bin + 1, 0.0);
        count.resize(bin + 1, 0.0);
      }
      const double d = blocks[j].mean - blocks[i].mean;
      const double g = d * d - blocks[i].white_var - blocks[j].white_var;
      sum[bin] += g;
      sum2[bin] += g * g;
      count[bin] += 1.0;
    }
  }
  std::vector<double> gamma(sum.size(), 0.0);
  double running = 0.0;
  for (size_t b = 0; b < sum.size(); ++b) {
    if (count[b] > 1.0) {
      const double mean = sum[b] / count[b];
      const double se = std::sqrt(std::max(0.0, sum2[b] / count[b] - mean * mean) / count[b]);
      running = std::max(running, mean - kBinZ * se);
    }
    gamma[b] = running;
  }
  return gamma;
}

}  // namespace

double SlowNoiseVariance(const std::vector<SlowNoiseCell>& cells, double segment_offset_var) {
  double white = 0.0;
  std::map<int, double> per_segment;
  for (const SlowNoiseCell& c : cells) {
    white += c.weight * c.weight * c.white_var;
    per_segment[c.segment] += c.weight;
  }
  double offsets = 0.0;
  for (const auto& [segment, a] : per_segment) offsets += a * a * segment_offset_var;
  const std::vector<Block> blocks = MakeBlocks(cells);
  const std::vector<double> gamma = Variogram(blocks);
  double wander = 0.0;
  for (size_t i = 0; i < blocks.size() && !gamma.empty(); ++i) {
    for (size_t j = i + 1; j < blocks.size(); ++j) {
      if (blocks[i].run != blocks[j].run) continue;
      const size_t bin =
          std::min(gamma.size() - 1, LagBin(std::abs(blocks[j].t_s - blocks[i].t_s)));
      wander -= blocks[i].weight * blocks[j].weight * gamma[bin];
    }
  }
  return white + offsets + std::max(0.0, wander);
}

}  // namespace adahrs::diagnosis
