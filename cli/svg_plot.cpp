#include "svg_plot.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace batchccd::cli {

namespace {

// Layout, in SVG user units (pixels at 100 %).
constexpr double kTitleBand = 34;  // the document's title, above the panels
constexpr double kPanelWidth = 460;
constexpr double kPanelHeight = 390;
constexpr double kFrameLeft = 78;    // room for tick labels and the y-axis title
constexpr double kFrameRight = 18;
constexpr double kFrameTop = 40;     // room for the panel's title
constexpr double kFrameBottom = 70;  // room for tick labels, the x-axis title and the note
constexpr double kZeroBand = 28;     // the "0" row or column of a broken axis
constexpr double kBreakGap = 8;      // between the zero band and the decades
constexpr double kInset = 12;        // keeps markers on the outermost decades off the frame
constexpr int kMaxDecadeIntervals = 6;  // more decades than this get a coarser tick step

constexpr double kTickFontSize = 11;
constexpr double kLabelFontSize = 11;
constexpr double kLabelHeight = kLabelFontSize + 3;
constexpr double kMarkerRadius = 5;
constexpr double kLabelGap = 4;  // between a marker's edge and its label
constexpr int kMaxLabelNudges = 6;
// Average advance of DejaVu Sans / Arial; layout only needs an estimate.
constexpr double kCharWidthEm = 0.6;
// From the alphabetic baseline to the middle of lower-case and digits.
constexpr double kBaselineToMiddleEm = 0.35;

constexpr std::string_view kFontFamily = "DejaVu Sans, Arial, Helvetica, sans-serif";
constexpr std::array<std::string_view, 10> kPalette = {
    "#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
    "#8c564b", "#e377c2", "#17becf", "#7f7f7f", "#bcbd22"};
// Centred on the origin, about kMarkerRadius across; a second cue besides
// colour when markers lie on top of each other.
constexpr std::array<std::string_view, 6> kMarkerShapes = {
    R"(<circle r="4.5"/>)",
    R"(<rect x="-4" y="-4" width="8" height="8"/>)",
    R"(<path d="M0,-5.5L5.5,0L0,5.5L-5.5,0Z"/>)",
    R"(<path d="M0,-5.5L5,3.5L-5,3.5Z"/>)",
    R"(<path d="M0,5.5L5,-3.5L-5,-3.5Z"/>)",
    R"(<path d="M-1.8,-5H1.8V-1.8H5V1.8H1.8V5H-1.8V1.8H-5V-1.8H-1.8Z"/>)"};

// One decimal is finer than any screen; rounding first keeps "-0.0" out.
std::string coordinate(double value) {
  char buffer[48];
  const double rounded = std::round(value * 10) / 10 + 0.0;
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, rounded,
                                    std::chars_format::fixed, 1);
  return std::string(buffer, result.ptr);
}

// Three significant digits; "nan" / "inf" / "-inf" as they are.
std::string short_value(double value) {
  char buffer[48];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value,
                                    std::chars_format::general, 3);
  return std::string(buffer, result.ptr);
}

// Usable both as element text and inside a quoted attribute.
std::string xml_escaped(std::string_view text) {
  std::string out;
  for (const char character : text) {
    switch (character) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        // XML 1.0 allows no other control characters, not even as references.
        out += static_cast<unsigned char>(character) < 0x20 ? ' ' : character;
    }
  }
  return out;
}

double text_width(std::string_view text, double font_size) {
  const auto code_points = std::count_if(text.begin(), text.end(), [](char byte) {
    return (static_cast<unsigned char>(byte) & 0xC0) != 0x80;  // not a continuation byte
  });
  return static_cast<double>(code_points) * kCharWidthEm * font_size;
}

// Shrinks long titles to fit their room instead of running into the next panel.
double fitted_font_size(std::string_view text, double preferred, double room) {
  const double width = text_width(text, preferred);
  return width <= room ? preferred : std::max(7.0, preferred * room / width);
}

// "0.01" to "100" as decimals, beyond that "1e-3", "1e3".
std::string decade_text(int exponent) {
  if (exponent < -2 || exponent > 2) return "1e" + std::to_string(exponent);
  if (exponent < 0) return "0." + std::string(-exponent - 1, '0') + "1";
  return "1" + std::string(exponent, '0');
}

int floor_to_multiple(int value, int step) {
  return static_cast<int>(std::floor(static_cast<double>(value) / step)) * step;
}

int ceil_to_multiple(int value, int step) {
  return static_cast<int>(std::ceil(static_cast<double>(value) / step)) * step;
}

// 1, 2, 5, 10, 20, 50, ... decades per tick, the first giving few enough ticks.
int decade_step(int decades) {
  for (int scale = 1;; scale *= 10) {
    for (const int multiple : {1, 2, 5}) {
      if (decades <= kMaxDecadeIntervals * multiple * scale) return multiple * scale;
    }
  }
}

struct Tick {
  double position;
  std::string text;
};

// One logarithmic axis, positions measured from the plot's origin corner.
// When some value is 0 a band for it comes first, then the axis break, then
// the decades.
class LogAxis {
 public:
  // `values` are finite and >= 0.
  LogAxis(const std::vector<double>& values, double length) : length_(length) {
    double smallest = std::numeric_limits<double>::infinity();
    double largest = 0;
    for (const double value : values) {
      if (value == 0) {
        has_zero_ = true;
      } else {
        smallest = std::min(smallest, value);
        largest = std::max(largest, value);
      }
    }
    if (largest > 0) {
      first_decade_ = static_cast<int>(std::floor(std::log10(smallest)));
      last_decade_ = static_cast<int>(std::ceil(std::log10(largest)));
    }
    // Equal powers of ten would leave no range at all; centre them instead.
    if (first_decade_ == last_decade_) {
      --first_decade_;
      ++last_decade_;
    }
    step_ = decade_step(last_decade_ - first_decade_);
    first_decade_ = floor_to_multiple(first_decade_, step_);
    last_decade_ = ceil_to_multiple(last_decade_, step_);
  }

  double length() const { return length_; }
  bool has_zero() const { return has_zero_; }
  double gap_begin() const { return kZeroBand; }
  double gap_end() const { return kZeroBand + kBreakGap; }

  double position(double value) const {
    return value == 0 ? kZeroBand / 2 : decade_position(std::log10(value));
  }

  // The zero band and the decades, each as (begin, end).
  std::vector<std::pair<double, double>> segments() const {
    if (!has_zero_) return {{0, length_}};
    return {{0, gap_begin()}, {gap_end(), length_}};
  }

  std::vector<Tick> major_ticks() const {
    std::vector<Tick> ticks;
    if (has_zero_) ticks.push_back({position(0), "0"});
    for (int decade = first_decade_; decade <= last_decade_; decade += step_)
      ticks.push_back({decade_position(decade), decade_text(decade)});
    return ticks;
  }

  // 2 to 9 times each decade, when every decade has a tick (else too dense).
  std::vector<double> minor_tick_positions() const {
    std::vector<double> positions;
    if (step_ != 1) return positions;
    for (int decade = first_decade_; decade < last_decade_; ++decade) {
      for (int multiple = 2; multiple <= 9; ++multiple)
        positions.push_back(decade_position(decade + std::log10(multiple)));
    }
    return positions;
  }

 private:
  double decade_position(double decade) const {
    const double begin = (has_zero_ ? gap_end() : 0) + kInset;
    const double end = length_ - kInset;
    return begin + (decade - first_decade_) / (last_decade_ - first_decade_) * (end - begin);
  }

  double length_;
  bool has_zero_ = false;
  int first_decade_ = 0;  // an arbitrary decade when there are no positive values
  int last_decade_ = 1;
  int step_ = 1;
};

struct Box {
  double left, top, right, bottom;

  bool overlaps(const Box& other) const {
    return left < other.right && other.left < right && top < other.bottom && other.top < bottom;
  }
  bool contains(const Box& other) const {
    return left <= other.left && other.right <= right && top <= other.top && other.bottom <= bottom;
  }
};

struct LabelPlacement {
  Box box;
  bool on_right;
  bool nudged;  // moved off the marker's line, so it gets a leader line
};

// Right of the marker if there is room, else left; moved a line up or down
// at a time, nearest first, while it would cover another label or marker.
// When nothing is free it overlaps rather than leaving the frame.
LabelPlacement place_label(double marker_x, double marker_y, double width, const Box& frame,
                           const std::vector<Box>& taken) {
  std::optional<LabelPlacement> first_inside_frame;
  for (int nudge = 0; nudge <= kMaxLabelNudges; ++nudge) {
    for (const int direction : {-1, 1}) {
      if (nudge == 0 && direction == 1) continue;  // the same place as direction -1
      const double middle = marker_y + direction * nudge * kLabelHeight;
      for (const bool on_right : {true, false}) {
        const double left = on_right ? marker_x + kMarkerRadius + kLabelGap
                                     : marker_x - kMarkerRadius - kLabelGap - width;
        const LabelPlacement candidate{
            {left, middle - kLabelHeight / 2, left + width, middle + kLabelHeight / 2},
            on_right, nudge != 0};
        if (!frame.contains(candidate.box)) continue;
        if (std::none_of(taken.begin(), taken.end(),
                         [&](const Box& box) { return box.overlaps(candidate.box); }))
          return candidate;
        if (!first_inside_frame) first_inside_frame = candidate;
      }
    }
  }
  if (first_inside_frame) return *first_inside_frame;
  const double left = marker_x + kMarkerRadius + kLabelGap;  // wider than the frame
  return {{left, marker_y - kLabelHeight / 2, left + width, marker_y + kLabelHeight / 2}, true,
          false};
}

struct MarkerStyle {
  std::string_view colour;
  std::string_view shape;
};

// By order of first appearance over all panels, so a label looks the same in each.
class MarkerStyles {
 public:
  explicit MarkerStyles(const std::vector<PlotPanel>& panels) {
    for (const PlotPanel& panel : panels) {
      for (const PlotPoint& point : panel.points) {
        if (std::find(labels_.begin(), labels_.end(), point.label) == labels_.end())
          labels_.push_back(point.label);
      }
    }
  }

  MarkerStyle of(const std::string& label) const {
    const auto index = static_cast<std::size_t>(
        std::find(labels_.begin(), labels_.end(), label) - labels_.begin());
    return {kPalette[index % kPalette.size()], kMarkerShapes[index % kMarkerShapes.size()]};
  }

 private:
  std::vector<std::string> labels_;
};

void append_line(std::string& svg, double x1, double y1, double x2, double y2) {
  svg += "<line x1=\"" + coordinate(x1) + "\" y1=\"" + coordinate(y1) + "\" x2=\"" +
         coordinate(x2) + "\" y2=\"" + coordinate(y2) + "\"/>\n";
}

// `attributes` is trusted markup; `content` is escaped.
void append_text(std::string& svg, double x, double y, std::string_view attributes,
                 std::string_view content) {
  svg += "<text x=\"" + coordinate(x) + "\" y=\"" + coordinate(y) + "\" ";
  svg += attributes;
  svg += ">" + xml_escaped(content) + "</text>\n";
}

std::string font_size_attribute(double size) { return "font-size=\"" + coordinate(size) + "\""; }

bool placeable(double value) { return std::isfinite(value) && value >= 0; }
bool placeable(const PlotPoint& point) { return placeable(point.x) && placeable(point.y); }

// "fcl (y = nan)" for a point a log axis cannot show.
std::string skipped_description(const PlotPoint& point) {
  std::string reasons;
  if (!placeable(point.x)) reasons = "x = " + short_value(point.x);
  if (!placeable(point.y))
    reasons += (reasons.empty() ? "y = " : ", y = ") + short_value(point.y);
  return point.label + " (" + reasons + ")";
}

struct PlacedPoint {
  const PlotPoint* point;
  double x, y;  // on the page
};

// One panel with its top-left corner at (origin_x, origin_y).
class PanelWriter {
 public:
  PanelWriter(const PlotPanel& panel, const MarkerStyles& styles, double origin_x,
              double origin_y)
      : panel_(panel),
        styles_(styles),
        origin_x_(origin_x),
        frame_{origin_x + kFrameLeft, origin_y + kFrameTop,
               origin_x + kPanelWidth - kFrameRight, origin_y + kPanelHeight - kFrameBottom},
        x_axis_(placeable_values(panel, &PlotPoint::x), frame_.right - frame_.left),
        y_axis_(placeable_values(panel, &PlotPoint::y), frame_.bottom - frame_.top) {
    for (const PlotPoint& point : panel.points) {
      if (placeable(point))
        placed_.push_back({&point, page_x(x_axis_.position(point.x)),
                           page_y(y_axis_.position(point.y))});
    }
  }

  void write(std::string& svg) const {
    write_titles(svg);
    write_grid(svg);
    write_frame(svg);
    write_ticks(svg);
    write_note(svg);
    write_points(svg);
  }

 private:
  static std::vector<double> placeable_values(const PlotPanel& panel,
                                              double PlotPoint::*coordinate) {
    std::vector<double> values;
    for (const PlotPoint& point : panel.points) {
      if (placeable(point)) values.push_back(point.*coordinate);
    }
    return values;
  }

  double page_x(double along) const { return frame_.left + along; }
  double page_y(double along) const { return frame_.bottom - along; }
  double frame_middle_x() const { return (frame_.left + frame_.right) / 2; }

  void write_titles(std::string& svg) const {
    const double title_size = fitted_font_size(panel_.title, 13, kPanelWidth - 16);
    append_text(svg, frame_middle_x(), frame_.top - 16,
                "text-anchor=\"middle\" font-weight=\"bold\" " + font_size_attribute(title_size),
                panel_.title);
    const double x_label_size = fitted_font_size(panel_.x_label, 12, frame_.right - frame_.left);
    append_text(svg, frame_middle_x(), frame_.bottom + 38,
                "text-anchor=\"middle\" " + font_size_attribute(x_label_size), panel_.x_label);
    const double y_label_size = fitted_font_size(panel_.y_label, 12, frame_.bottom - frame_.top);
    const double y_label_x = origin_x_ + 18;
    const double y_label_y = (frame_.top + frame_.bottom) / 2;
    append_text(svg, y_label_x, y_label_y,
                "text-anchor=\"middle\" transform=\"rotate(-90 " + coordinate(y_label_x) + " " +
                    coordinate(y_label_y) + ")\" " + font_size_attribute(y_label_size),
                panel_.y_label);
  }

  // Light lines at each major tick, interrupted at the axis breaks.
  void write_grid(std::string& svg) const {
    svg += "<g stroke=\"#e4e4e4\" stroke-width=\"1\">\n";
    for (const Tick& tick : x_axis_.major_ticks()) {
      for (const auto& [begin, end] : y_axis_.segments())
        append_line(svg, page_x(tick.position), page_y(begin), page_x(tick.position), page_y(end));
    }
    for (const Tick& tick : y_axis_.major_ticks()) {
      for (const auto& [begin, end] : x_axis_.segments())
        append_line(svg, page_x(begin), page_y(tick.position), page_x(end), page_y(tick.position));
    }
    svg += "</g>\n";
  }

  // One rectangle per pair of axis segments, and "/" marks where an axis is broken.
  void write_frame(std::string& svg) const {
    svg += "<g fill=\"none\" stroke=\"#444\" stroke-width=\"1\">\n";
    for (const auto& [x_begin, x_end] : x_axis_.segments()) {
      for (const auto& [y_begin, y_end] : y_axis_.segments()) {
        svg += "<rect x=\"" + coordinate(page_x(x_begin)) + "\" y=\"" + coordinate(page_y(y_end)) +
               "\" width=\"" + coordinate(x_end - x_begin) + "\" height=\"" +
               coordinate(y_end - y_begin) + "\"/>\n";
      }
    }
    constexpr double kHalfMark = 3;
    if (x_axis_.has_zero()) {
      for (const double gap_edge : {x_axis_.gap_begin(), x_axis_.gap_end()}) {
        for (const double edge : {0.0, y_axis_.length()})
          append_line(svg, page_x(gap_edge - kHalfMark), page_y(edge - 2 * kHalfMark),
                      page_x(gap_edge + kHalfMark), page_y(edge + 2 * kHalfMark));
      }
    }
    if (y_axis_.has_zero()) {
      for (const double gap_edge : {y_axis_.gap_begin(), y_axis_.gap_end()}) {
        for (const double edge : {0.0, x_axis_.length()})
          append_line(svg, page_x(edge - 2 * kHalfMark), page_y(gap_edge - kHalfMark),
                      page_x(edge + 2 * kHalfMark), page_y(gap_edge + kHalfMark));
      }
    }
    svg += "</g>\n";
  }

  // Major ticks outside the frame with their labels, minor ticks inside.
  void write_ticks(std::string& svg) const {
    constexpr double kMajorLength = 4, kMinorLength = 3;
    svg += "<g stroke=\"#444\" stroke-width=\"1\">\n";
    for (const Tick& tick : x_axis_.major_ticks())
      append_line(svg, page_x(tick.position), frame_.bottom, page_x(tick.position),
                  frame_.bottom + kMajorLength);
    for (const Tick& tick : y_axis_.major_ticks())
      append_line(svg, frame_.left - kMajorLength, page_y(tick.position), frame_.left,
                  page_y(tick.position));
    for (const double position : x_axis_.minor_tick_positions())
      append_line(svg, page_x(position), frame_.bottom, page_x(position),
                  frame_.bottom - kMinorLength);
    for (const double position : y_axis_.minor_tick_positions())
      append_line(svg, frame_.left, page_y(position), frame_.left + kMinorLength,
                  page_y(position));
    svg += "</g>\n";

    const std::string size = font_size_attribute(kTickFontSize);
    for (const Tick& tick : x_axis_.major_ticks())
      append_text(svg, page_x(tick.position), frame_.bottom + kMajorLength + kTickFontSize + 1,
                  "class=\"x-tick\" text-anchor=\"middle\" " + size, tick.text);
    for (const Tick& tick : y_axis_.major_ticks())
      append_text(svg, frame_.left - kMajorLength - 3,
                  page_y(tick.position) + kBaselineToMiddleEm * kTickFontSize,
                  "class=\"y-tick\" text-anchor=\"end\" " + size, tick.text);
  }

  // Names the points left out, so a missing marker is not mistaken for a missing method.
  void write_note(std::string& svg) const {
    std::string skipped;
    for (const PlotPoint& point : panel_.points) {
      if (!placeable(point)) skipped += (skipped.empty() ? "" : ", ") + skipped_description(point);
    }
    if (skipped.empty()) return;
    const std::string note = "not plotted (log axes need finite values >= 0): " + skipped;
    append_text(svg, frame_middle_x(), frame_.bottom + 56,
                "class=\"note\" text-anchor=\"middle\" fill=\"#a00\" " +
                    font_size_attribute(fitted_font_size(note, 10, kPanelWidth - 16)),
                note);
  }

  void write_points(std::string& svg) const {
    std::vector<Box> taken;
    for (const PlacedPoint& placed : placed_)
      taken.push_back({placed.x - kMarkerRadius - 1, placed.y - kMarkerRadius - 1,
                       placed.x + kMarkerRadius + 1, placed.y + kMarkerRadius + 1});
    std::vector<LabelPlacement> labels;
    for (const PlacedPoint& placed : placed_) {
      labels.push_back(place_label(placed.x, placed.y,
                                   text_width(placed.point->label, kLabelFontSize), frame_,
                                   taken));
      taken.push_back(labels.back().box);
    }

    // Leaders first, so markers and labels are drawn over them.
    svg += "<g stroke=\"#999\" stroke-width=\"0.8\">\n";
    for (std::size_t index = 0; index < placed_.size(); ++index) {
      const LabelPlacement& label = labels[index];
      if (label.nudged)
        append_line(svg, placed_[index].x, placed_[index].y,
                    label.on_right ? label.box.left - 1 : label.box.right + 1,
                    (label.box.top + label.box.bottom) / 2);
    }
    svg += "</g>\n";
    for (const PlacedPoint& placed : placed_) {
      const MarkerStyle style = styles_.of(placed.point->label);
      svg += "<g class=\"point\" transform=\"translate(" + coordinate(placed.x) + "," +
             coordinate(placed.y) + ")\" fill=\"" + std::string(style.colour) +
             "\" fill-opacity=\"0.9\" stroke=\"white\" stroke-width=\"0.8\"><title>" +
             xml_escaped(placed.point->label) + ": x = " + short_value(placed.point->x) +
             ", y = " + short_value(placed.point->y) + "</title>" + std::string(style.shape) +
             "</g>\n";
    }
    for (std::size_t index = 0; index < placed_.size(); ++index) {
      const LabelPlacement& label = labels[index];
      const std::string anchor = label.on_right ? "start" : "end";
      append_text(svg, label.on_right ? label.box.left : label.box.right,
                  (label.box.top + label.box.bottom) / 2 + kBaselineToMiddleEm * kLabelFontSize,
                  "class=\"label\" text-anchor=\"" + anchor + "\" fill=\"" +
                      std::string(styles_.of(placed_[index].point->label).colour) + "\" " +
                      font_size_attribute(kLabelFontSize),
                  placed_[index].point->label);
    }
  }

  const PlotPanel& panel_;
  const MarkerStyles& styles_;
  double origin_x_;
  Box frame_;
  LogAxis x_axis_;
  LogAxis y_axis_;
  std::vector<PlacedPoint> placed_;
};

}  // namespace

std::string scatter_svg(std::string_view title, const std::vector<PlotPanel>& panels) {
  const double width = kPanelWidth * static_cast<double>(std::max<std::size_t>(1, panels.size()));
  const double height = kTitleBand + kPanelHeight;
  std::string svg = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + coordinate(width) +
         "\" height=\"" + coordinate(height) + "\" viewBox=\"0 0 " + coordinate(width) + " " +
         coordinate(height) + "\" font-family=\"" + std::string(kFontFamily) +
         "\" fill=\"#222\">\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  append_text(svg, width / 2, 24,
              "text-anchor=\"middle\" font-weight=\"bold\" " +
                  font_size_attribute(fitted_font_size(title, 16, width - 16)),
              title);

  const MarkerStyles styles(panels);
  for (std::size_t index = 0; index < panels.size(); ++index)
    PanelWriter(panels[index], styles, kPanelWidth * static_cast<double>(index), kTitleBand)
        .write(svg);
  svg += "</svg>\n";
  return svg;
}

}  // namespace batchccd::cli
