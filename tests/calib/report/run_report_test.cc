// report.html checked structurally with an independent XML parser (python3 xml.etree): the
// sections exist, every figure is well-formed SVG with units in its axis labels, the constants
// table holds exactly the numbers of the constants.json file, missing inputs say "not available",
// and the ADS error map's reference column equals the altitudes the test set was aimed at.
#include "calib/report/run_report.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <ranges>
#include <string>
#include <string_view>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/constants/constants_file.h"
#include "common/gravity.h"
#include "hil/recording/recording_writer.h"
#include "tests/firmware_model/realistic_constants.h"
#include "tests/support/imu_recording_maker.h"
#include "tests/support/xml_tree.h"

namespace adahrs::calib {
namespace {

namespace fm = firmware_model;
using testing::FindAll;
using testing::FindTag;
using ::testing::HasSubstr;
using ::testing::Not;

class RunReportTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::filesystem::temp_directory_path() / ("adahrs_report_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    const auto params = std::vector<sensor_sim::ImuUnitParams>{
        sensor_sim::ImuUnitParams::Draw("IMU-0001", 2007, sensor_sim::ModelProfile::kNominal)};
    testing::ImuRecordingMaker maker(params, common::NormalGravityMps2(32.6, 200.0), 5);
    maker.Run(testing::ShippedSequence("imu_sensor_calibration", 50), dir_ / "run");
    AddAdsRows(dir_ / "run");
    std::filesystem::create_directories(dir_ / "fit");
    WriteConstantsFile(dir_ / "fit" / "IMU-0001.json", ImuConstants());
    WriteConstantsFile(dir_ / "fit" / "ADS-0001.json", AdsConstants());
  }
  static void TearDownTestSuite() { std::filesystem::remove_all(dir_); }

  // ADS rows at aims -1000...40000 ft, 25 degC, one TAG per aim, the reference pressure from the
  // fixture's own ISA (realistic_constants.h), codes synthesised from it.
  static void AddAdsRows(const std::filesystem::path& run) {
    nlohmann::json meta_file = nlohmann::json::parse(std::ifstream(run / "meta.json"));
    meta_file["units"].push_back({{"role", "ads1"},
                                  {"kind", "ads"},
                                  {"serial", "ADS-0001"},
                                  {"serial_number", 1},
                                  {"firmware", "1.0.0"},
                                  {"slot", 1},
                                  {"constants_version", 0},
                                  {"mode", 0}});
    // The maker's ads.csv holds only the header: write the ADS rows with a writer of their own and
    // put its ads.csv in place.
    const auto ads_dir = run.parent_path() / "ads_rows";
    std::filesystem::remove_all(ads_dir);
    hil::RecordingWriter writer(ads_dir, hil::RecordingStorage::kPlainCsv);
    int tag = 1;
    for (const double alt_ft : kAimsFt) {
      for (int i = 0; i < 10; ++i) {
        const fm::AdsRawFrame raw = fm::testing::SynthesiseAds(alt_ft, 150.0, 25.0);
        hil::AdsRecordRow row;
        row.t_s = tag * 100.0 + i * 0.01;
        row.unit = "ADS-0001";
        row.seq = static_cast<uint32_t>(i);
        row.step = tag;  // one acquisition per step, as the executor records them
        row.tag = static_cast<uint8_t>(tag);
        row.chamber_c = 25.0;
        row.ps_ref_pa = fm::testing::IsaPressure_pa(alt_ft);
        row.qc_ref_pa = fm::testing::ImpactPressure_pa(150.0);
        row.ps_cnt = raw.ps_cnt;
        row.pt_cnt = raw.pt_cnt;
        row.ps_temp_cnt = raw.ps_bridge_cnt;
        row.pt_temp_cnt = raw.pt_bridge_cnt;
        writer.Append(row);
      }
      ++tag;
    }
    writer.WriteMetaJson(meta_file);
    writer.Flush(true);
    std::filesystem::copy_file(
        ads_dir / "ads.csv", run / "ads.csv", std::filesystem::copy_options::overwrite_existing);
    std::ofstream(run / "meta.json") << meta_file.dump(2);
  }

  static ConstantsFile ImuConstants() {
    ConstantsFile f;
    f.serial = "IMU-0001";
    f.kind = hil::UnitKind::kImu;
    f.strategy = "reference";
    f.created_utc = "2024-05-01T09:00:00Z";
    f.software_version = "0.1.0";
    f.imu = fm::testing::RealisticImu(3);
    f.standard_errors = ImuStandardErrorsJson(Scaled(*f.imu));
    f.provenance.recordings = {{"run", std::string(64, 'b')}};
    return f;
  }
  static fm::ImuCalibrationConstants Scaled(fm::ImuCalibrationConstants c) {
    for (auto& t : c.thermal)
      for (double& k : t.k) k = 1e-3 * std::abs(k);
    for (auto& a : c.accel)
      a = {1e-3 * std::abs(a.offset_duty), 1e-3 * std::abs(a.scale_duty_per_g)};
    for (auto& g : c.gyro) {
      g.null_cnt = 0.5;
      for (double& l : g.l) l = 1e-3 * std::abs(l);
    }
    for (auto& r : c.ca_mps2_per_g)
      for (double& v : r) v = 1e-3 * std::abs(v);
    for (auto& r : c.cg)
      for (double& v : r) v = 1e-3 * std::abs(v);
    return c;
  }
  static ConstantsFile AdsConstants() {
    ConstantsFile f;
    f.serial = "ADS-0001";
    f.kind = hil::UnitKind::kAds;
    f.strategy = "reference";
    f.created_utc = "2024-05-01T09:00:00Z";
    f.software_version = "0.1.0";
    f.ads = fm::testing::RealisticAds();
    fm::AdsCalibrationConstants se = *f.ads;  // 0.1 % of each coefficient
    for (fm::SurfaceFit* surface : {&se.altitude_ft, &se.airspeed_kt}) {
      for (auto& row : surface->coeff_xy) {
        for (double& c : row) c = 1e-3 * std::abs(c);
      }
    }
    f.standard_errors = AdsStandardErrorsJson(se);
    return f;
  }

  static nlohmann::json Report(bool with_fit) {
    const auto out = dir_ / (with_fit ? "report.html" : "report_nofit.html");
    WriteRunReport(dir_ / "run", with_fit ? std::optional(dir_ / "fit") : std::nullopt, out);
    return testing::ParseXmlTree(out);
  }
  static nlohmann::json SectionById(const nlohmann::json& html, const std::string& id) {
    const auto found = FindAll(html, [&](const nlohmann::json& n) {
      return n["tag"] == "section" && n["attrib"].value("id", "") == id;
    });
    EXPECT_EQ(found.size(), 1u) << id;
    return found.empty() ? nlohmann::json() : found[0];
  }

  static constexpr double kAimsFt[] = {-1000.0, 5000.0, 20000.0, 40000.0};
  static inline std::filesystem::path dir_;
};

TEST_F(RunReportTest, SectionsFiguresAndConstantsMatchTheFiles) {
  const nlohmann::json html = Report(true);
  ASSERT_FALSE(html.is_null());
  for (const char* id : {"summary",
                         "IMU-0001",
                         "IMU-0001-constants",
                         "IMU-0001-thermal",
                         "IMU-0001-six-position",
                         "IMU-0001-gyro",
                         "IMU-0001-cross-axis",
                         "IMU-0001-noise",
                         "ADS-0001",
                         "ADS-0001-constants",
                         "ADS-0001-error-map",
                         "acceptance",
                         "evaluation"}) {
    SectionById(html, id);
  }
  // Every figure: well-formed SVG (parsed above), both axes labelled with a unit in parentheses.
  const auto svgs = FindTag(html, "svg");
  // Every figure says what it shows (data-figure): six-position residual, a scale-factor curve per
  // gyro, gyro residual, gyro and accelerometer Allan deviation; ADS-0001's raw codes of both
  // bridges and the codes less their straight line, the airspeed surface's residual map (every
  // acquisition is at 150 kt, none in the static sweep the altitude map takes), altitude and
  // airspeed error maps; and the time series: the instruments, IMU-0001's gyro counts and
  // accelerometer duty, ADS-0001's bridge codes.
  std::map<std::string, int> kinds;
  for (const auto& svg : svgs) ++kinds[svg["attrib"].value("data-figure", "")];
  EXPECT_EQ(kinds,
            (std::map<std::string, int>{{"six-position-residual", 1},
                                        {"gyro-scale", 3},
                                        {"gyro-residual", 1},
                                        {"allan", 2},
                                        {"ads-raw", 4},
                                        {"ads-surface-residual", 1},
                                        {"ads-error", 2},
                                        {"time-series", 4}}));
  EXPECT_EQ(FindTag(SectionById(html, "time-series"), "svg").size(), 4u);
  EXPECT_EQ(FindTag(SectionById(html, "ADS-0001-raw"), "svg").size(), 4u);
  for (const auto& svg : svgs) {
    EXPECT_THAT(FindTag(svg, "text", "xlabel").at(0)["text"].get<std::string>(), HasSubstr("("));
    EXPECT_THAT(FindTag(svg, "text", "ylabel").at(0)["text"].get<std::string>(), HasSubstr("("));
  }
  // The constants table holds exactly the file's numbers (read here straight from the file).
  const nlohmann::json file =
      nlohmann::json::parse(std::ifstream(dir_ / "fit" / "IMU-0001.json"))["constants"].flatten();
  const auto table = FindTag(SectionById(html, "IMU-0001-constants"), "table").at(0);
  size_t rows = 0;
  std::map<std::string, std::string> names;  // by JSON path
  for (const auto& tr : FindTag(table, "tr")) {
    const auto cells = FindTag(tr, "td");
    if (cells.empty()) continue;
    const std::string path = cells[1]["text"];
    ASSERT_TRUE(file.contains(path)) << path;
    const double expected = file[path].get<double>();
    // Printed to 10 significant digits.
    EXPECT_NEAR(std::stod(cells[2]["text"].get<std::string>()), expected, 1e-9 * std::abs(expected))
        << path;
    names[path] = cells[0]["text"];
    ++rows;
  }
  size_t numbers = 0;
  for (const auto& [path, value] : file.items()) numbers += value.is_number() ? 1 : 0;
  EXPECT_EQ(rows, numbers);
  // Named by channel and axis as docs/unit-protocol.md orders them (az1 ax1 ay1 az2 ax2 ay2 gx gy
  // gz; CA rows and columns x y z).
  EXPECT_EQ(names["/thermal/6/k/1"], "thermal gx k1");
  EXPECT_EQ(names["/accel/4/scale_duty_per_g"], "accel ax2 scale_duty_per_g");
  EXPECT_EQ(names["/gyro/2/null_cnt"], "gyro gz null_cnt");
  EXPECT_EQ(names["/ca_mps2_per_g/1/2"], "CA[y][z]");
  EXPECT_EQ(names["/cg/0/1"], "CG[x][y]");
  // No thermal profile in this run: said, not faked.
  EXPECT_THAT(SectionById(html, "IMU-0001-thermal")["text"].get<std::string>(),
              HasSubstr("Thermal drift not available"));
  // Six orientations in the six-position tables, each row with its chamber temperature.
  const auto six = FindTag(SectionById(html, "IMU-0001-six-position"), "table");
  const auto six_rows = FindTag(six.at(0), "tr");
  EXPECT_EQ(six_rows.size(), 1u + 6u);
  EXPECT_EQ(FindTag(six_rows.at(0), "th").at(0)["text"], "chamber (degC)");
  // The gyro table: per acquisition the chamber temperature, the mean raw counts and the counts
  // normalised by the step's 0 deg/s mean, which is 0 at 0 deg/s.
  const auto gyro_rows = FindTag(FindTag(SectionById(html, "IMU-0001-gyro"), "table").at(0), "tr");
  ASSERT_GT(gyro_rows.size(), 1u);
  int at_rest = 0;
  for (size_t r = 1; r < gyro_rows.size(); ++r) {
    const auto cells = FindTag(gyro_rows[r], "td");
    ASSERT_EQ(cells.size(), 7u);
    if (std::abs(std::stod(cells[2]["text"].get<std::string>())) < 0.5) {
      EXPECT_EQ(std::stod(cells[5]["text"].get<std::string>()), 0.0);
      ++at_rest;
    }
  }
  EXPECT_EQ(at_rest, 3);  // one 0 deg/s acquisition per gyro step
  // ADS: one row per aim, the reference column equal to the aim (the ISA of the fixture and of
  // sensor_sim agree to well under 0.5 ft over this range).
  const auto ads_tables = FindTag(SectionById(html, "ADS-0001-error-map"), "table");
  const auto ads_rows = FindTag(ads_tables.at(0), "tr");
  ASSERT_EQ(ads_rows.size(), 1u + std::size(kAimsFt));
  for (size_t i = 0; i < std::size(kAimsFt); ++i) {
    const auto cells = FindTag(ads_rows[i + 1], "td");
    EXPECT_NEAR(std::stod(cells[1]["text"].get<std::string>()), kAimsFt[i], 0.5);
  }
  EXPECT_THAT(SectionById(html, "acceptance")["text"].get<std::string>(),
              HasSubstr("acceptance.json not available"));
}

// The noise figures are log-log with a tick per decade, and the tables say in which units and at
// which tau each term was read (the maker's acquisitions are 50 packets: 0.5 s, short of 1 s).
TEST_F(RunReportTest, NoiseFiguresAreLogLogAndTheTermsNameTheirTau) {
  const nlohmann::json html = Report(true);
  ASSERT_FALSE(html.is_null());
  const nlohmann::json section = SectionById(html, "IMU-0001-noise");
  const auto svgs = FindTag(section, "svg");
  ASSERT_EQ(svgs.size(), 2u);
  for (const auto& svg : svgs) {
    EXPECT_EQ(FindTag(svg, "text", "xlabel").at(0)["text"], "cluster time tau (s)");
    for (const char* tick : {"xtick", "ytick"}) {
      const auto ticks = FindTag(svg, "line", tick);
      ASSERT_GE(ticks.size(), 2u);
      for (const auto& t : ticks) {
        const double exponent = std::log10(std::stod(t["attrib"]["data-value"].get<std::string>()));
        EXPECT_NEAR(exponent, std::round(exponent), 1e-9) << tick;
      }
    }
    EXPECT_EQ(FindTag(svg, "polyline", "series").size(), 3u);  // x, y, z
  }
  const auto tables = FindTag(section, "table");
  ASSERT_EQ(tables.size(), 2u);
  EXPECT_THAT(tables[0]["text"].get<std::string>(), HasSubstr("IEEE Std 952"));
  for (const auto& table : tables) {
    const auto rows = FindTag(table, "tr");
    ASSERT_EQ(rows.size(), 4u);  // header, x, y, z
    for (size_t r = 1; r < rows.size(); ++r) {
      const auto cells = FindTag(rows[r], "td");
      EXPECT_THAT(cells.at(1)["text"].get<std::string>(), HasSubstr("record too short for 1 s"));
      EXPECT_GT(std::stod(cells.at(2)["text"].get<std::string>()), 0.0);
      EXPECT_THAT(cells.at(4)["text"].get<std::string>(), HasSubstr("at tau"));
    }
  }
  const std::string header = FindTag(tables[0], "tr").at(0)["text"];
  EXPECT_THAT(header, HasSubstr("deg/sqrt(h)"));
  EXPECT_THAT(header, HasSubstr("one-sided"));
}

TEST_F(RunReportTest, WithoutAFitDirectoryEverySectionSaysWhy) {
  const nlohmann::json html = Report(false);
  ASSERT_FALSE(html.is_null());
  EXPECT_THAT(SectionById(html, "IMU-0001-constants")["text"].get<std::string>(),
              HasSubstr("no constants.json for IMU-0001"));
  EXPECT_THAT(SectionById(html, "ADS-0001-error-map")["text"].get<std::string>(),
              HasSubstr("not available"));
  EXPECT_THAT(SectionById(html, "IMU-0001-noise")["text"].get<std::string>(),
              HasSubstr("Noise not available"));
  EXPECT_THAT(SectionById(html, "evaluation")["text"].get<std::string>(),
              HasSubstr("no fit directory given"));
}

// A run the fit refuses (here every ADS row in one step, across four tags) draws no raw points
// either: the raw section states the fit's refusal, naming ads.csv and the line.
TEST_F(RunReportTest, RawRowsTheFitRefusesAreShownWithItsReason) {
  const auto run = dir_ / "run_one_step";
  std::filesystem::remove_all(run);
  std::filesystem::copy(dir_ / "run", run, std::filesystem::copy_options::recursive);
  std::ifstream in(dir_ / "run" / "ads.csv");
  std::ofstream out(run / "ads.csv");
  std::string line;
  std::getline(in, line);
  out << line << "\n";
  const auto header = std::string_view(line);
  const size_t step_column = std::ranges::count(header.substr(0, header.find("step,")), ',');
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    for (const auto cell : std::views::split(line, ','))
      cells.emplace_back(cell.begin(), cell.end());
    cells.at(step_column) = "1";
    for (size_t i = 0; i < cells.size(); ++i) out << (i ? "," : "") << cells[i];
    out << "\n";
  }
  out.close();
  WriteRunReport(run, dir_ / "fit", dir_ / "report_one_step.html");
  const nlohmann::json html = testing::ParseXmlTree(dir_ / "report_one_step.html");
  const std::string raw = SectionById(html, "ADS-0001-raw")["text"].get<std::string>();
  EXPECT_THAT(raw, HasSubstr("not available"));
  EXPECT_THAT(raw, HasSubstr("ads.csv line 12 column tag: unit ADS-0001 step 1 carries tag 2"));
  EXPECT_TRUE(FindTag(SectionById(html, "ADS-0001-raw"), "svg").empty());
}

// The ADS error maps are drawn against the specification given (a campaign's file), not the -A
// compiled in: a file whose altitude tolerances are ten times the -A's gives ten times each row's
// tolerance, and the band names the file's specification.
TEST_F(RunReportTest, AdsErrorMapsUseTheSpecificationGiven) {
  nlohmann::json wide = nlohmann::json::parse(
      std::ifstream(std::string(ADAHRS_SOURCE_DIR) + "/calib/specifications/ahr150a-a.json"));
  wide["name"] = "WIDE-TEST";
  for (auto& point : wide["quantities"]["altitude"]["points_ft"])
    point[1] = 10.0 * point[1].get<double>();
  const auto spec_path = dir_ / "wide.json";
  std::ofstream(spec_path) << wide.dump();
  WriteRunReport(dir_ / "run", dir_ / "fit", dir_ / "report_a.html");
  WriteRunReport(dir_ / "run",
                 dir_ / "fit",
                 dir_ / "report_wide.html",
                 std::nullopt,
                 ReadSpecificationFile(spec_path));
  // Each altitude row's tolerance column (the 4th), in order.
  const auto tolerances = [&](const std::filesystem::path& file, std::string* band) {
    const nlohmann::json html = testing::ParseXmlTree(file);
    const nlohmann::json section = SectionById(html, "ADS-0001-error-map");
    *band = section.dump();
    std::vector<double> out;
    for (const auto& table : FindTag(section, "table")) {
      if (table.dump().find("reference (ft)") == std::string::npos) continue;
      for (const auto& tr : FindTag(table, "tr")) {
        const auto cells = FindTag(tr, "td");
        if (cells.size() == 5) out.push_back(std::stod(cells[3]["text"].get<std::string>()));
      }
    }
    return out;
  };
  std::string band_a, band_wide;
  const std::vector<double> a = tolerances(dir_ / "report_a.html", &band_a);
  const std::vector<double> w = tolerances(dir_ / "report_wide.html", &band_wide);
  ASSERT_FALSE(a.empty());
  ASSERT_EQ(a.size(), w.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(w[i], 10.0 * a[i], 1e-9 * w[i]) << i;
  EXPECT_THAT(band_a, HasSubstr("AHR150A-A tolerance"));
  EXPECT_THAT(band_wide, HasSubstr("WIDE-TEST tolerance"));
  EXPECT_THAT(band_wide, Not(HasSubstr("AHR150A-A tolerance")));
}

// A calibration run has no acceptance files: page one says it was not judged, and where from.
TEST_F(RunReportTest, AnUnjudgedRunSaysSoOnPageOne) {
  const nlohmann::json html = Report(true);
  const auto paragraphs = FindTag(SectionById(html, "verdict"), "p");
  ASSERT_EQ(paragraphs.size(), 1u);
  EXPECT_THAT(paragraphs[0]["text"].get<std::string>(), HasSubstr("Not judged"));
  EXPECT_TRUE(FindTag(SectionById(html, "verdict"), "table").empty());
}

TEST_F(RunReportTest, AcceptanceVerdictsShowAsPassAndFail) {
  std::ofstream(dir_ / "fit" / "acceptance.json")
      << R"({"run_id": "acc", "points": [{"serial": "IMU-0001", "quantity": "rate_z",
            "error": 0.02, "tolerance": 0.015, "pass": false},
           {"serial": "IMU-0001", "quantity": "accel_x", "error": 0.0004, "tolerance": 0.001,
            "pass": true}]})";
  const nlohmann::json html = Report(true);
  std::filesystem::remove(dir_ / "fit" / "acceptance.json");
  const auto cells = FindTag(SectionById(html, "acceptance"), "td");
  std::vector<std::string> verdicts;
  for (const auto& c : cells) {
    if (c["attrib"].contains("class")) verdicts.push_back(c["text"]);
  }
  EXPECT_THAT(verdicts, ::testing::ElementsAre("FAIL", "PASS"));
}

}  // namespace
}  // namespace adahrs::calib
