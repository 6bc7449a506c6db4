#include "firmware_model/golden_vectors.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <string>

#include "firmware_model/unit_firmware.h"

namespace adahrs::firmware_model {
namespace {

using nlohmann::json;

template <typename Constants, typename ReadFn>
json Blocks(const Constants& c, const std::vector<uint8_t>& ids, ReadFn read) {
  json blocks = json::array();
  for (uint8_t id : ids) {
    constexpr uint8_t kCapacity = std::max(kImuMaxBlockWords, kAdsMaxBlockWords);
    int16_t words[kCapacity];
    uint8_t count = 0;
    if (read(&c, id, words, kCapacity, &count) != ConstantsStatus::kOk) {
      throw std::logic_error("golden vectors: block " + std::to_string(id) + " cannot be read");
    }
    blocks.push_back({{"id", id}, {"words", std::vector<int16_t>(words, words + count)}});
  }
  return blocks;
}

json ImuModes(const ImuConstants& c, const ImuRawFrame& raw) {
  json modes = json::array();
  for (uint8_t m = 0; m <= 3; ++m) {
    DspEngine engine;
    ImuCompensatedFrame out{};
    ImuCompensate(&engine, c, static_cast<ImuCompensationMode>(m), raw, &out);
    modes.push_back({{"mode", m},
                     {"value", std::vector<int32_t>(out.value, out.value + kImuOutputValues)},
                     {"flags", out.flags},
                     {"cycles", engine.cycles()}});
  }
  return modes;
}

// Both modes of one frame; the surface mode advances `state` (kRaw leaves it alone).
json AdsModes(const AdsConstants& c, const AdsRawFrame& raw, AdsHysteresisState* state) {
  json modes = json::array();
  for (uint8_t m = 0; m <= 1; ++m) {
    DspEngine engine;
    AdsCompensatedFrame out{};
    AdsCompensate(&engine, c, static_cast<AdsCompensationMode>(m), raw, state, &out);
    modes.push_back({{"mode", m},
                     {"value", std::vector<int32_t>(out.value, out.value + kAdsOutputValues)},
                     {"flags", out.flags},
                     {"cycles", engine.cycles()}});
  }
  return modes;
}

std::string Compare(const json& expected, const json& got, const std::string& where) {
  for (size_t m = 0; m < expected.size(); ++m) {
    for (const char* key : {"value", "flags", "cycles"}) {
      if (expected[m][key] != got[m][key]) {
        std::ostringstream s;
        s << where << " mode " << expected[m]["mode"] << " " << key << ": expected "
          << expected[m][key] << ", got " << got[m][key];
        return s.str();
      }
    }
  }
  return "";
}

}  // namespace

json MakeCompensatorGolden(const ImuConstants& imu,
                           const AdsConstants& ads,
                           const std::vector<ImuRawFrame>& imu_frames,
                           const std::vector<AdsRawFrame>& ads_frames) {
  json doc;
  doc["format"] = 1;
  // A format-2 set is its blocks 0x01..0x0F; a set whose format-3 stages are on adds 0x10..0x1B.
  const uint8_t last = imu.scale_temperature.enabled != 0 ? kImuBlockLast : uint8_t{kImuBlockCg};
  std::vector<uint8_t> imu_ids;
  for (uint8_t id = kImuBlockThermalFirst; id <= last; ++id) imu_ids.push_back(id);
  doc["imu"]["blocks"] = Blocks(imu, imu_ids, ImuConstantsReadBlock);
  doc["imu"]["frames"] = json::array();
  for (const ImuRawFrame& f : imu_frames) {
    doc["imu"]["frames"].push_back({{"t1_cnt", f.t1_cnt},
                                    {"t2_cnt", f.t2_cnt},
                                    {"gyro_cnt", f.gyro_cnt},
                                    {"temp_cnt", f.temp_cnt},
                                    {"modes", ImuModes(imu, f)}});
  }
  doc["ads"]["blocks"] = Blocks(ads, {kAdsBlockAltitude, kAdsBlockAirspeed}, AdsConstantsReadBlock);
  doc["ads"]["frames"] = json::array();
  AdsHysteresisState state;
  AdsHysteresisReset(&state);
  for (const AdsRawFrame& f : ads_frames) {
    doc["ads"]["frames"].push_back({{"ps_code", f.ps_cnt},
                                    {"pt_code", f.pt_cnt},
                                    {"ps_bridge_code", f.ps_bridge_cnt},
                                    {"pt_bridge_code", f.pt_bridge_cnt},
                                    {"oat_code", f.oat_cnt},
                                    {"modes", AdsModes(ads, f, &state)}});
  }
  return doc;
}

std::string ReplayCompensatorGolden(const json& golden) {
  ImuConstants imu;
  ImuConstantsInit(&imu);
  for (const json& b : golden.at("imu").at("blocks")) {
    const std::vector<int16_t> words = b.at("words").get<std::vector<int16_t>>();
    const ConstantsStatus s = ImuConstantsWriteBlock(
        &imu, b.at("id").get<uint8_t>(), words.data(), static_cast<uint8_t>(words.size()));
    if (s != ConstantsStatus::kOk) return "IMU block " + b.at("id").dump() + " refused";
  }
  AdsConstants ads;
  AdsConstantsInit(&ads);
  for (const json& b : golden.at("ads").at("blocks")) {
    const std::vector<int16_t> words = b.at("words").get<std::vector<int16_t>>();
    const ConstantsStatus s = AdsConstantsWriteBlock(
        &ads, b.at("id").get<uint8_t>(), words.data(), static_cast<uint8_t>(words.size()));
    if (s != ConstantsStatus::kOk) return "ADS block " + b.at("id").dump() + " refused";
  }
  const json& imu_frames = golden.at("imu").at("frames");
  for (size_t i = 0; i < imu_frames.size(); ++i) {
    const json& f = imu_frames[i];
    ImuRawFrame raw{};
    for (int k = 0; k < 6; ++k) {
      raw.t1_cnt[k] = f.at("t1_cnt")[k].get<uint16_t>();
      raw.t2_cnt[k] = f.at("t2_cnt")[k].get<uint16_t>();
    }
    for (int k = 0; k < 3; ++k) {
      raw.gyro_cnt[k] = f.at("gyro_cnt")[k].get<int32_t>();
      raw.temp_cnt[k] = f.at("temp_cnt")[k].get<uint16_t>();
    }
    const std::string diff =
        Compare(f.at("modes"), ImuModes(imu, raw), "IMU frame " + std::to_string(i));
    if (!diff.empty()) return diff;
  }
  const json& ads_frames = golden.at("ads").at("frames");
  AdsHysteresisState state;
  AdsHysteresisReset(&state);
  for (size_t i = 0; i < ads_frames.size(); ++i) {
    const json& f = ads_frames[i];
    const AdsRawFrame raw{f.at("ps_code").get<int32_t>(),
                          f.at("pt_code").get<int32_t>(),
                          f.at("ps_bridge_code").get<int32_t>(),
                          f.at("pt_bridge_code").get<int32_t>(),
                          f.at("oat_code").get<int32_t>()};
    const std::string diff =
        Compare(f.at("modes"), AdsModes(ads, raw, &state), "ADS frame " + std::to_string(i));
    if (!diff.empty()) return diff;
  }
  return "";
}

}  // namespace adahrs::firmware_model
