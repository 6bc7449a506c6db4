#include "calib/ads_calibration/ads_calibration_points.h"

#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "common/air_data.h"
#include "common/atmosphere.h"

namespace adahrs::calib {
namespace {

using hil::RejectedInterval;

bool Rejected(const std::vector<RejectedInterval>& intervals, const hil::AdsRecordRow& row) {
  for (const RejectedInterval& r : intervals) {
    if (r.step == row.step && row.t_s >= r.t_start_s && row.t_s <= r.t_end_s) return true;
  }
  return false;
}

void CheckFinite(double value, const char* column, int line, const std::string& source) {
  if (!std::isfinite(value)) {
    throw std::runtime_error(fmt::format(
        "{}/ads.csv line {} column {}: value {} is not finite", source, line, column, value));
  }
}

// The ADS1254's output word: 24-bit two's complement (datasheet), so its rails are these codes.
constexpr int32_t kAdcMaxCode = (1 << 23) - 1;
constexpr int32_t kAdcMinCode = -(1 << 23);

void CheckNotSaturated(int32_t code, const char* column, int line, const std::string& source) {
  if (code >= kAdcMaxCode || code <= kAdcMinCode) {
    throw std::runtime_error(fmt::format(
        "{}/ads.csv line {} column {}: code {} is at the ADS1254 rail (saturated input)",
        source,
        line,
        column,
        code));
  }
}

// A point's truth is the test set's pressure; if that moved within the acquisition, the mean pairs
// codes and references of different pressures. `E` is AdsPointSelector's extremes of a column.
template <typename E>
void CheckSteady(const E& e, const char* column, int step, const std::string& source) {
  if (e.max - e.min <= kMaxReferenceSpanPa) return;
  throw std::runtime_error(fmt::format(
      "{}/ads.csv lines {} and {} column {}: the test set's reference moved {:.1f} Pa within step "
      "{}'s acquisition ({:.1f} to {:.1f} Pa; limit {:.0f} Pa): not a steady point (reject the "
      "interval in meta.json or repeat the step)",
      source,
      std::min(e.min_line, e.max_line),
      std::max(e.min_line, e.max_line),
      column,
      e.max - e.min,
      step,
      e.min,
      e.max,
      kMaxReferenceSpanPa));
}

}  // namespace

void AdsPointSelector::Extremes::Add(double v, int line, bool first) {
  if (first || v < min) min = v, min_line = line;
  if (first || v > max) max = v, max_line = line;
}

AdsPointSelector::AdsPointSelector(const hil::RecordingMeta& meta,
                                   std::string serial,
                                   std::string source)
    : serial_(std::move(serial)), source_(std::move(source)), rejected_(meta.rejected_intervals) {}

void AdsPointSelector::Add(const hil::AdsRecordRow& row, int line) {
  if (row.unit != serial_) return;
  unit_seen_ = true;
  if (row.tag == 0 || Rejected(rejected_, row)) return;
  CheckFinite(row.ps_ref_pa, "ps_ref_pa", line, source_);
  CheckFinite(row.qc_ref_pa, "qc_ref_pa", line, source_);
  CheckFinite(row.chamber_c, "chamber_c", line, source_);
  CheckNotSaturated(row.ps_cnt, "ps_cnt", line, source_);
  CheckNotSaturated(row.pt_cnt, "pt_cnt", line, source_);
  CheckNotSaturated(row.ps_temp_cnt, "ps_temp_cnt", line, source_);
  CheckNotSaturated(row.pt_temp_cnt, "pt_temp_cnt", line, source_);
  Sum& s = by_step_[row.step];
  if (s.point.rows == 0) {
    s.point.step = row.step;
    s.point.tag = row.tag;
    s.point.first_line = line;
  } else if (s.point.tag != row.tag) {
    throw std::runtime_error(fmt::format(
        "{}/ads.csv line {} column tag: unit {} step {} carries tag {} after tag {} (line {})",
        source_,
        line,
        serial_,
        row.step,
        row.tag,
        s.point.tag,
        s.point.first_line));
  }
  s.ps_ref_range.Add(row.ps_ref_pa, line, s.point.rows == 0);
  s.qc_ref_range.Add(row.qc_ref_pa, line, s.point.rows == 0);
  ++s.point.rows;
  s.ps += row.ps_cnt;
  s.pt += row.pt_cnt;
  s.ps_t += row.ps_temp_cnt;
  s.pt_t += row.pt_temp_cnt;
  s.ps_ref += row.ps_ref_pa;
  s.qc_ref += row.qc_ref_pa;
  s.chamber += row.chamber_c;
}

std::vector<AdsCalibrationPoint> AdsPointSelector::Points() const {
  if (!unit_seen_) {
    throw std::runtime_error(
        fmt::format("{}/ads.csv: no row of unit {} (column unit)", source_, serial_));
  }
  std::vector<AdsCalibrationPoint> out;
  for (const auto& [step, s] : by_step_) {
    CheckSteady(s.ps_ref_range, "ps_ref_pa", step, source_);
    CheckSteady(s.qc_ref_range, "qc_ref_pa", step, source_);
    AdsCalibrationPoint p = s.point;
    const double n = p.rows;
    p.ps_cnt = s.ps / n;
    p.pt_cnt = s.pt / n;
    p.ps_temp_cnt = s.ps_t / n;
    p.pt_temp_cnt = s.pt_t / n;
    p.ps_ref_pa = s.ps_ref / n;
    p.qc_ref_pa = s.qc_ref / n;
    p.chamber_c = s.chamber / n;
    try {
      p.alt_ft = common::IsaPressureAltitudeFt(p.ps_ref_pa);
      p.cas_kt = common::CalibratedAirspeedKt(std::max(0.0, p.qc_ref_pa));
    } catch (const std::domain_error& e) {
      throw std::runtime_error(fmt::format(
          "{}/ads.csv line {} columns ps_ref_pa/qc_ref_pa: step {} reference outside ISA: {}",
          source_,
          p.first_line,
          step,
          e.what()));
    }
    p.airspeed_point = p.cas_kt >= kMinAirspeedPointKt;
    out.push_back(p);
  }
  return out;
}

std::vector<AdsCalibrationPoint> SelectAdsCalibrationPoints(const hil::Recording& recording,
                                                            const std::string& serial,
                                                            const std::string& source) {
  AdsPointSelector selector(recording.meta, serial, source);
  for (size_t i = 0; i < recording.ads.size(); ++i) {
    selector.Add(recording.ads[i], static_cast<int>(i) + 2);  // line 1 is the header
  }
  return selector.Points();
}

std::map<std::string, std::vector<AdsCalibrationPoint>> StreamAdsCalibrationPoints(
    const std::filesystem::path& run_dir,
    const std::vector<std::string>& serials,
    const std::string& source) {
  const hil::RecordingMeta meta = hil::ReadRecordingMeta(run_dir).meta;
  std::vector<AdsPointSelector> selectors;
  for (const std::string& serial : serials) selectors.emplace_back(meta, serial, source);
  hil::RowSinks sinks;
  sinks.ads = [&](hil::AdsRecordRow&& row, int line) {
    for (AdsPointSelector& s : selectors) s.Add(row, line);
  };
  hil::StreamRecording(run_dir, sinks);
  std::map<std::string, std::vector<AdsCalibrationPoint>> out;
  for (size_t i = 0; i < serials.size(); ++i) out[serials[i]] = selectors[i].Points();
  return out;
}

}  // namespace adahrs::calib
