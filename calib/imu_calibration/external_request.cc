#include "calib/imu_calibration/external_request.h"

#include <cmath>
#include <map>
#include <tuple>

#include "common/imu_layout.h"
#include "firmware_model/reference_compensator.h"

namespace adahrs::calib {
namespace {

namespace fm = firmware_model;

const char* SegmentName(ThermalSegment s) {
  switch (s) {
    case ThermalSegment::kUpRamp:
      return "up";
    case ThermalSegment::kDownRamp:
      return "down";
    case ThermalSegment::kSoak:
      return "soak";
  }
  return "soak";
}

// The raw outputs U of a packet: duty for the accelerometers, counts for the gyros.
std::array<double, 9> RawOutputs(const ImuSample& s) {
  static const fm::ImuCalibrationConstants kNone{};
  return fm::ImuReference(kNone, fm::ImuCompensationMode::kRaw, s.raw);
}

// Mean and sample standard deviation (0 for one value), by Welford's recurrence.
struct Moments {
  long long n = 0;
  double mean = 0.0;
  double m2 = 0.0;
  void Add(double x) {
    ++n;
    const double delta = x - mean;
    mean += delta / static_cast<double>(n);
    m2 += delta * (x - mean);
  }
  double Sd() const { return n > 1 ? std::sqrt(m2 / static_cast<double>(n - 1)) : 0.0; }
};

nlohmann::json AcquisitionJson(const ImuAcquisition& a, bool samples) {
  std::array<Moments, 9> u;
  std::array<Moments, 3> temp;
  Moments chamber;
  nlohmann::json rows_u = nlohmann::json::array(), rows_t = nlohmann::json::array();
  for (const ImuSample& s : a.samples) {
    const std::array<double, 9> out = RawOutputs(s);
    for (int ch = 0; ch < 9; ++ch) u[ch].Add(out[ch]);
    for (int j = 0; j < 3; ++j) temp[j].Add(s.raw.temp_cnt[j]);
    chamber.Add(s.chamber_c);
    if (samples) {
      rows_u.push_back(out);
      rows_t.push_back({s.raw.temp_cnt[0], s.raw.temp_cnt[1], s.raw.temp_cnt[2]});
    }
  }
  nlohmann::json j;
  j["run"] = a.samples.empty() ? 0 : a.samples.front().run;
  j["step"] = a.step;
  j["kind"] = a.step_kind;
  j["orientation"] = a.orientation;
  j["up_B"] = UpAxisOf(a.orientation);
  j["rate_dps"] = a.rate_dps;
  j["chamber_c"] = chamber.mean;
  j["count"] = a.samples.size();
  for (const char* key : {"u_mean", "u_sd", "temp_mean_cnt", "temp_sd_cnt"}) {
    j[key] = nlohmann::json::array();
  }
  for (const Moments& m : u) {
    j["u_mean"].push_back(m.mean);
    j["u_sd"].push_back(m.Sd());
  }
  for (const Moments& m : temp) {
    j["temp_mean_cnt"].push_back(m.mean);
    j["temp_sd_cnt"].push_back(m.Sd());
  }
  if (samples) j["samples"] = {{"u", std::move(rows_u)}, {"temp_cnt", std::move(rows_t)}};
  return j;
}

nlohmann::json ChannelTableJson() {
  nlohmann::json table = nlohmann::json::array();
  for (const common::ImuChannel& c : common::kImuChannels) {
    table.push_back({{"name", c.name},
                     {"axis", c.axis},
                     {"sign", c.sign},
                     {"thermometer", c.thermometer},
                     {"gyro", c.gyro}});
  }
  return table;
}

}  // namespace

std::vector<ThermalBandSums> SumThermalBands(const ImuUnitData& unit, double band_width_cnt) {
  using Key = std::tuple<int, long long, int>;  // thermometer, band, segment
  std::map<Key, ThermalBandSums> bands;
  for (size_t i = 0; i < unit.thermal.size(); ++i) {
    const ImuSample& s = unit.thermal[i];
    const ThermalSegment segment = unit.thermal_segment[i];
    const std::array<double, 9> out = RawOutputs(s);
    for (int j = 0; j < 3; ++j) {
      const double t = s.raw.temp_cnt[j];
      const long long band = static_cast<long long>(std::floor(t / band_width_cnt));
      const Key key{j, band, static_cast<int>(segment)};
      ThermalBandSums& b = bands[key];
      if (b.count == 0) {
        b.thermometer = j;
        b.band = band;
        b.segment = segment;
        b.pivot_cnt = static_cast<double>(band) * band_width_cnt;
        b.temp_min_cnt = b.temp_max_cnt = t;
        for (int ch = 0; ch < 9; ++ch) {
          if (common::kImuChannels[ch].thermometer == j) b.channels.push_back({ch, {}, 0.0, 0.0});
        }
      }
      ++b.count;
      b.temp_min_cnt = std::min(b.temp_min_cnt, t);
      b.temp_max_cnt = std::max(b.temp_max_cnt, t);
      const double d = t - b.pivot_cnt;
      double dk = 1.0;
      for (int k = 0; k < 4; ++k) b.d_sums[k] += (dk *= d);
      for (ThermalBandSums::Channel& c : b.channels) {
        const double y = out[c.channel];
        c.u_sums[0] += y;
        c.u_sums[1] += d * y;
        c.u_sums[2] += d * d * y;
        // Welford's recurrence over the band's rows: count is this row's ordinal.
        const double delta = y - c.u_mean;
        c.u_mean += delta / static_cast<double>(b.count);
        c.u_m2 += delta * (y - c.u_mean);
      }
    }
  }
  std::vector<ThermalBandSums> result;
  for (auto& entry : bands) result.push_back(std::move(entry.second));
  return result;
}

nlohmann::json ToJson(const ThermalBandSums& b) {
  nlohmann::json channels = nlohmann::json::array();
  for (const ThermalBandSums::Channel& c : b.channels) {
    channels.push_back(
        {{"channel", c.channel}, {"u_sums", c.u_sums}, {"u_mean", c.u_mean}, {"u_m2", c.u_m2}});
  }
  return {{"thermometer", b.thermometer},
          {"band", b.band},
          {"segment", SegmentName(b.segment)},
          {"pivot_cnt", b.pivot_cnt},
          {"count", b.count},
          {"temp_min_cnt", b.temp_min_cnt},
          {"temp_max_cnt", b.temp_max_cnt},
          {"d_sums", b.d_sums},
          {"channels", std::move(channels)}};
}

nlohmann::json ExternalImuRequest(const ImuUnitData& unit,
                                  const ImuRunData& data,
                                  const ExternalRequestHeader& header) {
  nlohmann::json j;
  j["protocol"] = kExternalRequestName;
  j["protocol_version"] = kExternalProtocolVersion;
  j["kind"] = "imu";
  j["serial"] = unit.serial;
  j["strategy"] = header.strategy;
  j["options"] = header.options;
  j["firmware_format"] = header.firmware_format;
  j["local_gravity_mps2"] = data.local_gravity_mps2;
  j["recordings"] = nlohmann::json::array();
  for (size_t i = 0; i < data.recordings.size(); ++i) {
    j["recordings"].push_back(
        {{"path", data.recordings[i].path},
         {"sha256", data.recordings[i].sha256},
         {"sequence", i < data.sequence_names.size() ? data.sequence_names[i] : ""}});
  }
  j["channels"] = ChannelTableJson();
  j["acquisitions"] = nlohmann::json::array();
  for (const auto* list : {&unit.accel, &unit.gyro, &unit.cross_axis}) {
    for (const ImuAcquisition& a : *list) {
      j["acquisitions"].push_back(AcquisitionJson(a, header.inputs.acquisition_samples));
    }
  }
  if (unit.thermal.empty()) {
    j["thermal"] = nullptr;
  } else {
    nlohmann::json bands = nlohmann::json::array();
    for (const ThermalBandSums& b : SumThermalBands(unit, header.inputs.thermal_band_width_cnt)) {
      bands.push_back(ToJson(b));
    }
    j["thermal"] = {{"band_width_cnt", header.inputs.thermal_band_width_cnt},
                    {"orientation",
                     unit.thermal_orientation == 0 ? nlohmann::json(nullptr)
                                                   : nlohmann::json(unit.thermal_orientation)},
                    {"bands", std::move(bands)}};
  }
  j["excluded_rows"] = unit.exclusions.size();
  return j;
}

}  // namespace adahrs::calib
