#include "svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace rangefill::cli {

namespace {

const char* const kColors[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                               "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
constexpr int kColorCount = sizeof kColors / sizeof kColors[0];

// Panel layout: the plot area of each panel and the margins round it.
constexpr double kPanelWidth = 300, kPanelHeight = 230;
constexpr double kLeft = 52, kRight = 12, kTop = 24, kBottom = 40;
constexpr double kPlotWidth = kPanelWidth - kLeft - kRight,
                 kPlotHeight = kPanelHeight - kTop - kBottom;

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

void text(std::ostringstream& svg, double x, double y, const std::string& content,
          const char* anchor = "middle", const char* extra = "") {
  svg << "<text x=\"" << number(x) << "\" y=\"" << number(y) << "\" text-anchor=\"" << anchor
      << "\"" << extra << ">" << escape_xml(content) << "</text>\n";
}

void line(std::ostringstream& svg, double x1, double y1, double x2, double y2,
          const char* stroke = "#000", double width = 1) {
  svg << "<line x1=\"" << number(x1) << "\" y1=\"" << number(y1) << "\" x2=\"" << number(x2)
      << "\" y2=\"" << number(y2) << "\" stroke=\"" << stroke << "\" stroke-width=\""
      << number(width) << "\"/>\n";
}

// Opens an SVG of `panels` panels, `columns` to a row, with `header` pixels above them.
void open(std::ostringstream& svg, size_t panels, size_t columns, double header) {
  const size_t rows = std::max<size_t>(1, (panels + columns - 1) / columns);
  const double width = kPanelWidth * std::min(std::max<size_t>(panels, 1), columns);
  const double height = header + kPanelHeight * rows;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << number(width) << "\" height=\""
      << number(height) << "\" viewBox=\"0 0 " << number(width) << " " << number(height)
      << "\" font-family=\"sans-serif\" font-size=\"11\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
}

// Frame, title and axis labels of panel `index`; returns its plot area's top-left corner.
std::pair<double, double> panel(std::ostringstream& svg, size_t index, size_t columns,
                                double header, const std::string& title, const std::string& x_label,
                                const std::string& y_label) {
  const double x0 = kPanelWidth * (index % columns) + kLeft;
  const double y0 = header + kPanelHeight * (index / columns) + kTop;
  svg << "<rect x=\"" << number(x0) << "\" y=\"" << number(y0) << "\" width=\""
      << number(kPlotWidth) << "\" height=\"" << number(kPlotHeight)
      << "\" fill=\"none\" stroke=\"#000\"/>\n";
  text(svg, x0 + kPlotWidth / 2, y0 - 8, title, "middle", " font-weight=\"bold\"");
  text(svg, x0 + kPlotWidth / 2, y0 + kPlotHeight + 32, x_label);
  const double ly = y0 + kPlotHeight / 2, lx = x0 - 40;
  text(svg, lx, ly, y_label, "middle",
       (" transform=\"rotate(-90 " + number(lx) + " " + number(ly) + ")\"").c_str());
  return {x0, y0};
}

// Decades spanning the positive values, at least one and at most four (smaller values go on the
// lower edge).
std::pair<int, int> decades(const std::vector<double>& values) {
  double low = HUGE_VAL, high = 0;
  for (double v : values) {
    if (v > 0) low = std::min(low, v), high = std::max(high, v);
  }
  if (!(high > 0)) return {0, 1};
  const int from = static_cast<int>(std::floor(std::log10(low)));
  const int to = static_cast<int>(std::ceil(std::log10(high)));
  return {std::max(from, to - 4), std::max(to, from + 1)};
}

// Position in [0, 1] of `value` on the decades; at or below 0: 0.
double on_log_axis(double value, std::pair<int, int> range) {
  if (!(value > 0)) return 0;
  return std::clamp((std::log10(value) - range.first) / (range.second - range.first), 0.0, 1.0);
}

}  // namespace

std::string escape_xml(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    switch (c) {
      case '&':
        escaped += "&amp;";
        break;
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '"':
        escaped += "&quot;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

std::string scatter_svg(const std::vector<ScatterSeries>& series, const std::string& x_label,
                        const std::string& y_label) {
  std::vector<double> xs, ys;
  for (const ScatterSeries& one : series) {
    xs.insert(xs.end(), one.x.begin(), one.x.end());
    ys.insert(ys.end(), one.y.begin(), one.y.end());
  }
  const auto x_range = decades(xs), y_range = decades(ys);
  constexpr double kWidth = 640, kHeight = 420, kX0 = 60, kY0 = 20, kLegend = 150;
  constexpr double kPlotW = kWidth - kX0 - kLegend, kPlotH = kHeight - kY0 - 50;
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << number(kWidth) << "\" height=\""
      << number(kHeight) << "\" viewBox=\"0 0 " << number(kWidth) << " " << number(kHeight)
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
  for (int d = x_range.first; d <= x_range.second; ++d) {
    const double x = kX0 + kPlotW * (d - x_range.first) / (x_range.second - x_range.first);
    line(svg, x, kY0, x, kY0 + kPlotH, "#ddd");
    text(svg, x, kY0 + kPlotH + 15, number(std::pow(10.0, d)));
  }
  for (int d = y_range.first; d <= y_range.second; ++d) {
    const double y =
        kY0 + kPlotH * (1 - double(d - y_range.first) / (y_range.second - y_range.first));
    line(svg, kX0, y, kX0 + kPlotW, y, "#ddd");
    text(svg, kX0 - 4, y + 4, number(std::pow(10.0, d)), "end");
  }
  svg << "<rect x=\"" << number(kX0) << "\" y=\"" << number(kY0) << "\" width=\"" << number(kPlotW)
      << "\" height=\"" << number(kPlotH) << "\" fill=\"none\" stroke=\"#000\"/>\n";
  text(svg, kX0 + kPlotW / 2, kHeight - 12, x_label);
  const double ly = kY0 + kPlotH / 2;
  text(svg, 16, ly, y_label, "middle",
       (" transform=\"rotate(-90 16 " + number(ly) + ")\"").c_str());
  // Markers by series: circles, squares, triangles, diamonds, then again in other colours.
  auto marker = [&](size_t i, double x, double y) {
    const char* color = kColors[i % kColorCount];
    switch (i % 4) {
      case 0:
        svg << "<circle cx=\"" << number(x) << "\" cy=\"" << number(y) << "\" r=\"3.5\"";
        break;
      case 1:
        svg << "<rect x=\"" << number(x - 3) << "\" y=\"" << number(y - 3)
            << "\" width=\"6\" height=\"6\"";
        break;
      case 2:
        svg << "<polygon points=\"" << number(x) << "," << number(y - 4) << " " << number(x - 4)
            << "," << number(y + 3) << " " << number(x + 4) << "," << number(y + 3) << "\"";
        break;
      default:
        svg << "<polygon points=\"" << number(x) << "," << number(y - 4) << " " << number(x + 4)
            << "," << number(y) << " " << number(x) << "," << number(y + 4) << " " << number(x - 4)
            << "," << number(y) << "\"";
    }
    svg << " fill=\"" << color << "\" fill-opacity=\"0.6\" stroke=\"" << color << "\"/>\n";
  };
  for (size_t i = 0; i < series.size(); ++i) {
    for (size_t k = 0; k < series[i].x.size() && k < series[i].y.size(); ++k) {
      marker(i, kX0 + kPlotW * on_log_axis(series[i].x[k], x_range),
             kY0 + kPlotH * (1 - on_log_axis(series[i].y[k], y_range)));
    }
    const double legend_y = kY0 + 10 + 18 * i;
    marker(i, kX0 + kPlotW + 16, legend_y - 4);
    text(svg, kX0 + kPlotW + 26, legend_y,
         series[i].name + " (" + std::to_string(series[i].x.size()) + ")", "start");
  }
  svg << "</svg>\n";
  return svg.str();
}

std::string stacked_bars_svg(const std::vector<BarPanel>& panels,
                             const std::vector<std::string>& segment_names,
                             const std::string& x_label) {
  constexpr size_t kColumns = 2;
  constexpr double kHeader = 22;
  std::ostringstream svg;
  open(svg, panels.size(), kColumns, kHeader);
  double legend_x = 8;
  for (size_t s = 0; s < segment_names.size(); ++s) {
    svg << "<rect x=\"" << number(legend_x) << "\" y=\"6\" width=\"10\" height=\"10\" fill=\""
        << kColors[s % kColorCount] << "\"/>\n";
    text(svg, legend_x + 14, 15, segment_names[s], "start");
    legend_x += 20 + 7 * segment_names[s].size();
  }
  for (size_t i = 0; i < panels.size(); ++i) {
    const BarPanel& p = panels[i];
    const auto [x0, y0] = panel(svg, i, kColumns, kHeader, p.title, x_label, "share of holes");
    for (int percent = 0; percent <= 100; percent += 25) {
      const double y = y0 + kPlotHeight * (1 - percent / 100.0);
      line(svg, x0, y, x0 + kPlotWidth, y, "#ddd");
      text(svg, x0 - 4, y + 4, std::to_string(percent) + " %", "end");
    }
    const double slot = kPlotWidth / std::max<size_t>(1, p.categories.size());
    for (size_t c = 0; c < p.categories.size(); ++c) {
      const double x = x0 + slot * c + slot * 0.15;
      text(svg, x0 + slot * (c + 0.5), y0 + kPlotHeight + 14, p.categories[c]);
      double bottom = 0;
      for (size_t s = 0; c < p.segments.size() && s < p.segments[c].size(); ++s) {
        const double share = std::clamp(p.segments[c][s], 0.0, 1.0 - bottom);
        if (share <= 0) continue;
        svg << "<rect x=\"" << number(x) << "\" y=\""
            << number(y0 + kPlotHeight * (1 - bottom - share)) << "\" width=\""
            << number(slot * 0.7) << "\" height=\"" << number(kPlotHeight * share) << "\" fill=\""
            << kColors[s % kColorCount] << "\"/>\n";
        bottom += share;
      }
    }
  }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace rangefill::cli
