#include "evaluation/roc_figure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string_view>
#include <vector>

namespace owsim {
namespace {

constexpr double kWidth = 760, kHeight = 500, kLeft = 70, kRight = 30, kTop = 50, kBottom = 110;
constexpr double kZeroColumn = 44;  // left of the log axis, for values without false returns
constexpr const char* kColour = "#1f5fbf";

std::string xml_text(std::string_view text) {
  std::string out;
  for (const char c : text) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

std::string short_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

struct Point {
  const RocRow* row;
  double rate;  // false returns per second (--detections: false warnings per flight hour)
  double pd;
};

// The decades the log axis spans: from the smallest positive rate's to the largest's, at least one.
std::pair<int, int> decades(const std::vector<Point>& points) {
  double smallest = INFINITY, largest = 0.0;
  for (const Point& point : points) {
    if (point.rate <= 0.0) continue;
    smallest = std::min(smallest, point.rate);
    largest = std::max(largest, point.rate);
  }
  if (largest <= 0.0) return {-1, 0};
  const int lo = static_cast<int>(std::floor(std::log10(smallest)));
  const int hi = static_cast<int>(std::ceil(std::log10(largest)));
  return {lo, std::max(hi, lo + 1)};
}

}  // namespace

std::string roc_svg(const RocReport& report, const RocOptions& options) {
  std::vector<Point> points;
  for (const RocRow& row : report.rows) {
    const double rate =
        row.warnings ? row.warnings->false_warnings_per_hour() : row.false_returns.per_s();
    if (row.windows == 0 || !std::isfinite(rate)) continue;
    points.push_back(
        {&row, rate, static_cast<double>(row.windows_detected) / static_cast<double>(row.windows)});
  }
  const bool zeros = std::any_of(points.begin(), points.end(),
                                 [](const Point& point) { return point.rate <= 0.0; });
  const std::pair<int, int> span = decades(points);
  const int decade_lo = span.first;  // plain names: clang 14 cannot capture structured bindings
  const int decade_hi = span.second;
  const double plot_w = kWidth - kLeft - kRight;
  const double plot_h = kHeight - kTop - kBottom;
  const double axis_x0 = kLeft + (zeros ? kZeroColumn : 0.0);
  const double decades_x0 = axis_x0 + (zeros ? kZeroColumn / 3.0 : 0.0);  // clear of the "0"
  const auto x_of = [&](double rate) {
    if (rate <= 0.0) return kLeft + kZeroColumn / 2.0;
    return decades_x0 +
           (std::log10(rate) - decade_lo) / (decade_hi - decade_lo) * (kLeft + plot_w - decades_x0);
  };
  const auto y_of = [&](double p) { return kTop + (1.0 - p) * plot_h; };
  std::string svg;
  const auto add = [&](const char* format, auto... values) {
    char text[512];
    std::snprintf(text, sizeof text, format, values...);
    svg += text;
  };
  add("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%g\" height=\"%g\" "
      "viewBox=\"0 0 %g %g\" font-family=\"sans-serif\" font-size=\"12\">\n",
      kWidth, kHeight, kWidth, kHeight);
  add("<rect width=\"%g\" height=\"%g\" fill=\"white\"/>\n", kWidth, kHeight);
  const std::string title = (options.detections ? "Warning Pd of " : "Pd of ") + report.target +
                            " at " + short_number(options.range_lo_m) + "–" +
                            short_number(options.range_hi_m) + " m: ≥ " +
                            std::to_string(options.criterion.returns) +
                            (options.detections ? " warned frame(s) within " : " return(s) within ") +
                            short_number(options.criterion.window_s) + " s, by " + options.by;
  svg += "<text x=\"" + short_number(kLeft) + "\" y=\"24\" font-size=\"14\">" + xml_text(title) +
         "</text>\n";
  for (int tick = 0; tick <= 10; ++tick) {
    const double p = tick / 10.0;
    add("<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"#ddd\"/>\n", kLeft, y_of(p),
        kLeft + plot_w, y_of(p));
    add("<text x=\"%g\" y=\"%g\" text-anchor=\"end\">%.1f</text>\n", kLeft - 6, y_of(p) + 4, p);
  }
  for (int decade = decade_lo; decade <= decade_hi; ++decade) {
    const double x = x_of(std::pow(10.0, decade));
    add("<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"#ddd\"/>\n", x, kTop, x,
        kTop + plot_h);
    add("<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">%g</text>\n", x, kTop + plot_h + 18,
        std::pow(10.0, decade));
    for (int minor = 2; minor <= 9 && decade < decade_hi; ++minor) {
      const double xm = x_of(minor * std::pow(10.0, decade));
      add("<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"#f0f0f0\"/>\n", xm, kTop, xm,
          kTop + plot_h);
    }
  }
  if (zeros) {
    add("<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"#444\" stroke-dasharray=\"4 "
        "3\"/>\n",
        axis_x0, kTop, axis_x0, kTop + plot_h);
    add("<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">0</text>\n", x_of(0.0), kTop + plot_h + 18);
  }
  add("<rect x=\"%g\" y=\"%g\" width=\"%g\" height=\"%g\" fill=\"none\" stroke=\"#444\"/>\n", kLeft,
      kTop, plot_w, plot_h);
  add("<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">%s (log scale)</text>\n",
      kLeft + plot_w / 2, kTop + plot_h + 38,
      options.detections ? "false warnings per flight hour" : "false returns per second");
  add("<text transform=\"translate(18 %g) rotate(-90)\" text-anchor=\"middle\">Pd within %s s"
      "</text>\n",
      kTop + plot_h / 2, short_number(options.criterion.window_s).c_str());
  if (points.size() > 1) {  // the band between the intervals, then the curve, in value order
    svg += "<polygon class=\"roc-band\" fill=\"" + std::string(kColour) +
           "\" fill-opacity=\"0.15\" points=\"";
    for (const Point& point : points) {
      add("%.2f,%.2f ", x_of(point.rate), y_of(point.row->window_interval.upper));
    }
    for (auto it = points.rbegin(); it != points.rend(); ++it) {
      add("%.2f,%.2f ", x_of(it->rate), y_of(it->row->window_interval.lower));
    }
    svg += "\"/>\n<polyline fill=\"none\" stroke-width=\"2\" stroke=\"" + std::string(kColour) +
           "\" points=\"";
    for (const Point& point : points) add("%.2f,%.2f ", x_of(point.rate), y_of(point.pd));
    svg += "\"/>\n";
  }
  for (const Point& point : points) {
    const double x = x_of(point.rate);
    const double lower = y_of(point.row->window_interval.lower);
    const double upper = y_of(point.row->window_interval.upper);
    add("<path class=\"roc-interval\" d=\"M%.2f %.2fV%.2fM%.2f %.2fh8M%.2f %.2fh8\" "
        "stroke=\"%s\" fill=\"none\"/>\n",
        x, lower, upper, x - 4, lower, x - 4, upper, kColour);
    svg += "<circle class=\"roc-point\" data-value=\"" + xml_text(point.row->value) + "\"";
    add(" cx=\"%.2f\" cy=\"%.2f\" r=\"3.5\" fill=\"%s\"/>\n", x, y_of(point.pd), kColour);
    // The value below the point, or above it near the axis.
    const double label_y = y_of(point.pd) + (point.pd < 0.15 ? -8.0 : 14.0);
    add("<text x=\"%.2f\" y=\"%.2f\" font-size=\"11\">", x + 6, label_y);
    svg += xml_text(point.row->value) + "</text>\n";
  }
  const double legend_y = kTop + plot_h + 62;
  svg += "<text x=\"" + short_number(kLeft) + "\" y=\"" + short_number(legend_y) +
         "\">Each point: the members with one value of " + xml_text(options.by) +
         " (labelled), over " + std::to_string(report.flights) + " flights.</text>\n";
  svg += "<text x=\"" + short_number(kLeft) + "\" y=\"" + short_number(legend_y + 18) +
         "\">Bars and band: " + short_number(options.confidence * 100.0) +
         " % Clopper–Pearson intervals of Pd within the window.</text>\n";
  svg += "</svg>\n";
  return svg;
}

}  // namespace owsim
