#include "calib/campaign/quick_sequences.h"

#include <algorithm>
#include <fstream>
#include <stdexcept>

#include "calib/sequence/sequence_json.h"
#include "common/param_reader.h"

namespace adahrs::calib {
namespace {

std::string WriteQuick(const std::string& file, const std::filesystem::path& dir) {
  nlohmann::json document = common::ParamReader::LoadFile(file);
  for (nlohmann::json& step : document.at("steps")) {
    if (step.contains("soak_s")) {
      step["soak_s"] = std::min(step["soak_s"].get<double>(), kQuickSoakS);
    }
    if (step.contains("packets")) {
      step["packets"] = std::min(step["packets"].get<int>(), kQuickPackets);
    }
  }
  const std::string name = document.at("name").get<std::string>() + "_quick";
  document["name"] = name;
  const std::filesystem::path path = dir / (name + ".json");
  SequenceFromJson(document, path.string());  // throws SequenceError if the variant is not valid
  std::filesystem::create_directories(dir);
  std::ofstream out(path);
  out << document.dump(2) << "\n";
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
  return path.string();
}

}  // namespace

CampaignSequences WriteQuickSequences(const CampaignSequences& s,
                                      const std::filesystem::path& dir) {
  CampaignSequences quick;
  for (const std::string& file : s.imu_calibration)
    quick.imu_calibration.push_back(WriteQuick(file, dir));
  quick.ads_calibration = WriteQuick(s.ads_calibration, dir);
  quick.imu_acceptance = WriteQuick(s.imu_acceptance, dir);
  quick.ads_acceptance = WriteQuick(s.ads_acceptance, dir);
  return quick;
}

}  // namespace adahrs::calib
