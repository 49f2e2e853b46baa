#pragma once
// A small self-contained SVG scatter/line plot for the bench reports (docs/bench/): no plotting
// library on the machine, and a text format diffs well in the repository.
#include <string>
#include <vector>

#include "common/error.hpp"

namespace nano::bench {

struct PlotPoint {
  double x = 0, y = 0;
  std::string label;  // drawn beside the point when not empty
};

struct PlotSeries {
  std::string name;
  std::vector<PlotPoint> points;
  bool lines = false;  // join the points in order
};

struct PlotSpec {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;  // log axes need positive values; others are left out and counted
  std::vector<PlotSeries> series;
};

// The SVG document (800 × 500). Throws an InputError against `source` (where the points came from)
// when no point can be drawn.
std::string svg_plot(const PlotSpec& spec, const InputSource& source);

}  // namespace nano::bench
