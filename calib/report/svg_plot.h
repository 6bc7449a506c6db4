// A small inline-SVG x-y plot for report.html: framed axes with nice ticks (nice_ticks.h), axis
// labels that carry their units, a title, series drawn as polylines or point markers, optional
// shaded bands (a tolerance envelope: lower and upper y at each x) and a legend. The output is one
// self-contained <svg> element (SVG 1.1, no scripts, no external references), well-formed XML with
// every text escaped, so it can be embedded in HTML or parsed by any XML reader.
// Coordinates: data (x, y) maps linearly to pixels, x to the right, y upwards, inside the frame;
// an axis marked logarithmic maps log10 of the value instead, with a tick per decade, and values
// <= 0 on it are not drawn (as non-finite ones).
// Left out: multiple y axes, error bars, colour maps (a heat map is a set of series).
#pragma once

#include <string>
#include <vector>

#include "common/html_page.h"

namespace adahrs::calib {

struct PlotSeries {
  enum class Style { kLine, kPoints };
  std::string label;  ///< legend text
  std::vector<double> x;
  std::vector<double> y;
  Style style = Style::kLine;
  std::string colour{};  ///< empty: the palette's colour for the series' place
};

/// A shaded region between y_lo(x) and y_hi(x) (e.g. the specification's tolerance envelope).
struct PlotBand {
  std::string label;
  std::vector<double> x;
  std::vector<double> y_lo;
  std::vector<double> y_hi;
  std::string colour = "#2ca02c";  ///< fill, drawn at 15 % opacity
};

struct Plot {
  std::string title;
  std::string x_label;  ///< with its unit, e.g. "chamber temperature (degC)"
  std::string y_label;  ///< with its unit
  std::vector<PlotSeries> series;
  std::vector<PlotBand> bands;
  bool log_x = false;  ///< decade axis (an Allan deviation's tau)
  bool log_y = false;
  int width_px = 640;
  int height_px = 360;
  /// What the figure shows, as the <svg>'s data-figure attribute ("time-series", "thermal-fit",
  /// ...; docs/report.md "Figures"): how a reader of the page counts figures by kind. Empty: none.
  std::string figure{};
};

/// The plot as an <svg> element. Non-finite points are skipped (a line breaks there). Throws
/// std::invalid_argument naming the plot and series if x and y lengths differ or nothing is
/// drawable.
std::string RenderSvg(const Plot& plot);

/// The XML escape of every text in the reports (common/html_page.h).
using common::XmlEscape;

}  // namespace adahrs::calib
