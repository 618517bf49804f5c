// The log-log chart: drawn into a PNG without a window, read back with cairo
// and checked pixel by pixel where the data should be.
#include <cairo.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <memory>
#include <set>

#include "chart/trade_chart.h"
#include "support/release_chart_caches.h"
#include "support/scratch_dir.h"
#include "tradeoff/pareto_front.h"

namespace neurocloth {
namespace {
namespace fs = std::filesystem;

// A PNG read back: 8-bit channels.
class Picture {
 public:
  explicit Picture(const std::string& path)
      : surface_(cairo_image_surface_create_from_png(path.c_str()), cairo_surface_destroy) {}
  bool ok() const { return cairo_surface_status(surface_.get()) == CAIRO_STATUS_SUCCESS; }
  int width() const { return cairo_image_surface_get_width(surface_.get()); }
  int height() const { return cairo_image_surface_get_height(surface_.get()); }
  // {r, g, b} of pixel (x, y), 0..255.
  std::array<int, 3> at(int x, int y) const {
    const unsigned char* row = cairo_image_surface_get_data(surface_.get()) +
                               y * cairo_image_surface_get_stride(surface_.get());
    const std::uint32_t p = reinterpret_cast<const std::uint32_t*>(row)[x];
    return {static_cast<int>((p >> 16) & 0xff), static_cast<int>((p >> 8) & 0xff),
            static_cast<int>(p & 0xff)};
  }
  // True when some pixel within `radius` of (x, y) is within `tolerance` of `c` in every channel.
  bool near(double x, double y, const Rgb& c, int radius, int tolerance) const {
    for (int dy = -radius; dy <= radius; ++dy)
      for (int dx = -radius; dx <= radius; ++dx) {
        const int px = static_cast<int>(x) + dx, py = static_cast<int>(y) + dy;
        if (px < 0 || py < 0 || px >= width() || py >= height()) continue;
        const auto v = at(px, py);
        if (std::abs(v[0] - static_cast<int>(std::lround(c.r * 255))) <= tolerance &&
            std::abs(v[1] - static_cast<int>(std::lround(c.g * 255))) <= tolerance &&
            std::abs(v[2] - static_cast<int>(std::lround(c.b * 255))) <= tolerance)
          return true;
      }
    return false;
  }

 private:
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface_;
};

const Rgb kBlue{0.12, 0.47, 0.71}, kRed{0.84, 0.15, 0.16}, kBlack{0, 0, 0}, kWhite{1, 1, 1};

ChartSpec two_lines() {
  ChartSpec spec;
  spec.title = "two lines";
  spec.x_label = "cost";
  spec.y_label = "error";
  spec.width = 800;
  spec.height = 500;
  spec.series = {{"blue", kBlue, {{0.003, 0.2}, {0.03, 0.02}, {0.3, 0.002, true}}},
                 {"red", kRed, {{0.01, 0.5, true}, {0.1, 1e-5, true}}}};
  spec.ring_legend = "Pareto front";
  return spec;
}

TEST(LogLogChart, AxesSpanWholeDecadesAroundThePoints) {
  const LogLogChart chart(two_lines());
  EXPECT_EQ(chart.x_lo(), -3);
  EXPECT_EQ(chart.x_hi(), 0);
  EXPECT_EQ(chart.y_lo(), -6);  // 1e-5 / 1.3 falls below 1e-5
  EXPECT_EQ(chart.y_hi(), 0);
  // Decades are evenly spaced: log-log.
  const auto a = chart.to_pixel(0.001, 1e-6), b = chart.to_pixel(0.01, 1e-5),
             c = chart.to_pixel(0.1, 1e-4);
  EXPECT_NEAR(b.first - a.first, c.first - b.first, 1e-9);
  EXPECT_NEAR(a.second - b.second, b.second - c.second, 1e-9);
  EXPECT_GT(b.first, a.first);
  EXPECT_LT(b.second, a.second);  // larger errors higher up
}

TEST(LogLogChart, WritesAPngOfItsSizeWithEachLineWhereItsDataIs) {
  const std::string path = test::scratch_path("two_lines.png");
  fs::remove(path);
  const LogLogChart chart(two_lines());
  chart.write_png(path);
  const Picture pic(path);
  ASSERT_TRUE(pic.ok());
  EXPECT_EQ(pic.width(), 800);
  EXPECT_EQ(pic.height(), 500);

  for (const ChartSeries& s : chart.spec().series) {
    SCOPED_TRACE(s.name);
    for (const ChartPoint& p : s.points) {
      const auto [x, y] = chart.to_pixel(p.x, p.y);
      // The marker's centre is the series' colour exactly (8-bit rounding aside).
      EXPECT_TRUE(pic.near(x, y, s.colour, 0, 1)) << p.x << ", " << p.y;
      // A ring of black around the Pareto points, none around the others.
      EXPECT_EQ(pic.near(x + 8.5, y, kBlack, 1, 40), p.ringed) << p.x << ", " << p.y;
    }
    // The line between two markers: its colour half-way along.
    const auto [x0, y0] = chart.to_pixel(s.points[0].x, s.points[0].y);
    const auto [x1, y1] = chart.to_pixel(s.points[1].x, s.points[1].y);
    EXPECT_TRUE(pic.near((x0 + x1) / 2, (y0 + y1) / 2, s.colour, 1, 2));
  }
  // No colour where no line passes: the blue line stays off the red point's spot.
  const auto [rx, ry] = chart.to_pixel(0.1, 1e-5);
  EXPECT_FALSE(pic.near(rx, ry, kBlue, 3, 10));
  // Not blank: white background, black frame, text, several colours.
  EXPECT_TRUE(pic.near(2, 2, kWhite, 0, 0));
  EXPECT_TRUE(pic.near(LogLogChart::kLeft, 200, kBlack, 1, 140));  // 1 px, antialiased
  std::set<std::array<int, 3>> colours;
  for (int y = 0; y < pic.height(); y += 3)
    for (int x = 0; x < pic.width(); x += 3)
      colours.insert(pic.at(x, y));
  EXPECT_GT(colours.size(), 20u);
  // The title is drawn above the plot, centred.
  bool title_ink = false;
  for (int x = 300; x < 400 && !title_ink; ++x)
    for (int y = 15; y < 40 && !title_ink; ++y)
      title_ink = pic.at(x, y)[0] < 100;
  EXPECT_TRUE(title_ink);
}

TEST(LogLogChart, LeavesOutWhatALogScaleCannotShow) {
  ChartSpec spec = two_lines();
  spec.series[0].points.push_back({0.05, 0.0});
  spec.series[0].points.push_back({std::numeric_limits<double>::quiet_NaN(), 0.1});
  spec.series[0].points.push_back({-1, 0.1});
  const LogLogChart chart(spec);
  EXPECT_EQ(chart.y_lo(), -6);  // the zero did not drag the axis to -infinity
  const std::string path = test::scratch_path("with_zeros.png");
  chart.write_png(path);
  EXPECT_TRUE(Picture(path).ok());
}

TEST(LogLogChart, AnUnwritablePathIsAnErrorNamingIt) {
  const LogLogChart chart(two_lines());
  try {
    chart.write_png("/no/such/folder/chart.png");
    FAIL() << "wrote into a folder that does not exist";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/no/such/folder/chart.png"), std::string::npos);
  }
}

TradeRow row(const std::string& method, double cost, double error, const char* status = "ok") {
  TradeRow r;
  r.method = method;
  r.parameter = "dt";
  r.value = r.dt = 0.001;
  r.wall_per_simulated_second = cost;
  r.position_error_max = error;
  r.status = status;
  return r;
}

TEST(TradeChart, OneColouredLinePerMethodWithTheParetoFrontRinged) {
  TradeTable t;
  t.scene = "hand";
  t.seconds = 2;
  t.reference.change = 1e-4;  // not met: drawn as a rule
  t.rows = {row("network", 0.2, 0.05), row("network", 0.1, 0.1), row("rk4", 0.3, 0.001),
            row("rk4", 0.6, 0.002),
            row("explicit_euler", 0.1, std::numeric_limits<double>::quiet_NaN(), "diverged")};
  const ChartSpec spec = trade_chart_spec(t, Metric::node_max);
  ASSERT_EQ(spec.series.size(), 3u);
  EXPECT_EQ(spec.series[0].name, "network");
  EXPECT_EQ(spec.series[1].name, "rk4");
  EXPECT_EQ(spec.series[2].name, "explicit_euler (none finished)");
  EXPECT_TRUE(spec.series[2].points.empty());
  // Sorted by cost, and ringed exactly where pareto_front says.
  EXPECT_EQ(spec.series[0].points[0].x, 0.1);
  EXPECT_TRUE(spec.series[0].points[0].ringed);
  EXPECT_TRUE(spec.series[0].points[1].ringed);
  EXPECT_TRUE(spec.series[1].points[0].ringed);
  EXPECT_FALSE(spec.series[1].points[1].ringed);
  EXPECT_EQ(pareto_front(t.rows, Metric::node_max).size(), 3u);
  ASSERT_EQ(spec.rules.size(), 1u);
  EXPECT_EQ(spec.rules[0].y, 1e-4);
  EXPECT_NE(spec.title.find("hand"), std::string::npos);
  // Every method has its own colour.
  const char* methods[] = {"network", "explicit_euler", "verlet",
                           "rk4",     "implicit_euler", "adaptive"};
  std::set<std::array<double, 3>> colours;
  for (const char* m : methods) {
    const Rgb c = method_colour(m);
    colours.insert({c.r, c.g, c.b});
  }
  EXPECT_EQ(colours.size(), 6u);

  const std::string path = test::scratch_path("trade.png");
  write_trade_chart(t, Metric::node_max, path);
  const Picture pic(path);
  ASSERT_TRUE(pic.ok());
  const LogLogChart chart(spec);
  const auto [x, y] = chart.to_pixel(0.3, 0.001);
  EXPECT_TRUE(pic.near(x, y, method_colour("rk4"), 0, 1));
}

// Projective's iterations counts are lines of their own, named and shaded by the count.
TEST(TradeChart, ProjectiveHasALinePerIterationsCount) {
  TradeTable t;
  t.scene = "hand";
  t.seconds = 2;
  t.reference.change = 1e-9;
  t.reference.met = true;
  t.rows = {row("projective", 0.1, 0.3), row("projective", 0.3, 0.2), row("projective", 0.2, 0.25),
            row("projective", 0.6, 0.1)};
  const int iterations[] = {1, 4, 1, 4};
  for (std::size_t i = 0; i < t.rows.size(); ++i)
    t.rows[i].iterations = iterations[i];
  const ChartSpec spec = trade_chart_spec(t, Metric::node_max);
  ASSERT_EQ(spec.series.size(), 2u);
  EXPECT_EQ(spec.series[0].name, "projective 1 it.");
  EXPECT_EQ(spec.series[1].name, "projective 4 it.");
  ASSERT_EQ(spec.series[0].points.size(), 2u);
  EXPECT_EQ(spec.series[0].points[1].x, 0.2);
  const Rgb one = spec.series[0].colour, four = spec.series[1].colour;
  EXPECT_LT(one.g, four.g) << "fewer iterations, darker";
  const Rgb cyan = method_colour("projective");
  EXPECT_LE(four.g, cyan.g);
}

// The implicit step's tolerances too, shaded darker the looser the solve.
TEST(TradeChart, ImplicitHasALinePerTolerance) {
  TradeTable t;
  t.scene = "hand";
  t.seconds = 2;
  t.reference.change = 1e-9;
  t.reference.met = true;
  t.rows = {row("implicit_euler", 0.3, 0.2), row("implicit_euler", 0.1, 0.21),
            row("implicit_euler", 0.6, 0.1), row("implicit_euler", 0.2, 0.11)};
  const double tolerances[] = {1e-10, 1e-3, 1e-10, 1e-3};
  for (std::size_t i = 0; i < t.rows.size(); ++i)
    t.rows[i].linear_tolerance = tolerances[i];
  const ChartSpec spec = trade_chart_spec(t, Metric::node_max);
  ASSERT_EQ(spec.series.size(), 2u);
  EXPECT_EQ(spec.series[0].name, "implicit_euler tol 1e-10");
  EXPECT_EQ(spec.series[1].name, "implicit_euler tol 0.001");
  ASSERT_EQ(spec.series[1].points.size(), 2u);
  const Rgb tight = spec.series[0].colour, loose = spec.series[1].colour;
  EXPECT_EQ(tight.b, method_colour("implicit_euler").b) << "the scene default at full strength";
  EXPECT_LT(loose.b, tight.b) << "looser, darker";
}

}  // namespace
}  // namespace neurocloth
