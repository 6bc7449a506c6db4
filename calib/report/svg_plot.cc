#include "calib/report/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "calib/report/nice_ticks.h"

namespace adahrs::calib {
namespace {

constexpr int kMarginLeftPx = 78;
constexpr int kMarginRightPx = 16;
constexpr int kMarginTopPx = 30;
constexpr int kMarginBottomPx = 48;
constexpr int kLegendRowPx = 16;
constexpr int kMaxTicks = 8;
constexpr const char* kColours[] = {"#1f77b4",
                                    "#d62728",
                                    "#2ca02c",
                                    "#ff7f0e",
                                    "#9467bd",
                                    "#8c564b",
                                    "#e377c2",
                                    "#17becf",
                                    "#7f7f7f",
                                    "#bcbd22"};

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void Add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool Empty() const { return lo > hi; }
};

struct Frame {
  AxisTicks x, y;
  double left, right, top, bottom;
  double Px(double v) const { return left + (v - x.lo) / (x.hi - x.lo) * (right - left); }
  double Py(double v) const { return bottom - (v - y.lo) / (y.hi - y.lo) * (bottom - top); }
};

void CheckLengths(const Plot& plot, const std::string& what, size_t x, size_t y) {
  if (x != y) {
    throw std::invalid_argument(
        fmt::format("plot '{}': {} has {} x values and {} y values", plot.title, what, x, y));
  }
}

std::string Colour(size_t i) { return kColours[i % std::size(kColours)]; }

// A series' own colour, else the palette's for its place.
std::string SeriesColour(const Plot& plot, size_t i) {
  return plot.series[i].colour.empty() ? Colour(i) : XmlEscape(plot.series[i].colour);
}

// The value as the axis maps it: log10 on a decade axis (NaN for values <= 0, not drawn).
double OnAxis(double v, bool log) {
  if (!log) return v;
  return v > 0.0 ? std::log10(v) : std::numeric_limits<double>::quiet_NaN();
}

// `plot` with every coordinate on a logarithmic axis replaced by its log10.
Plot ToAxisCoordinates(const Plot& plot) {
  Plot out = plot;
  for (PlotSeries& s : out.series) {
    for (double& x : s.x) x = OnAxis(x, plot.log_x);
    for (double& y : s.y) y = OnAxis(y, plot.log_y);
  }
  for (PlotBand& b : out.bands) {
    for (double& x : b.x) x = OnAxis(x, plot.log_x);
    for (double& y : b.y_lo) y = OnAxis(y, plot.log_y);
    for (double& y : b.y_hi) y = OnAxis(y, plot.log_y);
  }
  return out;
}

AxisTicks Ticks(const Range& r, bool log) {
  return log ? DecadeTicks(r.lo, r.hi) : NiceTicks(r.lo, r.hi, kMaxTicks);
}

// Tick value as data (10^v on a decade axis) and its label.
double TickData(double v, bool log) { return log ? std::pow(10.0, v) : v; }
std::string Label(double v, const AxisTicks& t, bool log) {
  return log ? DecadeLabel(v) : TickLabel(v, t.step);
}

struct DataRanges {
  Range x, y;
};

// The ranges of every finite point of the series and bands; refuses mismatched lengths and a plot
// with nothing to draw.
DataRanges CheckedDataRanges(const Plot& plot) {
  DataRanges r;
  for (const PlotSeries& s : plot.series) {
    CheckLengths(plot, "series '" + s.label + "'", s.x.size(), s.y.size());
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) {
        r.x.Add(s.x[i]);
        r.y.Add(s.y[i]);
      }
    }
  }
  for (const PlotBand& b : plot.bands) {
    CheckLengths(plot, "band '" + b.label + "'", b.x.size(), b.y_lo.size());
    CheckLengths(plot, "band '" + b.label + "'", b.x.size(), b.y_hi.size());
    for (size_t i = 0; i < b.x.size(); ++i) {
      r.x.Add(b.x[i]);
      r.y.Add(b.y_lo[i]);
      r.y.Add(b.y_hi[i]);
    }
  }
  if (r.x.Empty() || r.y.Empty()) {
    throw std::invalid_argument(fmt::format("plot '{}': no finite point to draw", plot.title));
  }
  return r;
}

Frame FrameFor(const Plot& plot, const DataRanges& r) {
  return Frame{Ticks(r.x, plot.log_x),
               Ticks(r.y, plot.log_y),
               static_cast<double>(kMarginLeftPx),
               static_cast<double>(plot.width_px - kMarginRightPx),
               static_cast<double>(kMarginTopPx),
               static_cast<double>(plot.height_px - kMarginBottomPx)};
}

// The opening <svg> element, sized for the plot and one legend row per series and band, and the
// title.
std::string SvgHeader(const Plot& plot) {
  const size_t legend_rows = plot.series.size() + plot.bands.size();
  const int height_px = plot.height_px + static_cast<int>(legend_rows) * kLegendRowPx;
  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\"{} width=\"{}\" height=\"{}\" "
      "viewBox=\"0 0 {} {}\" font-family=\"sans-serif\" font-size=\"11\">\n",
      plot.figure.empty() ? "" : fmt::format(" data-figure=\"{}\"", XmlEscape(plot.figure)),
      plot.width_px,
      height_px,
      plot.width_px,
      height_px);
  svg += fmt::format("<title>{}</title>\n", XmlEscape(plot.title));
  svg += fmt::format(
      "<text class=\"title\" x=\"{}\" y=\"18\" text-anchor=\"middle\" "
      "font-size=\"13\">{}</text>\n",
      plot.width_px / 2,
      XmlEscape(plot.title));
  return svg;
}

// Each band as a polygon: along its upper edge, back along its lower one.
std::string BandPolygons(const Plot& plot, const Frame& f) {
  std::string svg;
  for (const PlotBand& b : plot.bands) {
    std::string points;
    for (size_t k = 0; k < b.x.size(); ++k) {
      points += fmt::format("{:.2f},{:.2f} ", f.Px(b.x[k]), f.Py(b.y_hi[k]));
    }
    for (size_t k = b.x.size(); k-- > 0;) {
      points += fmt::format("{:.2f},{:.2f} ", f.Px(b.x[k]), f.Py(b.y_lo[k]));
    }
    svg += fmt::format(
        "<polygon class=\"band\" data-label=\"{}\" points=\"{}\" fill=\"{}\" "
        "fill-opacity=\"0.15\" stroke=\"none\"/>\n",
        XmlEscape(b.label),
        points,
        XmlEscape(b.colour));
  }
  return svg;
}

// The frame around the plot area and the ticks with their labels on both axes.
std::string FrameAndTicks(const Plot& plot, const Frame& f) {
  std::string svg;
  svg += fmt::format(
      "<rect class=\"frame\" x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" "
      "height=\"{:.2f}\" fill=\"none\" stroke=\"#333\"/>\n",
      f.left,
      f.top,
      f.right - f.left,
      f.bottom - f.top);
  for (const double v : f.x.values) {
    svg += fmt::format(
        "<line class=\"xtick\" data-value=\"{:.12g}\" x1=\"{:.2f}\" y1=\"{:.2f}\" "
        "x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"#333\"/>"
        "<text x=\"{:.2f}\" y=\"{:.2f}\" text-anchor=\"middle\">{}</text>\n",
        TickData(v, plot.log_x),
        f.Px(v),
        f.bottom,
        f.Px(v),
        f.bottom + 5,
        f.Px(v),
        f.bottom + 17,
        Label(v, f.x, plot.log_x));
  }
  for (const double v : f.y.values) {
    svg += fmt::format(
        "<line class=\"ytick\" data-value=\"{:.12g}\" x1=\"{:.2f}\" y1=\"{:.2f}\" "
        "x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"#333\"/>"
        "<text x=\"{:.2f}\" y=\"{:.2f}\" text-anchor=\"end\">{}</text>\n",
        TickData(v, plot.log_y),
        f.left - 5,
        f.Py(v),
        f.left,
        f.Py(v),
        f.left - 7,
        f.Py(v) + 4,
        Label(v, f.y, plot.log_y));
  }
  return svg;
}

std::string AxisLabels(const Plot& plot, const Frame& f) {
  std::string svg;
  svg += fmt::format(
      "<text class=\"xlabel\" x=\"{:.2f}\" y=\"{:.2f}\" text-anchor=\"middle\">{}"
      "</text>\n",
      (f.left + f.right) / 2,
      f.bottom + 36,
      XmlEscape(plot.x_label));
  svg += fmt::format(
      "<text class=\"ylabel\" x=\"14\" y=\"{:.2f}\" text-anchor=\"middle\" "
      "transform=\"rotate(-90 14 {:.2f})\">{}</text>\n",
      (f.top + f.bottom) / 2,
      (f.top + f.bottom) / 2,
      XmlEscape(plot.y_label));
  return svg;
}

// A line series: a non-finite point ends one polyline; the next finite point starts another.
std::string LineSeries(const PlotSeries& s, const std::string& colour, const Frame& f) {
  std::string svg, points;
  auto flush = [&] {
    if (!points.empty()) {
      svg += fmt::format(
          "<polyline class=\"series\" data-label=\"{}\" points=\"{}\" "
          "fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"/>\n",
          XmlEscape(s.label),
          points,
          colour);
    }
    points.clear();
  };
  for (size_t k = 0; k < s.x.size(); ++k) {
    if (!std::isfinite(s.x[k]) || !std::isfinite(s.y[k])) {
      flush();
      continue;
    }
    points += fmt::format("{:.2f},{:.2f} ", f.Px(s.x[k]), f.Py(s.y[k]));
  }
  flush();
  return svg;
}

// A point series: a circle per finite point, in one group.
std::string PointSeries(const PlotSeries& s, const std::string& colour, const Frame& f) {
  std::string svg =
      fmt::format("<g class=\"series\" data-label=\"{}\" fill=\"{}\">", XmlEscape(s.label), colour);
  for (size_t k = 0; k < s.x.size(); ++k) {
    if (!std::isfinite(s.x[k]) || !std::isfinite(s.y[k])) continue;
    svg +=
        fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"2.5\"/>", f.Px(s.x[k]), f.Py(s.y[k]));
  }
  svg += "</g>\n";
  return svg;
}

// One legend row per series, then one per band, below the plot area.
std::string Legend(const Plot& plot, const Frame& f) {
  std::string svg;
  double legend_y = plot.height_px - 4.0;
  for (size_t i = 0; i < plot.series.size(); ++i, legend_y += kLegendRowPx) {
    svg += fmt::format(
        "<g class=\"legend\"><rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"14\" "
        "height=\"4\" fill=\"{}\"/><text x=\"{:.2f}\" y=\"{:.2f}\">{}</text></g>\n",
        f.left,
        legend_y + 4,
        SeriesColour(plot, i),
        f.left + 20,
        legend_y + 10,
        XmlEscape(plot.series[i].label));
  }
  for (const PlotBand& b : plot.bands) {
    svg += fmt::format(
        "<g class=\"legend\"><rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"14\" "
        "height=\"10\" fill=\"{}\" fill-opacity=\"0.15\"/><text x=\"{:.2f}\" "
        "y=\"{:.2f}\">{}</text></g>\n",
        f.left,
        legend_y + 1,
        XmlEscape(b.colour),
        f.left + 20,
        legend_y + 10,
        XmlEscape(b.label));
    legend_y += kLegendRowPx;
  }
  return svg;
}

}  // namespace

std::string RenderSvg(const Plot& data_plot) {
  const Plot plot = ToAxisCoordinates(data_plot);
  const Frame f = FrameFor(plot, CheckedDataRanges(plot));
  std::string svg = SvgHeader(plot);
  svg += BandPolygons(plot, f);
  svg += FrameAndTicks(plot, f);
  svg += AxisLabels(plot, f);
  for (size_t i = 0; i < plot.series.size(); ++i) {
    const PlotSeries& s = plot.series[i];
    svg += s.style == PlotSeries::Style::kLine ? LineSeries(s, SeriesColour(plot, i), f)
                                               : PointSeries(s, SeriesColour(plot, i), f);
  }
  svg += Legend(plot, f);
  svg += "</svg>\n";
  return svg;
}

}  // namespace adahrs::calib
