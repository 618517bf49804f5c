#include "chart/loglog_chart.h"

#include <cairo.h>
#include <fontconfig/fontconfig.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <ostream>
#include <stdexcept>

#include "core/base/vec3.h"
#include "core/io/text_file.h"

namespace neurocloth {
namespace {

bool plottable(double x, double y) {
  return x > 0 && y > 0 && std::isfinite(x) && std::isfinite(y);
}

// Whole decades around [lo, hi] (both > 0) with a margin, so that no marker
// sits on the frame; at least one decade wide.
std::pair<int, int> decades(double lo, double hi) {
  int a = static_cast<int>(std::floor(std::log10(lo / 1.3)));
  int b = static_cast<int>(std::ceil(std::log10(hi * 1.3)));
  if (b <= a) b = a + 1;
  return {a, b};
}

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using Context = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

void colour(cairo_t* cr, const Rgb& c) {
  cairo_set_source_rgb(cr, c.r, c.g, c.b);
}

// "10" with the exponent raised and smaller, right-aligned (align 1) or centred (0.5) at x.
void power_of_ten(cairo_t* cr, int exponent, double x, double y, double align) {
  const std::string base = "10", exp = std::to_string(exponent);
  cairo_set_font_size(cr, 13);
  cairo_text_extents_t b;
  cairo_text_extents(cr, base.c_str(), &b);
  cairo_set_font_size(cr, 10);
  cairo_text_extents_t e;
  cairo_text_extents(cr, exp.c_str(), &e);
  const double width = b.x_advance + e.x_advance;
  const double x0 = x - align * width;
  cairo_set_font_size(cr, 13);
  cairo_move_to(cr, x0, y);
  cairo_show_text(cr, base.c_str());
  cairo_set_font_size(cr, 10);
  cairo_move_to(cr, x0 + b.x_advance, y - 6);
  cairo_show_text(cr, exp.c_str());
}

void centred_text(cairo_t* cr, const std::string& s, double x, double y) {
  cairo_text_extents_t t;
  cairo_text_extents(cr, s.c_str(), &t);
  cairo_move_to(cr, x - t.x_advance / 2, y);
  cairo_show_text(cr, s.c_str());
}

// cairo's PNG encoder hands its bytes here as it makes them.
cairo_status_t append_to_stream(void* closure, const unsigned char* data, unsigned int length) {
  auto& out = *static_cast<std::ostream*>(closure);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(length));
  return out ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

}  // namespace

LogLogChart::LogLogChart(ChartSpec spec) : spec_(std::move(spec)) {
  double xmin = std::numeric_limits<double>::infinity(), xmax = 0;
  double ymin = xmin, ymax = 0;
  for (const ChartSeries& s : spec_.series)
    for (const ChartPoint& p : s.points)
      if (plottable(p.x, p.y)) {
        xmin = std::min(xmin, p.x);
        xmax = std::max(xmax, p.x);
        ymin = std::min(ymin, p.y);
        ymax = std::max(ymax, p.y);
      }
  for (const ChartRule& r : spec_.rules)
    if (plottable(1, r.y)) {
      ymin = std::min(ymin, r.y);
      ymax = std::max(ymax, r.y);
    }
  for (const ChartBand& b : spec_.bands)
    if (plottable(1, b.lo) && plottable(1, b.hi)) {
      ymin = std::min(ymin, b.lo);
      ymax = std::max(ymax, b.hi);
    }
  if (xmax > 0) std::tie(x_lo_, x_hi_) = decades(xmin, xmax);
  if (ymax > 0) std::tie(y_lo_, y_hi_) = decades(ymin, ymax);
}

std::pair<double, double> LogLogChart::to_pixel(double x, double y) const {
  const double right = spec_.width - kLegendWidth, bottom = spec_.height - kBottom;
  const double u = (std::log10(x) - x_lo_) / (x_hi_ - x_lo_);
  const double v = (std::log10(y) - y_lo_) / (y_hi_ - y_lo_);
  return {kLeft + u * (right - kLeft), bottom - v * (bottom - kTop)};
}

void LogLogChart::write_png(const std::string& path) const {
  write_file_atomically(path, [&](std::ostream& out) { write_png(out, path); });
}

void LogLogChart::write_png(std::ostream& out, const std::string& path) const {
  if (spec_.width < kLeft + kLegendWidth + 100 || spec_.height < kTop + kBottom + 100)
    throw std::runtime_error(path + ": the chart is too small to draw");
  Surface surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, spec_.width, spec_.height),
                  cairo_surface_destroy);
  Context owner(cairo_create(surface.get()), cairo_destroy);
  cairo_t* cr = owner.get();
  const double right = spec_.width - kLegendWidth, bottom = spec_.height - kBottom;
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);

  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);

  // Grid: a line at every decade, short ticks at 2..9 times each, labels at
  // the decades. One axis at a time: `along` is a pixel on the axis, `across`
  // one perpendicular to it.
  cairo_set_line_width(cr, 1);
  auto draw_axis = [&](bool x_axis) {
    const int lo = x_axis ? x_lo_ : y_lo_, hi = x_axis ? x_hi_ : y_hi_;
    auto pixel_of = [&](double v) {
      return x_axis ? to_pixel(v, std::pow(10.0, y_lo_)).first
                    : to_pixel(std::pow(10.0, x_lo_), v).second;
    };
    auto line = [&](double along, double across0, double across1) {
      if (x_axis) {
        cairo_move_to(cr, along, across0);
        cairo_line_to(cr, along, across1);
      } else {
        cairo_move_to(cr, across0, along);
        cairo_line_to(cr, across1, along);
      }
      cairo_stroke(cr);
    };
    // The axis line's side, and the way its ticks point (into the plot).
    const double base = x_axis ? bottom : kLeft, tick = x_axis ? -4 : 4;
    for (int k = lo; k <= hi; ++k) {
      const double p = pixel_of(std::pow(10.0, k));
      cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
      line(p, x_axis ? kTop : kLeft, x_axis ? bottom : right);
      cairo_set_source_rgb(cr, 0, 0, 0);
      if (x_axis)
        power_of_ten(cr, k, p, bottom + 22, 0.5);
      else
        power_of_ten(cr, k, kLeft - 8, p + 5, 1);
      for (int m = 2; m <= 9 && k < hi; ++m)
        line(pixel_of(m * std::pow(10.0, k)), base, base + tick);
    }
  };
  draw_axis(true);
  draw_axis(false);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_rectangle(cr, kLeft, kTop, right - kLeft, bottom - kTop);
  cairo_stroke(cr);

  // Everything in data space stays inside the plot area.
  cairo_save(cr);
  cairo_rectangle(cr, kLeft, kTop, right - kLeft, bottom - kTop);
  cairo_clip(cr);
  for (const ChartBand& b : spec_.bands) {
    if (!plottable(1, b.lo) || !plottable(1, b.hi)) continue;
    const double top = to_pixel(std::pow(10.0, x_lo_), b.hi).second;
    const double low = to_pixel(std::pow(10.0, x_lo_), b.lo).second;
    cairo_set_source_rgb(cr, 0.86, 0.90, 0.97);
    cairo_rectangle(cr, kLeft, top, right - kLeft, std::max(low - top, 1.0));
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0.30, 0.38, 0.55);
    cairo_set_font_size(cr, 11);
    cairo_move_to(cr, right - 8 - 7 * static_cast<double>(b.label.size()), low - 4);
    cairo_show_text(cr, b.label.c_str());
  }
  const double dash[] = {6, 4};
  for (const ChartRule& r : spec_.rules) {
    if (!plottable(1, r.y)) continue;
    const double py = to_pixel(std::pow(10.0, x_lo_), r.y).second;
    cairo_set_source_rgb(cr, 0.45, 0.45, 0.45);
    cairo_set_dash(cr, dash, 2, 0);
    cairo_move_to(cr, kLeft, py);
    cairo_line_to(cr, right, py);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
    cairo_set_font_size(cr, 11);
    cairo_move_to(cr, kLeft + 6, py - 4);
    cairo_show_text(cr, r.label.c_str());
  }
  // The ringed points' line goes under the series, so markers keep their colour.
  std::vector<std::pair<double, double>> ringed;
  for (const ChartSeries& s : spec_.series)
    for (const ChartPoint& p : s.points)
      if (p.ringed && plottable(p.x, p.y)) ringed.push_back(to_pixel(p.x, p.y));
  std::sort(ringed.begin(), ringed.end());
  if (!spec_.ring_legend.empty() && ringed.size() > 1) {
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.5);
    cairo_set_dash(cr, dash, 2, 0);
    for (std::size_t i = 0; i < ringed.size(); ++i)
      (i ? cairo_line_to : cairo_move_to)(cr, ringed[i].first, ringed[i].second);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
  }
  for (const ChartSeries& s : spec_.series) {
    colour(cr, s.colour);
    cairo_set_line_width(cr, 2);
    bool drawing = false;
    for (const ChartPoint& p : s.points) {
      if (!plottable(p.x, p.y)) continue;
      const auto [px, py] = to_pixel(p.x, p.y);
      (drawing ? cairo_line_to : cairo_move_to)(cr, px, py);
      drawing = true;
    }
    cairo_stroke(cr);
    for (const ChartPoint& p : s.points) {
      if (!plottable(p.x, p.y)) continue;
      const auto [px, py] = to_pixel(p.x, p.y);
      cairo_arc(cr, px, py, 4.5, 0, 2 * kPi);
      cairo_fill(cr);
    }
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 2);
  for (const auto& [px, py] : ringed) {
    cairo_new_sub_path(cr);
    cairo_arc(cr, px, py, 8.5, 0, 2 * kPi);
  }
  cairo_stroke(cr);
  cairo_restore(cr);

  // Title and axis labels.
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
  cairo_set_font_size(cr, 16);
  centred_text(cr, spec_.title, (kLeft + right) / 2, kTop - 18);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 13);
  centred_text(cr, spec_.x_label, (kLeft + right) / 2, spec_.height - 18);
  cairo_save(cr);
  cairo_translate(cr, 22, (kTop + bottom) / 2);
  cairo_rotate(cr, -kPi / 2);
  centred_text(cr, spec_.y_label, 0, 0);
  cairo_restore(cr);

  // Legend, right of the plot.
  double ly = kTop + 12;
  const double lx = right + 20;
  cairo_set_font_size(cr, 13);
  for (const ChartSeries& s : spec_.series) {
    colour(cr, s.colour);
    cairo_set_line_width(cr, 2);
    cairo_new_path(cr);
    cairo_move_to(cr, lx, ly);
    cairo_line_to(cr, lx + 28, ly);
    cairo_stroke(cr);
    cairo_arc(cr, lx + 14, ly, 4.5, 0, 2 * kPi);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_move_to(cr, lx + 38, ly + 5);
    cairo_show_text(cr, s.name.c_str());
    ly += 24;
  }
  if (!spec_.ring_legend.empty()) {
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 2);
    cairo_new_path(cr);  // the text left a current point; the ring must not join it
    cairo_arc(cr, lx + 14, ly, 8.5, 0, 2 * kPi);
    cairo_stroke(cr);
    cairo_move_to(cr, lx + 38, ly + 5);
    cairo_show_text(cr, spec_.ring_legend.c_str());
  }

  cairo_surface_flush(surface.get());
  if (cairo_status(cr) != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(
        path + ": cannot draw the chart: " + cairo_status_to_string(cairo_status(cr)));
  const cairo_status_t written =
      cairo_surface_write_to_png_stream(surface.get(), append_to_stream, &out);
  if (written != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(path + ": cannot write the chart: " + cairo_status_to_string(written));
}

void release_chart_caches() {
  cairo_debug_reset_static_data();
  FcFini();
}

}  // namespace neurocloth
