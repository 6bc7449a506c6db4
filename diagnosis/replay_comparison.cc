#include "diagnosis/replay_comparison.h"

#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

#include <fmt/format.h>

#include "common/imu_layout.h"
#include "diagnosis/diagnosis_cells.h"
#include "hil/recording/recording_reader.h"

namespace adahrs::diagnosis {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kAdsChannels = 2;
constexpr std::array<const char*, kAdsChannels> kAdsChannelNames = {"ps", "pt"};

// Mean and variance of a stream, about its first value (gyro counts are millions; their squares
// summed over an acquisition would lose the noise's digits).
struct Moments {
  int64_t n = 0;
  double shift = 0.0, sum = 0.0, sum_sq = 0.0;
  void Add(double x) {
    if (n == 0) shift = x;
    const double d = x - shift;
    sum += d;
    sum_sq += d * d;
    ++n;
  }
  double Mean() const { return shift + sum / static_cast<double>(n); }
  double VarianceOfMean() const {
    if (n < 2) return 0.0;
    const double var = (sum_sq - sum * sum / static_cast<double>(n)) / static_cast<double>(n - 1);
    return std::max(0.0, var) / static_cast<double>(n);
  }
};

struct Acquisition {
  std::vector<Moments> channels;
  Moments ps_ref_pa, qc_ref_pa;
};

// serial, step, tag, table rate in 0.1 °/s (a gyro step's one TAG spans all its rates).
using Key = std::tuple<std::string, int, int, long>;

struct RunMeans {
  std::map<Key, Acquisition> acquisitions;
  std::map<std::string, bool> imu;  // serial -> is an IMU
};

Acquisition& At(
    RunMeans* m, const std::string& serial, int step, int tag, long rate, size_t channels) {
  Acquisition& a = m->acquisitions[{serial, step, tag, rate}];
  if (a.channels.empty()) a.channels.resize(channels);
  return a;
}

RunMeans ReadMeans(const fs::path& run) {
  RunMeans m;
  hil::RowSinks sinks;
  sinks.imu = [&](hil::ImuRecordRow&& r, int) {
    if (r.tag == 0) return;
    m.imu[r.unit] = true;
    Acquisition& a =
        At(&m, r.unit, r.step, r.tag, std::lround(r.table_rate_dps * 10.0), kImuChannels);
    for (size_t ch = 0; ch < 6; ++ch) {
      const double t2 = r.accel_ticks[2 * ch + 1];
      if (t2 <= 0.0) continue;
      a.channels[ch].Add((r.accel_ticks[2 * ch] / t2 - 0.5) / kAccelDatasheetDutyPerG * 1000.0);
    }
    for (size_t g = 0; g < 3; ++g)
      a.channels[6 + g].Add(r.gyro_cnt[g] / kGyroDatasheetCountsPerDps);
  };
  sinks.ads = [&](hil::AdsRecordRow&& r, int) {
    if (r.tag == 0) return;
    m.imu[r.unit] = false;
    Acquisition& a = At(&m, r.unit, r.step, r.tag, 0, kAdsChannels);
    a.channels[0].Add(r.ps_cnt);
    a.channels[1].Add(r.pt_cnt);
    a.ps_ref_pa.Add(r.ps_ref_pa);
    a.qc_ref_pa.Add(r.qc_ref_pa);
  };
  hil::StreamRecording(run, sinks);
  return m;
}

// Codes per pascal of bridge `ch` of `serial`: the least-squares slope of the acquisitions' mean
// code on their mean reference pressure; 0 when the reference never moved.
double CodesPerPa(const RunMeans& m, const std::string& serial, int ch) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& [key, a] : m.acquisitions) {
    if (std::get<0>(key) != serial || a.channels[ch].n == 0) continue;
    const double x = ch == 0 ? a.ps_ref_pa.Mean() : a.qc_ref_pa.Mean(), y = a.channels[ch].Mean();
    n += 1;
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double den = n * sxx - sx * sx;
  return n >= 2 && den > 1e-9 * std::max(1.0, sxx * n) ? (n * sxy - sx * sy) / den : 0.0;
}

double Rms(const std::vector<AcquisitionResidual>& v, double AcquisitionResidual::*field) {
  double s = 0.0;
  for (const AcquisitionResidual& r : v) s += (r.*field) * (r.*field);
  return v.empty() ? 0.0 : std::sqrt(s / static_cast<double>(v.size()));
}

ChannelReplayFit CompareChannel(const std::string& serial,
                                bool imu,
                                int ch,
                                const RunMeans& rec,
                                const RunMeans& base,
                                const RunMeans& model) {
  ChannelReplayFit fit;
  fit.channel = imu ? common::kImuChannelNames[ch] : kAdsChannelNames[ch];
  double scale = 1.0;  // channel unit per mean value
  if (imu) {
    fit.unit = ch < 6 ? "mg" : "deg/s";
  } else {
    const double codes_per_pa = CodesPerPa(rec, serial, ch);
    fit.unit = codes_per_pa != 0.0 ? "Pa" : "code";
    scale = codes_per_pa != 0.0 ? 1.0 / std::abs(codes_per_pa) : 1.0;
  }
  for (const auto& [key, a] : rec.acquisitions) {
    if (std::get<0>(key) != serial) continue;
    const auto b = base.acquisitions.find(key), m = model.acquisitions.find(key);
    if (b == base.acquisitions.end() || m == model.acquisitions.end()) continue;
    const Moments &r = a.channels[ch], &rb = b->second.channels[ch], &rm = m->second.channels[ch];
    if (r.n == 0 || rb.n == 0 || rm.n == 0) continue;
    AcquisitionResidual res;
    res.label = fmt::format("step {} tag {}", std::get<1>(key), std::get<2>(key));
    if (imu && std::get<3>(key) != 0)
      res.label += fmt::format(" at {:g} deg/s", 0.1 * static_cast<double>(std::get<3>(key)));
    res.base = (r.Mean() - rb.Mean()) * scale;
    res.model = (r.Mean() - rm.Mean()) * scale;
    res.noise_se =
        std::sqrt(r.VarianceOfMean() + 0.5 * (rb.VarianceOfMean() + rm.VarianceOfMean())) * scale;
    fit.acquisitions.push_back(std::move(res));
  }
  fit.rms_base = Rms(fit.acquisitions, &AcquisitionResidual::base);
  fit.rms_model = Rms(fit.acquisitions, &AcquisitionResidual::model);
  fit.rms_noise = Rms(fit.acquisitions, &AcquisitionResidual::noise_se);
  return fit;
}

}  // namespace

json ChannelReplayFit::ToJson() const {
  json acq = json::array();
  for (const AcquisitionResidual& a : acquisitions) {
    acq.push_back(
        {{"acquisition", a.label}, {"base", a.base}, {"model", a.model}, {"noise_se", a.noise_se}});
  }
  return {{"channel", channel},
          {"unit", unit},
          {"rms_base", rms_base},
          {"rms_model", rms_model},
          {"rms_noise", rms_noise},
          {"acquisitions", acq}};
}

json UnitReplayFit::ToJson() const {
  json ch = json::array();
  for (const ChannelReplayFit& c : channels) ch.push_back(c.ToJson());
  return {{"unit_serial", serial}, {"channels", ch}};
}

json ReplayComparison::ToJson() const {
  json u = json::array();
  for (const UnitReplayFit& x : units) u.push_back(x.ToJson());
  return {{"format", "adahrs-replay-comparison"},
          {"format_version", 1},
          {"recording", recording.string()},
          {"base_replay", base_replay.string()},
          {"model_replay", model_replay.string()},
          {"held_out", held_out},
          {"units", u}};
}

ReplayComparison CompareReplays(const fs::path& recording,
                                const fs::path& base_replay,
                                const fs::path& model_replay,
                                bool held_out) {
  ReplayComparison out{recording, base_replay, model_replay, held_out, {}};
  const RunMeans rec = ReadMeans(recording), base = ReadMeans(base_replay),
                 model = ReadMeans(model_replay);
  for (const auto& [serial, imu] : rec.imu) {
    if (base.imu.count(serial) == 0 || model.imu.count(serial) == 0) continue;
    UnitReplayFit unit{serial, {}};
    for (int ch = 0; ch < (imu ? kImuChannels : kAdsChannels); ++ch) {
      ChannelReplayFit fit = CompareChannel(serial, imu, ch, rec, base, model);
      if (!fit.acquisitions.empty()) unit.channels.push_back(std::move(fit));
    }
    if (!unit.channels.empty()) out.units.push_back(std::move(unit));
  }
  if (out.units.empty()) {
    throw std::runtime_error(
        fmt::format("{} and {}: no acquisition (step and TAG) of {} in both replays",
                    base_replay.string(),
                    model_replay.string(),
                    recording.string()));
  }
  return out;
}

ReplayComparison CheckByReplay(const fs::path& run,
                               const std::vector<fs::path>& base_files,
                               const std::vector<fs::path>& model_files,
                               const fs::path& work_dir,
                               bool held_out,
                               const ReplayFunction& replay) {
  fs::remove_all(work_dir / "base");
  fs::remove_all(work_dir / "model");
  fs::create_directories(work_dir);
  replay(run, base_files, work_dir / "base");
  replay(run, model_files, work_dir / "model");
  return CompareReplays(run, work_dir / "base", work_dir / "model", held_out);
}

}  // namespace adahrs::diagnosis
