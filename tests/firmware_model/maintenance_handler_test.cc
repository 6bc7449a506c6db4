// Maintenance port (docs/unit-protocol.md §6-7), driven the way the PC drives it: requests built
// by UnitProtocolClient (Boost.CRC framing), bytes through MaintenanceHandler::Receive, responses
// decoded and parsed on the PC side. Covers every command, every NAK code with the state shown
// unchanged, and commit / power-cycle semantics.
#include "firmware_model/unit_firmware.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "firmware_model/constants_exporter.h"
#include "tests/firmware_model/realistic_constants.h"

#include "hil/codecs/unit_protocol_client.h"

namespace adahrs::firmware_model {
namespace {

using ::testing::HasSubstr;

constexpr UnitIdentity kImuIdentity = {UnitKind::kImu, 150042, 2, 7, 1};
constexpr UnitIdentity kAdsIdentity = {UnitKind::kAds, 230017, 1, 4, 0};

// Index of one mantissa low word per block layout (imu_constants.h, ads_constants.h,
// fixed_coeff.h): thermal: sensor, norm(3), work exponent, c0 hi at 5, lo at 6; accel: offset lo of
// az1 at 1; gyro: norm(3), work exponent, c0 lo at 5; matrices: [0][0] lo at 1; ADS: 2 norms, 5
// exponents, coefficient c_00 (the reference's a) lo at 12. Room for any constants block of either
// unit kind.
constexpr uint8_t kLargestBlockWords = std::max(kAdsMaxBlockWords, kImuMaxBlockWords);

int MantissaLowIndex(uint8_t block_id) {
  if (block_id <= kImuBlockThermalLast) return 6;
  if (block_id == kImuBlockAccelOffsetScale) return 1;
  if (block_id <= kImuBlockGyroCubicLast) return 5;
  if (block_id <= kImuBlockCg) return 1;
  return 12;
}

// A valid block that differs from the power-on defaults: the defaults with one mantissa's low
// word set to `marker` (a change of at most 2^16 LSB of a Q31 mantissa, far inside every
// format's overflow bound).
std::vector<int16_t> ValidBlock(UnitKind kind, uint8_t block_id, int16_t marker) {
  std::vector<int16_t> words(kLargestBlockWords);
  uint8_t count = 0;
  ConstantsStatus status;
  if (kind == UnitKind::kImu) {
    ImuConstants constants;
    ImuConstantsInit(&constants);
    status = ImuConstantsReadBlock(
        &constants, block_id, words.data(), static_cast<uint8_t>(words.size()), &count);
  } else {
    AdsConstants constants;
    AdsConstantsInit(&constants);
    status = AdsConstantsReadBlock(
        &constants, block_id, words.data(), static_cast<uint8_t>(words.size()), &count);
  }
  EXPECT_EQ(status, ConstantsStatus::kOk);
  words.resize(count);
  words[MantissaLowIndex(block_id)] = marker;
  return words;
}

std::vector<uint8_t> BlockIds(UnitKind kind) {
  std::vector<uint8_t> ids;
  if (kind == UnitKind::kImu) {
    for (uint8_t id = kImuBlockThermalFirst; id <= kImuBlockCg; ++id) ids.push_back(id);
  } else {
    ids = {kAdsBlockAltitude, kAdsBlockAirspeed};
  }
  return ids;
}

// Everything a refused request must leave alone.
struct Snapshot {
  uint8_t mode;
  uint8_t tag;
  bool constants_valid;
  uint16_t constants_version;
  uint16_t constants_crc;
  std::vector<std::vector<int16_t>> blocks;
  FlashImageInfo flash;
  bool operator==(const Snapshot& o) const {
    return mode == o.mode && tag == o.tag && constants_valid == o.constants_valid &&
           constants_version == o.constants_version && constants_crc == o.constants_crc &&
           blocks == o.blocks && flash.status == o.flash.status &&
           flash.constants_version == o.flash.constants_version &&
           flash.image_crc == o.flash.image_crc;
  }
};

class Unit {
 public:
  explicit Unit(const UnitIdentity& identity) : handler_(identity, &flash_) {}

  // Sends request bytes and returns every response the unit produced.
  std::vector<hil::MaintenanceResponse> SendRaw(const std::vector<uint8_t>& bytes) {
    std::vector<hil::MaintenanceResponse> responses;
    std::vector<uint8_t> out(kMaxFrameBytes);
    size_t offset = 0;
    while (true) {
      const PortResult result = handler_.Receive(bytes.data() + offset,
                                                 static_cast<uint16_t>(bytes.size() - offset),
                                                 out.data(),
                                                 static_cast<uint16_t>(out.size()));
      offset += result.consumed_bytes;
      if (result.response_bytes == 0) break;
      for (const Frame& frame : reader_.Push({out.data(), result.response_bytes})) {
        responses.push_back(hil::ParseMaintenanceResponse(frame));
      }
    }
    return responses;
  }

  // Sends one request and returns its single response, checking the sequence echo.
  hil::MaintenanceResponse Send(const std::vector<uint8_t>& request) {
    const std::vector<hil::MaintenanceResponse> responses = SendRaw(request);
    EXPECT_EQ(responses.size(), 1u) << hil::HexTrace(request);
    if (responses.empty())
      return hil::MaintenanceResponse{0, MaintenanceCommand::kNone, ResultCode::kFlashError, {}};
    EXPECT_EQ(responses[0].sequence, request[4]) << "response must echo the request sequence";
    return responses[0];
  }

  void WriteAllBlocks(int16_t marker) {
    for (const uint8_t id : BlockIds(handler_.kind())) {
      ASSERT_EQ(Send(client_.WriteBlock(id, ValidBlock(handler_.kind(), id, marker))).result,
                ResultCode::kAck)
          << "block " << +id;
    }
  }

  std::vector<int16_t> ReadBack(uint8_t block_id) {
    const hil::BlockReadback readback = hil::ParseReadBlock(Send(client_.ReadBlock(block_id)));
    EXPECT_EQ(readback.block_id, block_id);
    return readback.words;
  }

  Snapshot Take() const {
    Snapshot s{0,
               handler_.tag(),
               handler_.constants_valid(),
               handler_.constants_version(),
               handler_.constants_crc(),
               {},
               flash_.Inspect(handler_.kind())};
    s.mode = handler_.kind() == UnitKind::kImu ? static_cast<uint8_t>(handler_.imu_mode())
                                               : static_cast<uint8_t>(handler_.ads_mode());
    for (const uint8_t id : BlockIds(handler_.kind())) {
      std::vector<int16_t> words(kLargestBlockWords);
      uint8_t count = 0;
      if (handler_.kind() == UnitKind::kImu) {
        ImuConstantsReadBlock(&handler_.imu_constants(),
                              id,
                              words.data(),
                              static_cast<uint8_t>(words.size()),
                              &count);
      } else {
        AdsConstantsReadBlock(&handler_.ads_constants(),
                              id,
                              words.data(),
                              static_cast<uint8_t>(words.size()),
                              &count);
      }
      words.resize(count);
      s.blocks.push_back(words);
    }
    return s;
  }

  FlashStore flash_;
  MaintenanceHandler handler_;
  hil::UnitProtocolClient client_;
  hil::StreamReader reader_;
};

TEST(MaintenanceHandlerTest, IdentifyReportsTheFactoryIdentityAndNoConstants) {
  Unit unit(kImuIdentity);
  const hil::IdentifyInfo info = hil::ParseIdentify(unit.Send(unit.client_.Identify()));
  EXPECT_EQ(info.unit_kind, UnitKind::kImu);
  EXPECT_EQ(info.serial_number, 150042u);
  EXPECT_EQ(info.firmware_major, 2);
  EXPECT_EQ(info.firmware_minor, 7);
  EXPECT_EQ(info.firmware_patch, 1);
  EXPECT_FALSE(info.constants_valid);
  EXPECT_EQ(info.constants_version, 0);
  EXPECT_EQ(info.constants_crc, 0);
  EXPECT_EQ(info.mode, 0);
  EXPECT_EQ(info.tag, 0);
}

TEST(MaintenanceHandlerTest, SetTagIsCarriedByEveryLaterResponse) {
  Unit unit(kImuIdentity);
  const hil::MaintenanceResponse ack = unit.Send(unit.client_.SetTag(0xB7));
  EXPECT_EQ(ack.result, ResultCode::kAck);
  EXPECT_EQ(ack.data, std::vector<uint8_t>{0xB7});
  EXPECT_EQ(unit.handler_.tag(), 0xB7);
  EXPECT_EQ(hil::ParseIdentify(unit.Send(unit.client_.Identify())).tag, 0xB7);
}

TEST(MaintenanceHandlerTest, WriteAndReadBackEveryImuBlock) {
  Unit unit(kImuIdentity);
  for (const uint8_t id : BlockIds(UnitKind::kImu)) {
    const std::vector<int16_t> block =
        ValidBlock(UnitKind::kImu, id, static_cast<int16_t>(100 + id));
    const hil::MaintenanceResponse ack = unit.Send(unit.client_.WriteBlock(id, block));
    ASSERT_EQ(ack.result, ResultCode::kAck)
        << hil::ResultCodeName(ack.result) << " for block " << +id;
    EXPECT_EQ(unit.ReadBack(id), block) << "block " << +id;
  }
}

TEST(MaintenanceHandlerTest, CommitPersistsAcrossPowerCycleAndUncommittedWritesAreLost) {
  Unit unit(kImuIdentity);
  unit.WriteAllBlocks(11);
  const hil::CommitInfo commit = hil::ParseCommit(unit.Send(unit.client_.Commit()));
  EXPECT_EQ(commit.constants_version, 1);
  EXPECT_EQ(commit.constants_crc, unit.flash_.Inspect(UnitKind::kImu).image_crc);
  ASSERT_EQ(unit.Send(unit.client_.SetImuMode(ImuCompensationMode::kFullyCalibrated)).result,
            ResultCode::kAck);
  ASSERT_EQ(unit.Send(unit.client_.SetTag(9)).result, ResultCode::kAck);
  // An uncommitted change to CA.
  const std::vector<int16_t> changed = ValidBlock(UnitKind::kImu, kImuBlockCa, 777);
  ASSERT_EQ(unit.Send(unit.client_.WriteBlock(kImuBlockCa, changed)).result, ResultCode::kAck);
  EXPECT_EQ(unit.ReadBack(kImuBlockCa), changed);

  const hil::MaintenanceResponse reset = unit.Send(unit.client_.Reset());
  ASSERT_EQ(reset.result, ResultCode::kAck);
  EXPECT_EQ(reset.data, std::vector<uint8_t>{1});  // valid constants after the power cycle
  EXPECT_EQ(unit.ReadBack(kImuBlockCa), ValidBlock(UnitKind::kImu, kImuBlockCa, 11));
  const hil::IdentifyInfo info = hil::ParseIdentify(unit.Send(unit.client_.Identify()));
  EXPECT_EQ(info.mode, 0);  // power-on mode is raw
  EXPECT_EQ(info.tag, 0);
  EXPECT_TRUE(info.constants_valid);
  EXPECT_EQ(info.constants_version, 1);
  EXPECT_EQ(info.constants_crc, commit.constants_crc);
  EXPECT_EQ(unit.Send(unit.client_.SetImuMode(ImuCompensationMode::kThermal)).result,
            ResultCode::kAck);

  // Constants loaded from flash count as complete: a commit right away is accepted.
  EXPECT_EQ(hil::ParseCommit(unit.Send(unit.client_.Commit())).constants_version, 2);

  // A second unit powered on with the same flash gets the committed constants.
  MaintenanceHandler second(kImuIdentity, &unit.flash_);
  EXPECT_TRUE(second.constants_valid());
  EXPECT_EQ(second.constants_version(), 2);
}

TEST(MaintenanceHandlerTest, CorruptFlashMeansNoConstantsAfterPowerCycle) {
  Unit unit(kImuIdentity);
  unit.WriteAllBlocks(5);
  ASSERT_EQ(unit.Send(unit.client_.Commit()).result, ResultCode::kAck);
  unit.flash_.InjectBitFlip(40, 3);  // a payload word
  ASSERT_EQ(unit.Send(unit.client_.Reset()).data, std::vector<uint8_t>{0});
  EXPECT_FALSE(unit.handler_.constants_valid());
  EXPECT_EQ(unit.Send(unit.client_.SetImuMode(ImuCompensationMode::kSensorCalibrated)).result,
            ResultCode::kNoValidConstants);
  // RAM holds the uncalibrated defaults, not a partly loaded image.
  for (const uint8_t id : BlockIds(UnitKind::kImu)) {
    ImuConstants init;
    ImuConstantsInit(&init);
    std::vector<int16_t> words(kLargestBlockWords);
    uint8_t count = 0;
    ImuConstantsReadBlock(&init, id, words.data(), static_cast<uint8_t>(words.size()), &count);
    words.resize(count);
    EXPECT_EQ(unit.ReadBack(id), words) << "block " << +id;
  }
}

TEST(MaintenanceHandlerTest, EveryMalformedRequestIsRefusedWithItsCodeAndChangesNothing) {
  Unit unit(kImuIdentity);
  // Start from a committed unit in a calibrated mode with a TAG, so any change would show.
  unit.WriteAllBlocks(3);
  ASSERT_EQ(unit.Send(unit.client_.Commit()).result, ResultCode::kAck);
  ASSERT_EQ(unit.Send(unit.client_.SetImuMode(ImuCompensationMode::kSensorCalibrated)).result,
            ResultCode::kAck);
  ASSERT_EQ(unit.Send(unit.client_.SetTag(0x33)).result, ResultCode::kAck);
  hil::UnitProtocolClient& c = unit.client_;
  const auto cmd = [](MaintenanceCommand command) { return static_cast<uint8_t>(command); };
  std::vector<int16_t> ca = ValidBlock(UnitKind::kImu, kImuBlockCa, 1);
  std::vector<int16_t> ca_out_of_range = ca;
  ca_out_of_range[2] = 100;  // exponent of CA[0][0] outside -40..40
  std::vector<int16_t> ca_overflow = ca;
  ca_overflow[0] = 0x7FFF;  // CA[0][0] ~ 2^(5-31) * 2^31 = 32 m/s^2 per g: 32 * 10 g >= 256 m/s^2
  ca_overflow[1] = -1;
  ca_overflow[2] = 5;
  struct Case {
    const char* what;
    std::vector<uint8_t> request;
    MaintenanceCommand echoed;
    ResultCode expected;
  };
  std::vector<uint8_t> bad_crc = c.SetTag(0x44);
  bad_crc.back() ^= 0x01;
  std::vector<uint8_t> write_count_mismatch = c.WriteBlock(kImuBlockCa, ca);
  const std::vector<Case> cases = {
      {"bad CRC", bad_crc, MaintenanceCommand::kNone, ResultCode::kBadCrc},
      {"SET_MODE with two arguments",
       c.Request(cmd(MaintenanceCommand::kSetMode), std::vector<uint8_t>{0, 0}),
       MaintenanceCommand::kSetMode,
       ResultCode::kBadLength},
      {"SET_TAG without argument",
       c.Request(cmd(MaintenanceCommand::kSetTag), {}),
       MaintenanceCommand::kSetTag,
       ResultCode::kBadLength},
      {"WRITE_BLOCK count says 27, 26 words sent",
       c.Request(
           cmd(MaintenanceCommand::kWriteBlock),
           std::vector<uint8_t>(write_count_mismatch.begin() + 7, write_count_mismatch.end() - 4)),
       MaintenanceCommand::kWriteBlock,
       ResultCode::kBadLength},
      {"READ_BLOCK without block id",
       c.Request(cmd(MaintenanceCommand::kReadBlock), {}),
       MaintenanceCommand::kReadBlock,
       ResultCode::kBadLength},
      {"COMMIT with an argument",
       c.Request(cmd(MaintenanceCommand::kCommit), std::vector<uint8_t>{1}),
       MaintenanceCommand::kCommit,
       ResultCode::kBadLength},
      {"IDENTIFY with an argument",
       c.Request(cmd(MaintenanceCommand::kIdentify), std::vector<uint8_t>{1}),
       MaintenanceCommand::kIdentify,
       ResultCode::kBadLength},
      {"RESET with an argument",
       c.Request(cmd(MaintenanceCommand::kReset), std::vector<uint8_t>{1}),
       MaintenanceCommand::kReset,
       ResultCode::kBadLength},
      {"READ_COUNTERS with an argument",
       c.Request(cmd(MaintenanceCommand::kReadCounters), std::vector<uint8_t>{1}),
       MaintenanceCommand::kReadCounters,
       ResultCode::kBadLength},
      {"unknown command 0x55",
       c.Request(0x55, {}),
       static_cast<MaintenanceCommand>(0x55),
       ResultCode::kUnknownCommand},
      {"command NONE", c.Request(0x00, {}), MaintenanceCommand::kNone, ResultCode::kUnknownCommand},
      {"IMU mode 4",
       c.Request(cmd(MaintenanceCommand::kSetMode), std::vector<uint8_t>{4}),
       MaintenanceCommand::kSetMode,
       ResultCode::kBadArgument},
      {"write unknown block 0x30",
       c.WriteBlock(0x30, ca),
       MaintenanceCommand::kWriteBlock,
       ResultCode::kUnknownBlock},
      {"write ADS block on an IMU",
       c.WriteBlock(kAdsBlockAltitude, ca),
       MaintenanceCommand::kWriteBlock,
       ResultCode::kUnknownBlock},
      {"read unknown block 0x00",
       c.ReadBlock(0x00),
       MaintenanceCommand::kReadBlock,
       ResultCode::kUnknownBlock},
      {"CA with 26 words",
       c.WriteBlock(kImuBlockCa, std::vector<int16_t>(ca.begin(), ca.end() - 1)),
       MaintenanceCommand::kWriteBlock,
       ResultCode::kBlockWrongLength},
      {"CA exponent 100",
       c.WriteBlock(kImuBlockCa, ca_out_of_range),
       MaintenanceCommand::kWriteBlock,
       ResultCode::kConstantOutOfRange},
      {"CA gain 32 overflows 256 m/s^2 at 10 g",
       c.WriteBlock(kImuBlockCa, ca_overflow),
       MaintenanceCommand::kWriteBlock,
       ResultCode::kConstantOverflow},
  };
  const Snapshot before = unit.Take();
  for (const Case& test_case : cases) {
    const uint32_t naks_before =
        unit.handler_.counters().naks_by_code[static_cast<uint8_t>(test_case.expected)];
    const hil::MaintenanceResponse response = unit.Send(test_case.request);
    EXPECT_EQ(response.result, test_case.expected)
        << test_case.what << ": got " << hil::ResultCodeName(response.result) << " for "
        << hil::HexTrace(test_case.request);
    EXPECT_EQ(response.command, test_case.echoed) << test_case.what;
    EXPECT_TRUE(response.data.empty()) << test_case.what;
    EXPECT_EQ(unit.handler_.counters().naks_by_code[static_cast<uint8_t>(test_case.expected)],
              naks_before + 1)
        << test_case.what;
    EXPECT_TRUE(unit.Take() == before) << test_case.what << " changed the unit's state";
  }
  // Header errors are counted by the decoder but not answered.
  const uint32_t unknown_before = unit.handler_.decoder_counters().unknown_type;
  EXPECT_TRUE(unit.SendRaw(hil::BuildFrame(0x44, 0, 0, std::vector<uint8_t>{1})).empty());
  EXPECT_EQ(unit.handler_.decoder_counters().unknown_type, unknown_before + 1);
  EXPECT_TRUE(unit.Take() == before);
  // The counters the unit reports agree with the handler's.
  const hil::UnitCounters counters = hil::ParseCounters(unit.Send(c.ReadCounters()));
  EXPECT_EQ(counters.requests_naked, cases.size());
  EXPECT_EQ(counters.decoder.bad_crc, 1u);
  EXPECT_EQ(counters.decoder.unknown_type, 1u);
  // The reported counts are taken before READ_COUNTERS' own ACK is counted.
  EXPECT_EQ(counters.requests_acked + 1, unit.handler_.counters().requests_acked);
}

TEST(MaintenanceHandlerTest, CalibratedModesAndCommitNeedACompleteValidSet) {
  Unit unit(kImuIdentity);
  for (const auto mode : {ImuCompensationMode::kThermal,
                          ImuCompensationMode::kSensorCalibrated,
                          ImuCompensationMode::kFullyCalibrated}) {
    EXPECT_EQ(unit.Send(unit.client_.SetImuMode(mode)).result, ResultCode::kNoValidConstants);
  }
  EXPECT_EQ(unit.Send(unit.client_.SetImuMode(ImuCompensationMode::kRaw)).result, ResultCode::kAck);
  // All blocks but CG written: commit refused, flash untouched.
  for (const uint8_t id : BlockIds(UnitKind::kImu)) {
    if (id == kImuBlockCg) continue;
    ASSERT_EQ(unit.Send(unit.client_.WriteBlock(id, ValidBlock(UnitKind::kImu, id, 2))).result,
              ResultCode::kAck);
  }
  EXPECT_EQ(unit.Send(unit.client_.Commit()).result, ResultCode::kIncompleteConstants);
  EXPECT_EQ(unit.flash_.Inspect(UnitKind::kImu).status, FlashStatus::kErased);
  // Written but uncommitted constants do not unlock calibrated modes either.
  ASSERT_EQ(
      unit.Send(unit.client_.WriteBlock(kImuBlockCg, ValidBlock(UnitKind::kImu, kImuBlockCg, 2)))
          .result,
      ResultCode::kAck);
  EXPECT_EQ(unit.Send(unit.client_.SetImuMode(ImuCompensationMode::kThermal)).result,
            ResultCode::kNoValidConstants);
  EXPECT_EQ(unit.Send(unit.client_.Commit()).result, ResultCode::kAck);
  EXPECT_EQ(unit.Send(unit.client_.SetImuMode(ImuCompensationMode::kThermal)).result,
            ResultCode::kAck);
  EXPECT_EQ(unit.handler_.imu_mode(), ImuCompensationMode::kThermal);
}

// The format-3 blocks 0x10..0x1B are all or none: a commit with some of them is refused; with
// all of them the image (27 blocks, 502 payload words) fits the page and survives a power cycle;
// and an image of the format-2 blocks alone, as format-2 firmware committed it, still loads with
// the format-3 stages off.
TEST(MaintenanceHandlerTest, Format3BlocksAreAllOrNoneAndAFormat2ImageStillLoads) {
  const ImuConstants exported =
      ExportImuConstants(testing::WithScaleTemperature(testing::RealisticImu(21), 22)).constants;
  auto words_of = [&](const ImuConstants& c, uint8_t id) {
    std::vector<int16_t> words(kLargestBlockWords);
    uint8_t count = 0;
    EXPECT_EQ(
        ImuConstantsReadBlock(&c, id, words.data(), static_cast<uint8_t>(words.size()), &count),
        ConstantsStatus::kOk);
    words.resize(count);
    return words;
  };
  Unit unit(kImuIdentity);
  for (uint8_t id = kImuBlockThermalFirst; id <= kImuBlockScaleSwitch; ++id) {
    ASSERT_EQ(unit.Send(unit.client_.WriteBlock(id, words_of(exported, id))).result,
              ResultCode::kAck)
        << "block " << +id;
  }
  EXPECT_EQ(unit.Send(unit.client_.Commit()).result, ResultCode::kIncompleteConstants);
  EXPECT_EQ(unit.flash_.Inspect(UnitKind::kImu).status, FlashStatus::kErased);
  for (uint8_t id = kImuBlockScaleFactorFirst; id <= kImuBlockLast; ++id) {
    ASSERT_EQ(unit.Send(unit.client_.WriteBlock(id, words_of(exported, id))).result,
              ResultCode::kAck)
        << "block " << +id;
  }
  ASSERT_EQ(unit.Send(unit.client_.Commit()).result, ResultCode::kAck);
  EXPECT_EQ(unit.flash_.Inspect(UnitKind::kImu).payload_words, 502);
  ASSERT_EQ(unit.Send(unit.client_.Reset()).data, std::vector<uint8_t>{1});
  for (uint8_t id = kImuBlockThermalFirst; id <= kImuBlockLast; ++id) {
    EXPECT_EQ(unit.ReadBack(id), words_of(exported, id)) << "block " << +id;
  }
  EXPECT_EQ(unit.handler_.imu_constants().scale_temperature.enabled, 1);

  // A format-2 image: blocks 0x01..0x0F only.
  std::vector<int16_t> image;
  for (uint8_t id = kImuBlockThermalFirst; id <= kImuBlockCg; ++id) {
    const std::vector<int16_t> words = words_of(exported, id);
    image.push_back(id);
    image.push_back(static_cast<int16_t>(words.size()));
    image.insert(image.end(), words.begin(), words.end());
  }
  ASSERT_EQ(unit.flash_.Commit(UnitKind::kImu, image.data(), static_cast<uint16_t>(image.size())),
            FlashStatus::kOk);
  ASSERT_EQ(unit.Send(unit.client_.Reset()).data, std::vector<uint8_t>{1});
  EXPECT_EQ(unit.handler_.imu_constants().scale_temperature.enabled, 0);
  ImuConstants init;
  ImuConstantsInit(&init);
  for (uint8_t id = kImuBlockScaleSwitch; id <= kImuBlockLast; ++id) {
    EXPECT_EQ(unit.ReadBack(id), words_of(init, id)) << "block " << +id;
  }
  EXPECT_EQ(unit.ReadBack(kImuBlockCa), words_of(exported, kImuBlockCa));
}

TEST(MaintenanceHandlerTest, AdsUnitModesBlocksAndPowerCycle) {
  Unit unit(kAdsIdentity);
  EXPECT_EQ(unit.Send(unit.client_.SetAdsMode(AdsCompensationMode::kSurface)).result,
            ResultCode::kNoValidConstants);
  EXPECT_EQ(unit.Send(unit.client_.Request(0x01, std::vector<uint8_t>{2})).result,
            ResultCode::kBadArgument);
  EXPECT_EQ(
      unit.Send(unit.client_.WriteBlock(kImuBlockCa, ValidBlock(UnitKind::kImu, kImuBlockCa, 1)))
          .result,
      ResultCode::kUnknownBlock);
  unit.WriteAllBlocks(21);
  EXPECT_EQ(unit.ReadBack(kAdsBlockAirspeed), ValidBlock(UnitKind::kAds, kAdsBlockAirspeed, 21));
  ASSERT_EQ(hil::ParseCommit(unit.Send(unit.client_.Commit())).constants_version, 1);
  ASSERT_EQ(unit.Send(unit.client_.SetAdsMode(AdsCompensationMode::kSurface)).result,
            ResultCode::kAck);
  ASSERT_EQ(unit.Send(unit.client_.WriteBlock(kAdsBlockAltitude,
                                              ValidBlock(UnitKind::kAds, kAdsBlockAltitude, 99)))
                .result,
            ResultCode::kAck);
  ASSERT_EQ(unit.Send(unit.client_.Reset()).result, ResultCode::kAck);
  EXPECT_EQ(unit.handler_.ads_mode(), AdsCompensationMode::kRaw);
  EXPECT_EQ(unit.ReadBack(kAdsBlockAltitude), ValidBlock(UnitKind::kAds, kAdsBlockAltitude, 21));
  const hil::IdentifyInfo info = hil::ParseIdentify(unit.Send(unit.client_.Identify()));
  EXPECT_EQ(info.unit_kind, UnitKind::kAds);
  EXPECT_EQ(info.serial_number, 230017u);
  EXPECT_TRUE(info.constants_valid);
  // An IMU powered on with this flash finds no image of its own kind.
  MaintenanceHandler imu(kImuIdentity, &unit.flash_);
  EXPECT_FALSE(imu.constants_valid());
}

TEST(MaintenanceHandlerTest, ResetClearsCountersAndDataSequence) {
  Unit unit(kImuIdentity);
  EXPECT_EQ(unit.handler_.TakeDataSequence(), 0);
  for (int i = 1; i < 256; ++i) unit.handler_.TakeDataSequence();
  EXPECT_EQ(unit.handler_.TakeDataSequence(), 0);  // wrapped after 256 packets
  unit.handler_.TakeDataSequence();
  ASSERT_EQ(unit.Send(unit.client_.Request(0x77, {})).result, ResultCode::kUnknownCommand);
  ASSERT_EQ(unit.Send(unit.client_.Reset()).result, ResultCode::kAck);
  EXPECT_EQ(unit.handler_.TakeDataSequence(), 0);
  const hil::UnitCounters counters = hil::ParseCounters(unit.Send(unit.client_.ReadCounters()));
  EXPECT_EQ(counters.requests_naked, 0u);
  EXPECT_EQ(counters.requests_acked, 1u);     // the RESET ACK itself, counted after the power cycle
  EXPECT_EQ(counters.decoder.frames_ok, 1u);  // READ_COUNTERS
}

TEST(MaintenanceHandlerTest, ClientParsersRejectNaksAndMismatchesWithContext) {
  Unit unit(kImuIdentity);
  const hil::MaintenanceResponse nak =
      unit.Send(unit.client_.SetImuMode(ImuCompensationMode::kFullyCalibrated));
  try {
    hil::ParseCommit(nak);
    FAIL() << "ParseCommit accepted a response to SET_MODE";
  } catch (const hil::ProtocolError& e) {
    EXPECT_THAT(e.what(), HasSubstr("expected a response to COMMIT, got one to SET_MODE"));
  }
  const hil::MaintenanceResponse commit_nak = unit.Send(unit.client_.Commit());
  try {
    hil::ParseCommit(commit_nak);
    FAIL() << "ParseCommit accepted a NAK";
  } catch (const hil::ProtocolError& e) {
    EXPECT_THAT(e.what(), HasSubstr("COMMIT refused by the unit: NAK incomplete constants"));
  }
  Frame data_frame{};
  data_frame.type = static_cast<uint8_t>(PacketType::kImuData);
  data_frame.payload_length = 44;
  try {
    hil::ParseImuData(data_frame);
    FAIL() << "ParseImuData accepted a 44-byte payload";
  } catch (const hil::ProtocolError& e) {
    EXPECT_THAT(e.what(), HasSubstr("IMU data payload of 44 bytes is malformed"));
  }
  EXPECT_THROW(hil::ParseMaintenanceResponse(data_frame), hil::ProtocolError);
}

}  // namespace
}  // namespace adahrs::firmware_model
