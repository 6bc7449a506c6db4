// The campaign file (calib/campaign/campaign_file.h) and the campaign journal
// (calib/campaign/campaign_journal.h): the shipped example names files that exist; ToJson reads
// back to the same campaign; every malformed part is refused naming the file and the JSON path;
// the journal survives a reopen and forgets a download whose constants changed.
#include <gtest/gtest.h>

#include <fstream>

#include "adahrs_build_paths.h"
#include "calib/campaign/campaign_file.h"
#include "calib/campaign/campaign_journal.h"
#include "common/param_reader.h"
#include "tests/support/error_text.h"

namespace adahrs::calib {
namespace {

using test_support::ErrorText;

const std::filesystem::path kSource = std::filesystem::path(ADAHRS_SEQUENCE_DIR) / ".." / "..";

nlohmann::json Example() {
  return common::ParamReader::LoadFile((kSource / "docs/examples/campaign.json").string());
}

std::string Refusal(const nlohmann::json& document) {
  return ErrorText<common::ParamError>(
      [&] { CampaignFile::FromJson(document, "c.json", "/base"); });
}

TEST(CampaignFile, ShippedExampleNamesExistingFiles) {
  const CampaignFile c = CampaignFile::Load(kSource / "docs/examples/campaign.json");
  ASSERT_EQ(c.sequences.imu_calibration.size(), 1u);
  for (const std::string& f : {c.sequences.imu_calibration[0],
                               c.sequences.ads_calibration,
                               c.sequences.imu_acceptance,
                               c.sequences.ads_acceptance,
                               c.specification_file}) {
    EXPECT_TRUE(std::filesystem::path(f).is_absolute()) << f;
    EXPECT_TRUE(std::filesystem::exists(f)) << f;
  }
  EXPECT_EQ(c.imu_strategy, "joint");
  EXPECT_EQ(c.ads_strategy, "hysteresis_compensated");
  EXPECT_EQ(c.max_acceptance_attempts, 1);
}

TEST(CampaignFile, ToJsonReadsBackTheSameCampaign) {
  nlohmann::json j = Example();
  j["expected_serials"] = {{"imu1", "IMU-000007"}, {"ads1", "ADS-000001"}};
  j["fit"]["imu"] = "reference";
  const CampaignFile c = CampaignFile::FromJson(j, "c.json", "/base/dir");
  EXPECT_EQ(c.sequences.ads_acceptance, "/calib/sequences/ads_acceptance.json");
  const nlohmann::json again = c.ToJson();
  EXPECT_EQ(CampaignFile::FromJson(again, "again", "/elsewhere").ToJson(), again);
  EXPECT_EQ(again["expected_serials"]["imu1"], "IMU-000007");
  EXPECT_EQ(again["fit"]["imu"], "reference");
}

TEST(CampaignFile, MalformedPartsAreRefusedWithTheirJsonPath) {
  nlohmann::json j = Example();
  j["fit"]["imu"] = "joint_format9";
  EXPECT_NE(Refusal(j).find("c.json"), std::string::npos) << Refusal(j);
  EXPECT_NE(Refusal(j).find("$.fit.imu"), std::string::npos) << Refusal(j);

  j = Example();
  j["sequences"]["imu_calibration"].push_back(3);
  EXPECT_NE(Refusal(j).find("$.sequences.imu_calibration[1]"), std::string::npos) << Refusal(j);

  j = Example();
  j["sequences"].erase("ads_acceptance");
  EXPECT_NE(Refusal(j).find("$.sequences.ads_acceptance"), std::string::npos) << Refusal(j);

  j = Example();
  j["sequences"]["imu_acceptance_typo"] = "x.json";
  EXPECT_NE(Refusal(j).find("imu_acceptance_typo"), std::string::npos) << Refusal(j);

  j = Example();
  j["expected_serials"]["imu2"] = 42;
  EXPECT_NE(Refusal(j).find("$.expected_serials.imu2"), std::string::npos) << Refusal(j);

  j = Example();
  j["retest"]["max_attempts"] = 0;
  EXPECT_NE(Refusal(j).find("$.retest.max_attempts"), std::string::npos) << Refusal(j);

  j = Example();
  j["format_version"] = 2;
  EXPECT_NE(Refusal(j).find("$.format_version"), std::string::npos) << Refusal(j);
}

class CampaignJournalTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("adahrs-journal-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(CampaignJournalTest, StagesAndDownloadsSurviveAReopen) {
  UnitDownload d{"imu2", "IMU-000002", dir_ / "IMU-000002.json", "ab12", 1, 3, 0xBEEF, 9};
  {
    CampaignJournal journal(dir_);
    EXPECT_FALSE(journal.Done("fits"));
    journal.MarkDone("calibration_runs");
    journal.MarkDone("fits");
    journal.RecordDownload(d);
  }
  const CampaignJournal reopened(dir_);
  EXPECT_TRUE(reopened.Done("calibration_runs"));
  EXPECT_TRUE(reopened.Done("fits"));
  EXPECT_FALSE(reopened.Done("downloads"));
  const std::optional<UnitDownload> before = reopened.VerifiedDownload("IMU-000002", "ab12");
  ASSERT_TRUE(before.has_value());
  EXPECT_EQ(before->unit_constants_crc, 0xBEEF);
  EXPECT_EQ(before->blocks, 9u);
  EXPECT_FALSE(reopened.VerifiedDownload("IMU-000002", "cd34").has_value());  // changed
  EXPECT_FALSE(reopened.VerifiedDownload("IMU-000003", "ab12").has_value());
}

TEST_F(CampaignJournalTest, NewerConstantsSupersedeAnOlderVerifiedDownload) {
  CampaignJournal journal(dir_);
  journal.RecordDownload({"imu1", "IMU-000001", "a.json", "old", 1, 1, 1, 9});
  journal.RecordDownload({"imu1", "IMU-000001", "a.json", "new", 2, 2, 2, 9});
  EXPECT_FALSE(journal.VerifiedDownload("IMU-000001", "old").has_value());
  EXPECT_TRUE(journal.VerifiedDownload("IMU-000001", "new").has_value());
}

TEST_F(CampaignJournalTest, AMalformedJournalIsRefusedWithItsPath) {
  std::ofstream(dir_ / kCampaignJournalFile)
      << R"({"format": "adahrs-campaign-journal", "format_version": 1,
             "stages": [{"stage": "fits"}], "downloads": []})";
  const std::string error = ErrorText<common::ParamError>([&] { CampaignJournal journal(dir_); });
  EXPECT_NE(error.find(kCampaignJournalFile), std::string::npos) << error;
  EXPECT_NE(error.find("$.stages[0].finished_utc"), std::string::npos) << error;
}

}  // namespace
}  // namespace adahrs::calib
