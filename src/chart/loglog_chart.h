#pragma once
// A log-log line chart drawn with cairo into a PNG, no window or GPU needed:
// decade ticks and labels, one coloured line with markers per series, some
// points ringed (a Pareto front, say), dashed horizontal rules, shaded bands, a legend and a
// title. Knows nothing of cloth; trade_chart.h feeds it.
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

namespace neurocloth {

struct Rgb {
  double r = 0, g = 0, b = 0;  // 0..1
};

struct ChartPoint {
  double x = 0, y = 0;
  bool ringed = false;  // drawn with a black ring around its marker
};

struct ChartSeries {
  std::string name;
  Rgb colour;
  std::vector<ChartPoint> points;  // joined in this order; non-positive or NaN ones are left out
};

// A dashed horizontal line across the plot (e.g. a resolution limit).
struct ChartRule {
  double y = 0;
  std::string label;
};

// A shaded horizontal band across the plot, from y = lo to y = hi (e.g. a
// spread no point below can be told from).
struct ChartBand {
  double lo = 0, hi = 0;
  std::string label;
};

struct ChartSpec {
  std::string title, x_label, y_label;
  int width = 960, height = 600;  // pixels
  std::vector<ChartSeries> series;
  std::vector<ChartRule> rules;
  std::vector<ChartBand> bands;  // drawn first, under everything
  // The ringed points joined by a dashed black line in x order, under this legend name
  // (empty: rings only, no line, no legend entry).
  std::string ring_legend;
};

class LogLogChart {
 public:
  // Axes span whole decades around every finite positive point and rule.
  explicit LogLogChart(ChartSpec spec);

  // Where a data point lands, in pixels from the picture's top left.
  std::pair<double, double> to_pixel(double x, double y) const;
  // The decade exponents the axes span: 10^x_lo .. 10^x_hi and 10^y_lo .. 10^y_hi.
  int x_lo() const { return x_lo_; }
  int x_hi() const { return x_hi_; }
  int y_lo() const { return y_lo_; }
  int y_hi() const { return y_hi_; }
  const ChartSpec& spec() const { return spec_; }

  // The chart as PNG bytes on `out`. Throws std::runtime_error naming `name`
  // (the file the bytes are for) when cairo cannot draw or encode it.
  void write_png(std::ostream& out, const std::string& name) const;
  // The chart as the PNG file `path`, whole or not at all (write_file_atomically).
  void write_png(const std::string& path) const;

  // The plot area, in pixels.
  static constexpr double kLeft = 90, kTop = 50, kBottom = 70, kLegendWidth = 230;

 private:
  ChartSpec spec_;
  int x_lo_ = -3, x_hi_ = 0, y_lo_ = -3, y_hi_ = 0;
};

// Frees the font caches cairo and fontconfig keep for the life of the process
// (they are not leaks, but leak checkers cannot tell). Call when no chart is
// being drawn and none will be soon, e.g. when a command is done: the next
// chart loads them again. Not while any other cairo object is alive.
void release_chart_caches();

}  // namespace neurocloth
