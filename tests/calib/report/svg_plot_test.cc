#include "calib/report/svg_plot.h"

#include <unistd.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/report/nice_ticks.h"
#include "tests/support/xml_tree.h"

namespace adahrs::calib {
namespace {

using ::testing::ElementsAre;
using testing::FindTag;
using ::testing::HasSubstr;
using testing::ParseXmlTree;

// True if `step` is 1, 2 or 5 times a power of ten (to 1e-9 relative).
bool IsNiceStep(double step) {
  const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-12));
  return std::abs(mantissa - 1.0) < 1e-9 || std::abs(mantissa - 2.0) < 1e-9 ||
         std::abs(mantissa - 5.0) < 1e-9;
}

TEST(NiceTicksTest, CoversTheRangeWithNiceStepsOnMultiplesOfTheStep) {
  struct Case {
    double lo, hi;
  };
  for (const Case c : {Case{0.0, 1.0},
                       Case{-3.7, 12.1},
                       Case{-40.0, 85.0},
                       Case{4.7e-5, 4.9e-5},
                       Case{-1000.0, 50000.0},
                       Case{-0.0123, 0.0071},
                       Case{3.0, 3.0}}) {
    const AxisTicks t = NiceTicks(c.lo, c.hi, 8);
    EXPECT_LE(t.lo, c.lo) << c.lo;
    EXPECT_GE(t.hi, c.hi) << c.hi;
    EXPECT_TRUE(IsNiceStep(t.step)) << t.step;
    EXPECT_GE(t.values.size(), 2u);
    EXPECT_LE(t.values.size(), 8u);
    for (const double v : t.values) {
      EXPECT_NEAR(v / t.step, std::round(v / t.step), 1e-6) << v << " step " << t.step;
    }
  }
  // Worked by hand: [0, 1] in at most 6 ticks -> 0, 0.2, ..., 1.
  const AxisTicks unit = NiceTicks(0.0, 1.0, 6);
  EXPECT_DOUBLE_EQ(unit.step, 0.2);
  EXPECT_EQ(unit.values.size(), 6u);
  // [-40, 85] degC in at most 8 ticks: step 20 from -40 to 100.
  const AxisTicks temp = NiceTicks(-40.0, 85.0, 8);
  EXPECT_DOUBLE_EQ(temp.step, 20.0);
  EXPECT_DOUBLE_EQ(temp.lo, -40.0);
  EXPECT_DOUBLE_EQ(temp.hi, 100.0);
  EXPECT_THROW(NiceTicks(0.0, NAN, 8), std::invalid_argument);
}

TEST(NiceTicksTest, LabelsCarryTheDecimalsTheStepNeeds) {
  EXPECT_EQ(TickLabel(0.4, 0.2), "0.4");
  EXPECT_EQ(TickLabel(-20.0, 20.0), "-20");
  EXPECT_EQ(TickLabel(0.015, 0.005), "0.015");
  EXPECT_EQ(TickLabel(4.8e-5, 1e-6), "4.8e-05");
}

class SvgPlotTest : public ::testing::Test {
 protected:
  nlohmann::json RenderAndParse(const Plot& plot) {
    const auto file = std::filesystem::temp_directory_path() /
                      ("adahrs_svg_" + std::to_string(::getpid()) + ".svg");
    std::ofstream(file) << RenderSvg(plot);
    nlohmann::json tree = ParseXmlTree(file);
    std::filesystem::remove(file);
    return tree;
  }
  static std::vector<std::pair<double, double>> Points(const std::string& attribute) {
    std::vector<std::pair<double, double>> points;
    std::istringstream in(attribute);
    std::string pair;
    while (in >> pair) {
      const size_t comma = pair.find(',');
      points.emplace_back(std::stod(pair.substr(0, comma)), std::stod(pair.substr(comma + 1)));
    }
    return points;
  }
};

TEST_F(SvgPlotTest, PointsLandOnTheirTicksAndLabelsLegendAndTitleAreThere) {
  Plot plot;
  plot.title = "IMU-0001 gz drift <thermal> & fit";
  plot.x_label = "temperature (counts)";
  plot.y_label = "drift (counts)";
  // x and y at values that are ticks of their axes: [0, 100] -> step 20, [-10, 30] -> step 10.
  plot.series.push_back(
      {"measured", {0.0, 20.0, 100.0}, {-10.0, 30.0, 0.0}, PlotSeries::Style::kLine});
  plot.series.push_back({"fit", {40.0, NAN, 60.0}, {10.0, 0.0, 20.0}, PlotSeries::Style::kPoints});
  const nlohmann::json svg = RenderAndParse(plot);
  ASSERT_FALSE(svg.is_null());
  EXPECT_EQ(svg["tag"], "svg");
  EXPECT_EQ(FindTag(svg, "title")[0]["text"],
            plot.title);  // escaped in the file, intact when parsed
  std::map<double, double> x_px, y_px;
  for (const auto& tick : FindTag(svg, "line", "xtick")) {
    x_px[std::stod(tick["attrib"]["data-value"].get<std::string>())] =
        std::stod(tick["attrib"]["x1"].get<std::string>());
  }
  for (const auto& tick : FindTag(svg, "line", "ytick")) {
    y_px[std::stod(tick["attrib"]["data-value"].get<std::string>())] =
        std::stod(tick["attrib"]["y1"].get<std::string>());
  }
  ASSERT_TRUE(x_px.count(0.0) && x_px.count(20.0) && x_px.count(100.0));
  ASSERT_TRUE(y_px.count(-10.0) && y_px.count(30.0) && y_px.count(0.0));
  EXPECT_LT(y_px[30.0], y_px[-10.0]);  // y grows upwards
  const auto lines = FindTag(svg, "polyline", "series");
  ASSERT_EQ(lines.size(), 1u);
  const auto points = Points(lines[0]["attrib"]["points"]);
  ASSERT_EQ(points.size(), 3u);
  // Coordinates are written to 0.01 px.
  EXPECT_NEAR(points[0].first, x_px[0.0], 0.01);
  EXPECT_NEAR(points[0].second, y_px[-10.0], 0.01);
  EXPECT_NEAR(points[1].first, x_px[20.0], 0.01);
  EXPECT_NEAR(points[1].second, y_px[30.0], 0.01);
  EXPECT_NEAR(points[2].first, x_px[100.0], 0.01);
  EXPECT_NEAR(points[2].second, y_px[0.0], 0.01);
  // The NaN point is skipped: two markers.
  EXPECT_EQ(FindTag(svg, "circle").size(), 2u);
  std::vector<std::string> legend;
  for (const auto& entry : FindTag(svg, "g", "legend")) legend.push_back(entry["text"]);
  EXPECT_THAT(legend, ElementsAre("measured", "fit"));
  EXPECT_EQ(FindTag(svg, "text", "xlabel")[0]["text"], "temperature (counts)");
  EXPECT_EQ(FindTag(svg, "text", "ylabel")[0]["text"], "drift (counts)");
}

// A decade axis: ticks at whole powers of ten, points placed by log10 (a decade is the same
// width everywhere: 0.01 -> 0.1 as wide as 1 -> 10), values <= 0 not drawn, labels as numbers.
TEST_F(SvgPlotTest, LogAxesPutTicksOnDecadesAndPointsByTheirLogarithm) {
  Plot plot{"Allan deviation", "cluster time tau (s)", "Allan deviation (deg/s)", {}, {}};
  plot.log_x = plot.log_y = true;
  plot.series.push_back(
      {"G x", {0.01, 0.1, 1.0, 10.0, 0.0}, {0.5, 0.2, 0.05, 0.02, 1.0}, PlotSeries::Style::kLine});
  const nlohmann::json svg = RenderAndParse(plot);
  ASSERT_FALSE(svg.is_null());
  std::map<double, double> x_px;
  std::vector<std::string> x_labels;
  for (const auto& tick : FindTag(svg, "line", "xtick")) {
    x_px[std::stod(tick["attrib"]["data-value"].get<std::string>())] =
        std::stod(tick["attrib"]["x1"].get<std::string>());
  }
  std::vector<double> x_values;
  for (const auto& [value, px] : x_px) x_values.push_back(value);
  ASSERT_EQ(x_values.size(), 4u);
  EXPECT_DOUBLE_EQ(x_values[0], 0.01);
  EXPECT_DOUBLE_EQ(x_values[3], 10.0);
  EXPECT_NEAR(x_px[0.1] - x_px[0.01], x_px[10.0] - x_px[1.0], 0.02);
  std::vector<double> y_values;
  for (const auto& tick : FindTag(svg, "line", "ytick")) {
    y_values.push_back(std::stod(tick["attrib"]["data-value"].get<std::string>()));
  }
  EXPECT_THAT(y_values, ElementsAre(0.01, 0.1, 1.0));
  EXPECT_THAT(svg["text"].get<std::string>(), HasSubstr("0.01"));
  const auto lines = FindTag(svg, "polyline", "series");
  ASSERT_EQ(lines.size(), 1u);
  const auto points = Points(lines[0]["attrib"]["points"]);
  ASSERT_EQ(points.size(), 4u);  // tau 0 is not on a decade axis
  EXPECT_NEAR(points[0].first, x_px[0.01], 0.01);
  EXPECT_NEAR(points[2].first, x_px[1.0], 0.01);
}

TEST_F(SvgPlotTest, BandIsAClosedPolygonAroundItsLimits) {
  Plot plot;
  plot.title = "envelope";
  plot.x_label = "x (ft)";
  plot.y_label = "error (ft)";
  plot.bands.push_back({"tolerance", {0.0, 10.0}, {-15.0, -20.0}, {15.0, 20.0}});
  plot.series.push_back({"error", {0.0, 10.0}, {1.0, -2.0}, PlotSeries::Style::kLine});
  const nlohmann::json svg = RenderAndParse(plot);
  const auto bands = FindTag(svg, "polygon", "band");
  ASSERT_EQ(bands.size(), 1u);
  EXPECT_EQ(Points(bands[0]["attrib"]["points"]).size(), 4u);
  EXPECT_EQ(bands[0]["attrib"]["data-label"], "tolerance");
}

// What the figure shows is its <svg>'s data-figure attribute; a series' or a band's own colour
// replaces the palette's, in the plot and in the legend.
TEST_F(SvgPlotTest, FigureKindAndOwnColoursAreWritten) {
  Plot plot;
  plot.title = "map";
  plot.x_label = "x (degC)";
  plot.y_label = "y (ft)";
  plot.figure = "ads-surface-residual";
  plot.bands.push_back({"limit", {0.0, 1.0}, {-1.0, -1.0}, {1.0, 1.0}, "#123456"});
  plot.series.push_back({"ok", {0.0}, {0.5}, PlotSeries::Style::kPoints, "#abcdef"});
  plot.series.push_back({"palette", {1.0}, {0.5}, PlotSeries::Style::kPoints});
  const nlohmann::json svg = RenderAndParse(plot);
  EXPECT_EQ(svg["attrib"]["data-figure"], "ads-surface-residual");
  EXPECT_EQ(FindTag(svg, "polygon", "band").at(0)["attrib"]["fill"], "#123456");
  const auto series = FindTag(svg, "g", "series");
  ASSERT_EQ(series.size(), 2u);
  EXPECT_EQ(series[0]["attrib"]["fill"], "#abcdef");
  EXPECT_EQ(series[1]["attrib"]["fill"], "#d62728");  // the palette's second colour
  std::vector<std::string> fills;
  for (const auto& rect : FindTag(svg, "rect")) fills.push_back(rect["attrib"].value("fill", ""));
  EXPECT_THAT(fills, ::testing::Contains("#abcdef"));
  EXPECT_THAT(fills, ::testing::Contains("#123456"));
  plot.figure.clear();
  EXPECT_FALSE(RenderAndParse(plot)["attrib"].contains("data-figure"));
}

TEST_F(SvgPlotTest, MismatchedOrEmptySeriesAreRefusedByName) {
  Plot plot;
  plot.title = "bad";
  plot.series.push_back({"gx", {1.0, 2.0}, {1.0}, PlotSeries::Style::kLine});
  try {
    RenderSvg(plot);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("plot 'bad': series 'gx' has 2 x values and 1 y values"));
  }
  plot.series[0].y = {NAN, NAN};
  EXPECT_THROW(RenderSvg(plot), std::invalid_argument);
}

}  // namespace
}  // namespace adahrs::calib
