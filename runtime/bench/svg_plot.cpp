#include "runtime/bench/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace nano::bench {
namespace {

constexpr double kWidth = 800, kHeight = 500, kLeft = 80, kRight = 200, kTop = 40, kBottom = 60;
const char* const kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};

std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

std::string number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", v);
  return buffer;
}

// One axis: maps data to [0, 1] linearly or logarithmically, with "nice" tick values.
struct Axis {
  double lo = 0, hi = 1;
  bool log = false;
  double to_unit(double v) const {
    return log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo)) : (v - lo) / (hi - lo);
  }
  std::vector<double> ticks() const {
    std::vector<double> t;
    if (log) {
      for (double d = std::pow(10.0, std::floor(std::log10(lo))); d <= hi * 1.0001; d *= 10)
        for (double m : {1.0, 2.0, 5.0})
          if (d * m >= lo * 0.9999 && d * m <= hi * 1.0001) t.push_back(d * m);
      return t;
    }
    const double raw = (hi - lo) / 6;
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    const double step = raw / mag < 2 ? 2 * mag : raw / mag < 5 ? 5 * mag : 10 * mag;
    for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 * step; v += step) t.push_back(std::abs(v) < 1e-12 * step ? 0 : v);
    return t;
  }
};

Axis make_axis(double lo, double hi, bool log) {
  Axis a;
  a.log = log;
  if (log) {
    a.lo = lo / 1.3, a.hi = hi * 1.3;
  } else {
    const double pad = hi > lo ? 0.08 * (hi - lo) : std::max(1.0, std::abs(hi)) * 0.5;
    a.lo = lo - pad, a.hi = hi + pad;
    if (lo >= 0 && a.lo < 0) a.lo = 0;  // counts and percentages start at zero
  }
  return a;
}

}  // namespace

std::string svg_plot(const PlotSpec& spec, const InputSource& source) {
  const auto drawable = [&](const PlotPoint& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && (!spec.log_x || p.x > 0) && (!spec.log_y || p.y > 0);
  };
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  std::size_t left_out = 0;
  for (const PlotSeries& s : spec.series)
    for (const PlotPoint& p : s.points) {
      if (!drawable(p)) {
        ++left_out;
        continue;
      }
      x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
    }
  if (!(x0 <= x1)) source.fail("svg_plot: no point to draw in '" + spec.title + "'");
  const Axis ax = make_axis(x0, x1, spec.log_x), ay = make_axis(y0, y1, spec.log_y);
  const double pw = kWidth - kLeft - kRight, ph = kHeight - kTop - kBottom;
  const auto px = [&](double x) { return kLeft + pw * ax.to_unit(x); };
  const auto py = [&](double y) { return kTop + ph * (1 - ay.to_unit(y)); };

  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"800\" height=\"500\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg += "<rect width=\"800\" height=\"500\" fill=\"white\"/>\n";
  svg += "<text x=\"" + number(kLeft) + "\" y=\"24\" font-size=\"15\">" + escape(spec.title) + "</text>\n";
  for (double t : ax.ticks()) {
    const std::string x = number(px(t));
    svg += "<line x1=\"" + x + "\" y1=\"" + number(kTop) + "\" x2=\"" + x + "\" y2=\"" + number(kTop + ph) + "\" stroke=\"#ddd\"/>\n";
    svg += "<text x=\"" + x + "\" y=\"" + number(kTop + ph + 16) + "\" text-anchor=\"middle\">" + number(t) + "</text>\n";
  }
  for (double t : ay.ticks()) {
    const std::string y = number(py(t));
    svg += "<line x1=\"" + number(kLeft) + "\" y1=\"" + y + "\" x2=\"" + number(kLeft + pw) + "\" y2=\"" + y + "\" stroke=\"#ddd\"/>\n";
    svg += "<text x=\"" + number(kLeft - 6) + "\" y=\"" + y + "\" text-anchor=\"end\" dy=\"4\">" + number(t) + "</text>\n";
  }
  svg += "<rect x=\"" + number(kLeft) + "\" y=\"" + number(kTop) + "\" width=\"" + number(pw) + "\" height=\"" + number(ph) +
         "\" fill=\"none\" stroke=\"black\"/>\n";
  svg += "<text x=\"" + number(kLeft + pw / 2) + "\" y=\"" + number(kHeight - 18) + "\" text-anchor=\"middle\">" +
         escape(spec.x_label) + (spec.log_x ? " (log)" : "") + "</text>\n";
  svg += "<text transform=\"translate(18," + number(kTop + ph / 2) + ") rotate(-90)\" text-anchor=\"middle\">" +
         escape(spec.y_label) + (spec.log_y ? " (log)" : "") + "</text>\n";
  for (std::size_t k = 0; k < spec.series.size(); ++k) {
    const PlotSeries& s = spec.series[k];
    const std::string colour = kColours[k % std::size(kColours)];
    if (s.lines) {
      std::string points;
      for (const PlotPoint& p : s.points)
        if (drawable(p)) points += number(px(p.x)) + "," + number(py(p.y)) + " ";
      svg += "<polyline points=\"" + points + "\" fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"1.5\"/>\n";
    }
    for (const PlotPoint& p : s.points) {
      if (!drawable(p)) continue;
      svg += "<circle cx=\"" + number(px(p.x)) + "\" cy=\"" + number(py(p.y)) + "\" r=\"4\" fill=\"" + colour + "\"/>\n";
      if (!p.label.empty())
        svg += "<text x=\"" + number(px(p.x) + 6) + "\" y=\"" + number(py(p.y) - 6) + "\" font-size=\"10\">" + escape(p.label) + "</text>\n";
    }
    const double ly = kTop + 16 + 18 * double(k);
    svg += "<circle cx=\"" + number(kWidth - kRight + 20) + "\" cy=\"" + number(ly - 4) + "\" r=\"4\" fill=\"" + colour + "\"/>\n";
    svg += "<text x=\"" + number(kWidth - kRight + 30) + "\" y=\"" + number(ly) + "\">" + escape(s.name) + "</text>\n";
  }
  if (left_out != 0)
    svg += "<text x=\"" + number(kLeft) + "\" y=\"" + number(kHeight - 4) + "\" font-size=\"10\">" + std::to_string(left_out) +
           " point(s) not drawable on these axes (zero or negative on a log axis) are left out</text>\n";
  svg += "</svg>\n";
  return svg;
}

}  // namespace nano::bench
