// Replays the committed golden vectors bit for bit (outputs, flags, cycle counts), and checks that
// regenerating them from the same fixtures gives the same document (a change indicator: a diff
// means the fixed-point arithmetic changed; review it, then regenerate with ADAHRS_WRITE_GOLDEN=1
// (docs/firmware-compensator.md gives the command), which writes the files and fails: a run with
// the variable set never passes).
// The truth tests for the same arithmetic are the envelope sweeps (compensator_sweep_test.cc).
#include "firmware_model/golden_vectors.h"
#include "adahrs_build_paths.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "firmware_model/constants_exporter.h"
#include "tests/firmware_model/realistic_constants.h"

namespace adahrs::firmware_model {
namespace {

// Format 2 (blocks 0x01..0x0F) and format 3 (0x01..0x1B, the scale-temperature stages on).
const char* const kGoldenPath =
    ADAHRS_SOURCE_DIR "/tests/firmware_model/data/compensator_golden.json";
const char* const kGoldenFormat3Path =
    ADAHRS_SOURCE_DIR "/tests/firmware_model/data/compensator_golden_format3.json";

nlohmann::json Generate(bool format3 = false) {
  const ImuCalibrationConstants imu_cal =
      format3 ? testing::WithScaleTemperature(testing::RealisticImu(2024), 2025)
              : testing::RealisticImu(2024);
  common::Rng rng(99);
  std::vector<ImuRawFrame> imu_frames;
  const double temps_c[] = {-40.0, 0.0, 25.0, 85.0};
  for (int i = 0; i < 8; ++i) {
    const double s = i % 2 ? 1.0 : -1.0;
    imu_frames.push_back(testing::SynthesiseImu(imu_cal,
                                                {s * 10.0, -s * 3.0, 1.0},
                                                {s * 150.0, 20.0 * i, -s * 75.0},
                                                temps_c[i % 4],
                                                &rng));
  }
  ImuRawFrame bad = imu_frames[0];  // t1 >= t2 and a gyro count beyond 2^23: flagged, not wrapped
  bad.t1_cnt[3] = bad.t2_cnt[3];
  bad.gyro_cnt[1] = 9000000;
  imu_frames.push_back(bad);
  std::vector<AdsRawFrame> ads_frames;
  const double alts_ft[] = {-1000.0, 0.0, 10000.0, 30000.0, 50000.0};
  const double cas_kt[] = {30.0, 60.0, 100.0, 300.0, 450.0};
  for (int i = 0; i < 5; ++i)
    ads_frames.push_back(testing::SynthesiseAds(alts_ft[i], cas_kt[i], temps_c[i % 4]));
  // The ADS set is the pressure-law form (surface, then ISA / CAS tables and the square root):
  // the longer arithmetic path; the direct form's surface is the same code.
  return MakeCompensatorGolden(ExportImuConstants(imu_cal).constants,
                               ExportAdsConstants(testing::RealisticPressureAds()).constants,
                               imu_frames,
                               ads_frames);
}

class GoldenVectorsFormat : public ::testing::TestWithParam<bool> {
 protected:
  const char* Path() const { return GetParam() ? kGoldenFormat3Path : kGoldenPath; }
};

INSTANTIATE_TEST_SUITE_P(GoldenVectors,
                         GoldenVectorsFormat,
                         ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "Format3" : "Format2"; });

TEST_P(GoldenVectorsFormat, ReplayBitExact) {
  if (std::getenv("ADAHRS_WRITE_GOLDEN") != nullptr) {
    // A writing run compares the code with itself: it writes and fails, so that no run with the
    // variable set (a suite run that inherited it, say) can pass.
    std::ofstream(Path()) << Generate(GetParam()).dump(1) << "\n";
    FAIL() << "ADAHRS_WRITE_GOLDEN is set: wrote " << Path()
           << " and checked nothing; review its diff, then run again without the variable";
  }
  std::ifstream file(Path());
  ASSERT_TRUE(file.good()) << Path();
  const nlohmann::json golden = nlohmann::json::parse(file);
  ASSERT_EQ(golden.at("imu").at("frames").size(), 9u);
  ASSERT_EQ(golden.at("imu").at("blocks").size(), GetParam() ? 27u : 15u);
  EXPECT_EQ(ReplayCompensatorGolden(golden), "");
  // The bad frame carries its flags: bad duty and input saturation.
  const auto& bad_modes = golden["imu"]["frames"][8]["modes"];
  EXPECT_EQ(bad_modes[0]["flags"].get<int>() & (kFlagBadDuty | kFlagInputSaturated),
            kFlagBadDuty | kFlagInputSaturated);
}

TEST_P(GoldenVectorsFormat, RegenerationMatchesCommittedFile) {
  std::ifstream file(Path());
  ASSERT_TRUE(file.good()) << Path();
  EXPECT_EQ(nlohmann::json::parse(file), Generate(GetParam()));
}

TEST(GoldenVectors, ReplayDetectsAOneLsbChange) {
  std::ifstream file(kGoldenPath);
  ASSERT_TRUE(file.good());
  nlohmann::json golden = nlohmann::json::parse(file);
  golden["imu"]["frames"][2]["modes"][3]["value"][4] =
      golden["imu"]["frames"][2]["modes"][3]["value"][4].get<int32_t>() + 1;
  EXPECT_NE(ReplayCompensatorGolden(golden).find("IMU frame 2 mode 3 value"), std::string::npos);
}

}  // namespace
}  // namespace adahrs::firmware_model
