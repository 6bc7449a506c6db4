#include "diagnosis/held_out_excess.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace adahrs::diagnosis {
namespace {

constexpr size_t kNamedSegments = 4;

}  // namespace

std::optional<Unexplained> HeldOutExcess(const ChannelFitSummary& summary,
                                         const ClusteredFit& final_fit,
                                         const std::vector<std::string>& labels,
                                         double scale) {
  const double noise = summary.white_noise_rms;
  if (!(noise > 0.0) || !(summary.held_out_rms_final >= kHeldOutExcessRatio * noise))
    return std::nullopt;
  std::vector<std::pair<double, size_t>> per_segment;  // held-out RMS, segment
  for (size_t c = 0; c < final_fit.held_out_ss.size() && c < final_fit.cluster_weight.size(); ++c) {
    if (std::isnan(final_fit.held_out_ss[c]) || !(final_fit.cluster_weight[c] > 0.0)) continue;
    per_segment.emplace_back(
        std::sqrt(std::max(0.0, final_fit.held_out_ss[c] / final_fit.cluster_weight[c])) * scale,
        c);
  }
  std::sort(per_segment.rbegin(), per_segment.rend());
  const size_t beyond =
      static_cast<size_t>(std::count_if(per_segment.begin(), per_segment.end(), [&](const auto& s) {
        return s.first >= kHeldOutExcessRatio * noise;
      }));
  std::string where = fmt::format("{} of {} segments held out at >= {:.0f} x the noise",
                                  beyond,
                                  per_segment.size(),
                                  kHeldOutExcessRatio);
  for (size_t i = 0; i < per_segment.size() && i < kNamedSegments; ++i) {
    const size_t c = per_segment[i].second;
    where += fmt::format("{} {} ({:.3g} {})",
                         i == 0 ? ": largest " : "; ",
                         c < labels.size() ? labels[c] : fmt::format("segment {}", c + 1),
                         per_segment[i].first,
                         summary.unit);
  }
  Unexplained u;
  u.channel = summary.channel;
  u.where = where;
  u.description = fmt::format(
      "held-out RMS {:.3g} {}, {:.1f} times the {:.3g} {} white noise alone leaves: the model "
      "does not explain this recording (a shift between stretches, a missing effect or a "
      "wandering bias)",
      summary.held_out_rms_final,
      summary.unit,
      summary.held_out_rms_final / noise,
      noise,
      summary.unit);
  u.size = summary.held_out_rms_final;
  u.unit = summary.unit;
  return u;
}

}  // namespace adahrs::diagnosis
