// Small SVG charts for reports (rangefill bench): scatter panels on log axes and stacked bars.
// Plain text out, no dependency.
#pragma once

#include <string>
#include <vector>

namespace rangefill::cli {

/// One panel of scatter points.
struct ScatterPanel {
  std::string title;
  std::vector<double> x, y;
};

/// The panels side by side (three to a row) on the same logarithmic axes, which span the positive
/// values of all panels, four decades at most; a value below them (or not positive) is drawn on the
/// lower edge.
std::string scatter_panels_svg(const std::vector<ScatterPanel>& panels, const std::string& x_label,
                               const std::string& y_label);

/// One panel of stacked bars: per category, segments that add up to at most 1.
struct BarPanel {
  std::string title;
  std::vector<std::string> categories;
  std::vector<std::vector<double>> segments;  // [category][segment], shares in [0, 1]
};

/// The panels side by side (two to a row), the segments coloured in order with a legend of
/// `segment_names`, the y axis from 0 to 100 %.
std::string stacked_bars_svg(const std::vector<BarPanel>& panels,
                             const std::vector<std::string>& segment_names);

/// `text` with &, <, > and " escaped for XML and HTML.
std::string escape_xml(const std::string& text);

}  // namespace rangefill::cli
