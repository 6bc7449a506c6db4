#include "calib/campaign/campaign_file.h"

#include "calib/imu_calibration/imu_strategy.h"

#include <set>

#include "calib/ads_calibration/reference_ads_strategy.h"
#include "calib/ads_calibration/tolerance_ads_strategy.h"
#include "common/param_reader.h"

namespace adahrs::calib {
namespace {

using common::ParamReader;

// Acceptance attempts the policy may allow (each a whole acceptance run of the bench); a unit
// that fails five times is not a test problem.
constexpr int64_t kMaxAttempts = 5;

std::string Resolve(const std::string& file, const std::filesystem::path& base_dir) {
  const std::filesystem::path path(file);
  return (path.is_absolute() ? path : base_dir / path).lexically_normal().string();
}

// A non-empty file name under `key`, resolved against `base_dir`.
std::string FileName(const ParamReader& r,
                     std::string_view key,
                     const std::filesystem::path& base_dir) {
  const std::string file = r.String(key);
  if (file.empty()) r.Fail(r.path() + "." + std::string(key), "expected a file name");
  return Resolve(file, base_dir);
}

std::string OneOf(const ParamReader& r, std::string_view key, const std::set<std::string>& names) {
  const std::string value = r.String(key);
  if (names.count(value) == 0) {
    std::string allowed;
    for (const std::string& n : names) allowed += (allowed.empty() ? "" : ", ") + n;
    r.Fail(r.path() + "." + std::string(key),
           "unknown strategy \"" + value + "\" (expected one of " + allowed + ")");
  }
  return value;
}

// "joint", "reference" or an IMU strategy file (resolved, read now so that a bad one is refused
// before any run; its stem names its fit directory, which may not be a built-in's).
std::string ImuStrategyOf(const ParamReader& fit, const std::filesystem::path& base_dir) {
  const std::string value = fit.String("imu");
  if (!IsImuStrategyFile(value)) return OneOf(fit, "imu", {"joint", "reference"});
  const std::string file = Resolve(value, base_dir);
  const std::string stem = ImuStrategyLabel(file);
  if (stem == "joint" || stem == "reference") {
    fit.Fail(fit.path() + ".imu",
             "a strategy file may not be called " + stem +
                 ".json (its fits would replace the built-in's)");
  }
  if (!std::filesystem::is_regular_file(file)) {
    fit.Fail(fit.path() + ".imu", "no strategy file " + file);
  }
  ImuStrategy::Load(file);
  return file;
}

CampaignSequences ReadSequences(const ParamReader& r,
                                const nlohmann::json& object,
                                const std::filesystem::path& base_dir) {
  CampaignSequences s;
  const size_t count = r.ArrayLength("imu_calibration", 1, 16);
  for (size_t i = 0; i < count; ++i) {
    const nlohmann::json& item = object.at("imu_calibration")[i];
    const std::string where = r.path() + ".imu_calibration[" + std::to_string(i) + "]";
    if (!item.is_string() || item.get<std::string>().empty()) {
      r.Fail(where, "expected a sequence file name");
    }
    s.imu_calibration.push_back(Resolve(item.get<std::string>(), base_dir));
  }
  s.ads_calibration = FileName(r, "ads_calibration", base_dir);
  s.imu_acceptance = FileName(r, "imu_acceptance", base_dir);
  s.ads_acceptance = FileName(r, "ads_acceptance", base_dir);
  r.ExpectAllKeysUsed();
  return s;
}

std::map<std::string, std::string> ReadSerials(const ParamReader& r, const nlohmann::json& object) {
  std::map<std::string, std::string> serials;
  for (const auto& [role, serial] : object.items()) {
    const std::string where = r.path() + "." + role;
    if (!serial.is_string() || serial.get<std::string>().empty()) {
      r.Fail(where, "expected the unit's serial as text (e.g. \"IMU-000123\")");
    }
    serials[role] = r.String(role);
  }
  return serials;
}

}  // namespace

CampaignFile CampaignFile::FromJson(const nlohmann::json& document,
                                    const std::string& source,
                                    const std::filesystem::path& base_dir) {
  const ParamReader r(document, source);
  const int64_t version = r.Integer("format_version", 1, 1000);
  if (version != kCampaignFileFormatVersion) {
    r.Fail("$.format_version",
           "format version " + std::to_string(version) + " is not supported (this program reads " +
               std::to_string(kCampaignFileFormatVersion) + ")");
  }
  CampaignFile c;
  c.name = r.String("name");
  c.sequences = ReadSequences(r.Child("sequences"), document.at("sequences"), base_dir);
  const ParamReader fit = r.Child("fit");
  c.imu_strategy = ImuStrategyOf(fit, base_dir);
  c.ads_strategy = OneOf(fit, "ads", {kHysteresisAdsStrategyName, kReferenceAdsStrategyName});
  fit.ExpectAllKeysUsed();
  if (r.Has("specification")) c.specification_file = FileName(r, "specification", base_dir);
  if (r.Has("expected_serials")) {
    const ParamReader serials = r.Child("expected_serials");
    c.expected_serials = ReadSerials(serials, document.at("expected_serials"));
    serials.ExpectAllKeysUsed();
  }
  const ParamReader retest = r.Child("retest");
  c.max_acceptance_attempts = static_cast<int>(retest.Integer("max_attempts", 1, kMaxAttempts));
  retest.ExpectAllKeysUsed();
  r.ExpectAllKeysUsed();
  return c;
}

CampaignFile CampaignFile::Load(const std::filesystem::path& path) {
  const std::filesystem::path absolute = std::filesystem::absolute(path);
  return FromJson(ParamReader::LoadFile(path.string()), path.string(), absolute.parent_path());
}

nlohmann::json CampaignFile::ToJson() const {
  nlohmann::json j = {{"format_version", kCampaignFileFormatVersion},
                      {"name", name},
                      {"sequences",
                       {{"imu_calibration", sequences.imu_calibration},
                        {"ads_calibration", sequences.ads_calibration},
                        {"imu_acceptance", sequences.imu_acceptance},
                        {"ads_acceptance", sequences.ads_acceptance}}},
                      {"fit", {{"imu", imu_strategy}, {"ads", ads_strategy}}},
                      {"retest", {{"max_attempts", max_acceptance_attempts}}}};
  if (!specification_file.empty()) j["specification"] = specification_file;
  if (!expected_serials.empty()) j["expected_serials"] = expected_serials;
  return j;
}

}  // namespace adahrs::calib
