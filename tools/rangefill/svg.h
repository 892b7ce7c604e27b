// Small SVG charts for reports (rangefill bench): scatter plots on log axes and stacked bars.
// Plain text out, no dependency.
#pragma once

#include <string>
#include <vector>

namespace rangefill::cli {

/// One series of scatter points.
struct ScatterSeries {
  std::string name;
  std::vector<double> x, y;
};

/// The series overlaid on one plot, each in its colour and marker with a legend, on logarithmic
/// axes that span the positive values of all of them, four decades at most; a value below them
/// (or not positive) is drawn on the lower edge.
std::string scatter_svg(const std::vector<ScatterSeries>& series, const std::string& x_label,
                        const std::string& y_label);

/// One panel of stacked bars: per category, segments that add up to at most 1.
struct BarPanel {
  std::string title;
  std::vector<std::string> categories;
  std::vector<std::vector<double>> segments;  // [category][segment], shares in [0, 1]
};

/// The panels side by side (two to a row), the segments coloured in order with a legend of
/// `segment_names`, the categories along `x_label`, the y axis from 0 to 100 %.
std::string stacked_bars_svg(const std::vector<BarPanel>& panels,
                             const std::vector<std::string>& segment_names,
                             const std::string& x_label);

/// `text` with &, <, > and " escaped for XML and HTML.
std::string escape_xml(const std::string& text);

}  // namespace rangefill::cli
