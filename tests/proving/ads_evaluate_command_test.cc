// `adahrs evaluate` on an ADS unit (apps/evaluate_command.cc, proving/evaluation/
// ads_evaluation_report.h): a drawn unit (every effect on) run through the shipped ads_calibration
// sequence, fitted with the reference strategy as the campaign fits it, its truth written in the
// rig's schema. The command's evaluation.json must be the demo truth stage's for the same files;
// its no-history errors must match an independent computation from the truth file (the unit
// stepped by the simulator, the constants through the double-precision reference compensator)
// within the exporter's own fixed-point bound; and bad input is refused naming file and JSON path.
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/campaign/campaign_fits.h"
#include "common/air_data.h"
#include "common/atmosphere.h"
#include "common/param_reader.h"
#include "firmware_model/constants_exporter.h"
#include "firmware_model/reference_compensator.h"
#include "proving/demo/truth_evaluation.h"
#include "tests/support/ads_recording_sim.h"

namespace adahrs::proving {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr char kSerial[] = "ADS-0042";

struct CommandResult {
  int status = 0;
  std::string output;  ///< stdout and stderr
};

CommandResult RunAdahrs(const std::string& args) {
  const std::string cmd = std::string(std::getenv("ADAHRS_BIN_DIR")) + "/adahrs " + args + " 2>&1";
  FILE* pipe = ::popen(cmd.c_str(), "r");
  CommandResult r;
  char buffer[4096];
  size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) r.output.append(buffer, n);
  r.status = ::pclose(pipe);
  return r;
}

nlohmann::json ReadJson(const fs::path& path) { return nlohmann::json::parse(std::ifstream(path)); }

void WriteJson(const fs::path& path, const nlohmann::json& json) {
  std::ofstream(path) << json.dump(2) << "\n";
}

// The files a simulated campaign leaves: the run, the fit, the rig's truth file; made once, on
// first use inside a test (an exception there fails that test).
struct Campaign {
  fs::path dir;
  std::vector<calib::WrittenConstants> written;

  Campaign()
      : dir(fs::temp_directory_path() / ("adahrs_ads_evaluate_" + std::to_string(::getpid()))) {
    fs::remove_all(dir);
    fs::create_directories(dir / "truth");
    const sensor_sim::AdsUnitParams truth =
        sensor_sim::AdsUnitParams::Draw(kSerial, 6042, sensor_sim::ModelProfile::kTruth);
    WriteJson(dir / "truth" / (std::string(kSerial) + ".json"),
              {{"serial", kSerial},
               {"kind", "ads"},
               {"seed", 6042},
               {"model_profile", "truth"},
               {"params", truth.ToJson()}});
    const std::string sequence = calib::testing::ShippedSequencePath("ads_calibration");
    calib::testing::WriteAdsRecording(dir / "run", sequence, truth, 19);
    // The recording as the executor leaves it: its sequence in meta.json.
    nlohmann::json meta = ReadJson(dir / "run" / "meta.json");
    meta["sequence"] = ReadJson(sequence);
    meta["sequence_file"] = "ads_calibration.json";
    WriteJson(dir / "run" / "meta.json", meta);
    written = calib::FitAdsIntoDirectory(dir / "run", "reference", dir / "fit", "test");
  }
  ~Campaign() { fs::remove_all(dir); }

  fs::path TruthPath() const { return dir / "truth" / (std::string(kSerial) + ".json"); }
  fs::path ConstantsPath() const { return written.at(0).path; }
};

const Campaign& Made() {
  static const Campaign campaign;
  return campaign;
}

TEST(AdsEvaluateCommand, WritesTheDemoStagesEvaluationForTheSameFiles) {
  const Campaign& c = Made();
  ASSERT_EQ(c.written.size(), 1u);
  const std::vector<EvaluatedQuantity> demo =
      EvaluateAgainstTruth(c.written, c.dir / "truth", 9.80665, c.dir / "demo");
  const fs::path out = c.dir / "evaluation.json";
  const CommandResult r =
      RunAdahrs("evaluate --constants '" + c.ConstantsPath().string() + "' --truth '" +
                c.TruthPath().string() + "' --out '" + out.string() + "'");
  ASSERT_EQ(r.status, 0) << r.output;
  std::printf("%s", r.output.c_str());
  const nlohmann::json e = ReadJson(out);
  EXPECT_EQ(e, ReadJson(c.dir / "demo" / "evaluation" / (std::string(kSerial) + ".json")));
  EXPECT_EQ(e["format"], "adahrs-ads-evaluation");
  EXPECT_EQ(e["serial"], kSerial);
  EXPECT_EQ(e["strategy"], "reference");
  ASSERT_EQ(demo.size(), 2u);
  for (const EvaluatedQuantity& row : demo) {
    const nlohmann::json& q = e[row.quantity == "altitude" ? "altitude_ft" : "airspeed_kt"];
    EXPECT_EQ(q["worst_ratio_no_history"].get<double>(), row.worst) << row.quantity;
    EXPECT_EQ(q["verdict"], row.verdict) << row.quantity;
    EXPECT_THAT(r.output, HasSubstr(row.verdict));
  }
  // 52 altitudes (-1,000...50,000 ft by 1,000) and 43 airspeeds (30...450 kt by 10), each at 26
  // temperatures (-40...+85 degC by 5).
  EXPECT_EQ(e["altitude_ft"]["points"].size(), 52u * 26u);
  EXPECT_EQ(e["airspeed_kt"]["points"].size(), 43u * 26u);
}

// The error without history at every grid point, recomputed from the truth file: a fresh
// noiseless unit soaked at the point, its codes through the double-precision compensator. The
// target's fixed point may differ from the double one by at most the exporter's stated bound.
TEST(AdsEvaluateCommand, ErrorsWithoutHistoryAgreeWithTheTruthFileThroughTheDoubleCompensator) {
  const Campaign& campaign = Made();
  const fs::path out = campaign.dir / "independent.json";
  const CommandResult r =
      RunAdahrs("evaluate --constants '" + campaign.ConstantsPath().string() + "' --truth '" +
                campaign.TruthPath().string() + "' --out '" + out.string() + "'");
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json e = ReadJson(out);
  const nlohmann::json file = ReadJson(campaign.TruthPath());
  sensor_sim::AdsUnitParams p = sensor_sim::AdsUnitParams::FromJson(
      common::ParamReader(file["params"], campaign.TruthPath().string(), "$.params"));
  p.static_bridge.effects.noise = false;
  p.pitot_bridge.effects.noise = false;
  p.adc.effects.noise = false;
  p.static_thermal.effects.lag = false;
  p.pitot_thermal.effects.lag = false;
  const firmware_model::AdsCalibrationConstants& c = *campaign.written.at(0).file.ads;
  ASSERT_FALSE(c.altitude_ft.hysteresis.active());  // the reference runs no operator
  const firmware_model::AdsExportReport bound = firmware_model::ExportAdsConstants(c).report;
  for (int slot : {0, 1}) {
    const bool altitude = slot == 0;
    const nlohmann::json& points = e[altitude ? "altitude_ft" : "airspeed_kt"]["points"];
    double worst_difference = 0.0, worst_ratio = 0.0;
    for (const nlohmann::json& g : points) {
      const double value = g["value"].get<double>();
      const double temp_c = g["temp_c"].get<double>();
      sensor_sim::AdsStimulus s;
      s.ps_pa = altitude ? common::IsaStaticPressurePaFromFt(value) : 101325.0;
      s.qc_pa = altitude ? 0.0 : common::ImpactPressurePaFromKt(value);
      s.air_temp_c = s.oat_c = temp_c;
      sensor_sim::AdsUnit unit(p, 0, temp_c);
      unit.Step(s);
      const sensor_sim::AdsRawFrame f = unit.Step(s);
      const double out_value = firmware_model::AdsReference(
          c,
          firmware_model::AdsCompensationMode::kSurface,
          {f.ps_cnt, f.pt_cnt, f.ps_temp_cnt, f.pt_temp_cnt, f.oat_cnt})[slot];
      const double error = out_value - value;
      worst_difference =
          std::max(worst_difference, std::abs(error - g["error_no_history"].get<double>()));
      worst_ratio = std::max(worst_ratio, std::abs(error) / g["tolerance"].get<double>());
    }
    const double allowed = altitude ? bound.altitude_ft : bound.airspeed_kt;
    std::printf("%s: worst |command - independent| %.3g (exporter bound %.3g), worst ratio %.3f\n",
                altitude ? "altitude ft" : "airspeed kt",
                worst_difference,
                allowed,
                worst_ratio);
    EXPECT_LE(worst_difference, allowed);
    // The ratio the command reports, from errors each within `allowed` of the independent ones.
    const double reported =
        e[altitude ? "altitude_ft" : "airspeed_kt"]["worst_ratio_no_history"].get<double>();
    const double smallest_tolerance = altitude ? 15.0 : 1.0;  // Table 2's smallest
    EXPECT_NEAR(reported, worst_ratio, allowed / smallest_tolerance);
  }
}

TEST(AdsEvaluateCommand, BadInputIsRefusedNamingTheFileAndTheJsonPath) {
  const Campaign& c = Made();
  const std::string constants = c.ConstantsPath().string();
  // A truth file of another unit.
  const fs::path other = c.dir / "other.json";
  nlohmann::json truth = ReadJson(c.TruthPath());
  truth["params"]["serial"] = "ADS-0043";
  WriteJson(other, truth);
  CommandResult r = RunAdahrs("evaluate --constants '" + constants + "' --truth '" +
                              other.string() + "' --out " + (c.dir / "x.json").string());
  EXPECT_NE(r.status, 0);
  EXPECT_THAT(r.output, HasSubstr(other.string() + ": $.params.serial: 'ADS-0043'"));
  // An IMU's truth file for ADS constants.
  truth = ReadJson(c.TruthPath());
  truth["kind"] = "imu";
  WriteJson(other, truth);
  r = RunAdahrs("evaluate --constants '" + constants + "' --truth '" + other.string() + "' --out " +
                (c.dir / "x.json").string());
  EXPECT_NE(r.status, 0);
  EXPECT_THAT(r.output, HasSubstr(other.string() + ": $.kind: 'imu', not an ads truth file"));
  // A truth parameter out of its range.
  truth = ReadJson(c.TruthPath());
  truth["params"]["frame_period_s"] = -1.0;
  WriteJson(other, truth);
  r = RunAdahrs("evaluate --constants '" + constants + "' --truth '" + other.string() + "' --out " +
                (c.dir / "x.json").string());
  EXPECT_NE(r.status, 0);
  EXPECT_THAT(r.output, HasSubstr(other.string()));
  EXPECT_THAT(r.output, HasSubstr("$.params.frame_period_s"));
  // Constants without their altitude surface.
  nlohmann::json broken = ReadJson(c.ConstantsPath());
  broken["constants"].erase("altitude_ft");
  const fs::path broken_path = c.dir / "broken.json";
  WriteJson(broken_path, broken);
  r = RunAdahrs("evaluate --constants '" + broken_path.string() + "' --truth '" +
                c.TruthPath().string() + "' --out " + (c.dir / "x.json").string());
  EXPECT_NE(r.status, 0);
  EXPECT_THAT(r.output, HasSubstr(broken_path.string()));
  EXPECT_THAT(r.output, HasSubstr("altitude_ft"));
  EXPECT_FALSE(fs::exists(c.dir / "x.json"));
}

}  // namespace
}  // namespace adahrs::proving
