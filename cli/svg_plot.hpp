#pragma once

#include <string>
#include <string_view>
#include <vector>

// Scatter plots for the reports, written as SVG with nothing but the
// standard library. The same input gives the same bytes: numbers are
// formatted without the locale, at a fixed precision.
namespace batchccd::cli {

struct PlotPoint {
  std::string label;  // shown beside the marker; also picks its colour and shape
  double x = 0;
  double y = 0;
};

struct PlotPanel {
  std::string title;    // e.g. "wrong decisions (false negatives + false positives)"
  std::string x_label;  // e.g. "run time [s]"
  std::string y_label;  // e.g. "count"
  std::vector<PlotPoint> points;
};

// An SVG document: the title above the panels, laid side by side. Each panel
// is a scatter plot with logarithmic axes and decade ticks; each point a
// marker with its label beside it, moved up or down a line when it would
// cover another label or marker. A label has the same colour and marker
// shape in every panel. Values of 0 go on a separate "0" row (or column)
// past a break in the axis; NaN, infinite and negative values cannot be
// placed, so such points are left out and listed in a note under the panel.
std::string scatter_svg(std::string_view title, const std::vector<PlotPanel>& panels);

}  // namespace batchccd::cli
