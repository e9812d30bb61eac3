// The SVG scatter plots of the reports: well-formed XML with every text in
// it, escaped; zeros on the row past the axis break; points a log axis
// cannot show left out and named in a note; degenerate ranges kept inside
// the plot; labels of clustered points kept apart; one colour per label in
// every panel; and the same bytes every time.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <clocale>
#include <limits>
#include <regex>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "svg_plot.hpp"

namespace batchccd::cli {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// ---- a small XML well-formedness checker ---------------------------------------

bool is_name_character(char character) {
  return std::isalnum(static_cast<unsigned char>(character)) || character == '-' ||
         character == '_' || character == ':' || character == '.';
}

// Length of the entity or character reference at `at` (an '&'), 0 if there is none.
std::size_t reference_length(std::string_view text, std::size_t at) {
  const std::size_t end = text.find(';', at);
  if (end == std::string_view::npos) return 0;
  const std::string_view name = text.substr(at + 1, end - at - 1);
  const bool named = name == "amp" || name == "lt" || name == "gt" || name == "quot" || name == "apos";
  const bool numeric = name.size() > 1 && name[0] == '#' &&
                       std::all_of(name.begin() + 1, name.end(),
                                   [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
  return named || numeric ? end - at + 1 : 0;
}

// Empty when `document` is well-formed as far as the plots need: an optional
// declaration, one root element, tags closed in order, attributes quoted,
// unique and separated, '<' never in text or values, '&' only in references.
std::string xml_error(std::string_view document) {
  std::size_t at = 0;
  const auto at_text = [&] { return " at offset " + std::to_string(at); };
  const auto skip_spaces = [&] {
    const std::size_t start = at;
    while (at < document.size() && std::isspace(static_cast<unsigned char>(document[at]))) ++at;
    return at > start;
  };
  const auto read_name = [&] {
    const std::size_t start = at;
    while (at < document.size() && is_name_character(document[at])) ++at;
    return std::string(document.substr(start, at - start));
  };

  if (document.starts_with("<?xml")) {
    at = document.find("?>");
    if (at == std::string_view::npos) return "unterminated declaration";
    at += 2;
  }
  std::vector<std::string> open_elements;
  bool root_seen = false;
  while (at < document.size()) {
    const char character = document[at];
    if (character == '&') {
      const std::size_t length = reference_length(document, at);
      if (length == 0) return "bare '&'" + at_text();
      at += length;
      continue;
    }
    if (character != '<') {
      if (open_elements.empty() && !std::isspace(static_cast<unsigned char>(character)))
        return "text outside the root element" + at_text();
      ++at;
      continue;
    }
    ++at;
    const bool closing = at < document.size() && document[at] == '/';
    if (closing) ++at;
    const std::string name = read_name();
    if (name.empty()) return "'<' without a tag name" + at_text();
    if (closing) {
      skip_spaces();
      if (at >= document.size() || document[at] != '>') return "bad closing tag" + at_text();
      if (open_elements.empty() || open_elements.back() != name)
        return "</" + name + "> closes nothing open" + at_text();
      open_elements.pop_back();
      ++at;
      continue;
    }
    if (open_elements.empty() && root_seen) return "a second root element" + at_text();
    root_seen = true;
    std::set<std::string> attributes;
    for (;;) {
      const bool separated = skip_spaces();
      if (at >= document.size()) return "unterminated <" + name + ">";
      if (document[at] == '>') {
        open_elements.push_back(name);
        ++at;
        break;
      }
      if (document.substr(at, 2) == "/>") {
        at += 2;
        break;
      }
      if (!separated) return "attributes not separated by space" + at_text();
      const std::string attribute = read_name();
      if (attribute.empty()) return "bad character in <" + name + ">" + at_text();
      if (!attributes.insert(attribute).second) return "duplicate attribute " + attribute;
      if (at >= document.size() || document[at] != '=') return "attribute without '='" + at_text();
      ++at;
      const char quote = at < document.size() ? document[at] : '\0';
      if (quote != '"' && quote != '\'') return "unquoted attribute " + attribute + at_text();
      for (++at; at < document.size() && document[at] != quote;) {
        if (document[at] == '<') return "'<' in an attribute value" + at_text();
        if (document[at] == '&') {
          const std::size_t length = reference_length(document, at);
          if (length == 0) return "bare '&' in an attribute value" + at_text();
          at += length;
        } else {
          ++at;
        }
      }
      if (at >= document.size()) return "unterminated attribute value";
      ++at;
    }
  }
  if (!open_elements.empty()) return "<" + open_elements.back() + "> is never closed";
  if (!root_seen) return "no root element";
  return "";
}

TEST(SvgPlotXmlChecker, AcceptsWellFormedAndRejectsMalformedDocuments) {
  EXPECT_EQ(xml_error("<?xml version=\"1.0\"?>\n<a x=\"1\" y='&lt;'><b/>t &amp; &#38;</a>\n"), "");
  for (const std::string_view malformed :
       {"<a><b></a></b>", "<a x=1/>", "<a>&</a>", "<a x=\"<\"/>", "<a x=\"1\"y=\"2\"/>",
        "<a x=\"1\" x=\"2\"/>", "<a>", "<a/><b/>", "text<a/>", "<a>&nan;</a>", "<a x=\"1/>"})
    EXPECT_NE(xml_error(malformed), "") << malformed;
}

// ---- reading the plot back ----------------------------------------------------

struct Marker {
  std::string label;
  double x, y;
  std::string fill;
};

struct Text {
  double x, y;
  std::string attributes;
  std::string content;

  bool has_class(std::string_view name) const {
    return attributes.find("class=\"" + std::string(name) + "\"") != std::string::npos;
  }
};

std::vector<Marker> markers(const std::string& svg) {
  static const std::regex pattern(
      R"re(<g class="point" transform="translate\(([-0-9.]+),([-0-9.]+)\)" fill="([^"]+)"[^>]*><title>([^<]*): x = )re");
  std::vector<Marker> found;
  for (auto match = std::sregex_iterator(svg.begin(), svg.end(), pattern);
       match != std::sregex_iterator(); ++match)
    found.push_back({(*match)[4], std::stod((*match)[1]), std::stod((*match)[2]), (*match)[3]});
  return found;
}

std::vector<Text> texts(const std::string& svg) {
  static const std::regex pattern(R"re(<text x="([-0-9.]+)" y="([-0-9.]+)"([^>]*)>([^<]*)</text>)re");
  std::vector<Text> found;
  for (auto match = std::sregex_iterator(svg.begin(), svg.end(), pattern);
       match != std::sregex_iterator(); ++match)
    found.push_back({std::stod((*match)[1]), std::stod((*match)[2]), (*match)[3], (*match)[4]});
  return found;
}

std::vector<Text> texts_of_class(const std::string& svg, std::string_view name) {
  std::vector<Text> found = texts(svg);
  std::erase_if(found, [&](const Text& text) { return !text.has_class(name); });
  return found;
}

const Marker& marker_of(const std::vector<Marker>& all, std::string_view label) {
  const auto found = std::find_if(all.begin(), all.end(),
                                  [&](const Marker& marker) { return marker.label == label; });
  if (found == all.end()) throw std::runtime_error("no marker for " + std::string(label));
  return *found;
}

const Text& tick_labelled(const std::vector<Text>& ticks, std::string_view content) {
  const auto found = std::find_if(ticks.begin(), ticks.end(),
                                  [&](const Text& tick) { return tick.content == content; });
  if (found == ticks.end()) throw std::runtime_error("no tick " + std::string(content));
  return *found;
}

// Attribute values hold only coordinates, colours and fixed words.
std::vector<std::string> attribute_values(const std::string& svg) {
  static const std::regex pattern(R"re(="([^"]*)")re");
  std::vector<std::string> values;
  for (auto match = std::sregex_iterator(svg.begin(), svg.end(), pattern);
       match != std::sregex_iterator(); ++match)
    values.push_back((*match)[1]);
  return values;
}

void expect_no_nonfinite_attributes(const std::string& svg) {
  for (std::string value : attribute_values(svg)) {
    std::transform(value.begin(), value.end(), value.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    EXPECT_EQ(value.find("nan"), std::string::npos) << value;
    EXPECT_EQ(value.find("inf"), std::string::npos) << value;
  }
}

double document_dimension(const std::string& svg, const std::string& name) {
  const std::regex pattern("<svg [^>]*" + name + "=\"([0-9.]+)\"");
  std::smatch match;
  if (!std::regex_search(svg, match, pattern)) throw std::runtime_error("no svg " + name);
  return std::stod(match[1]);
}

// ---- the plots ------------------------------------------------------------------

const std::vector<std::string> kMethods = {"exact", "conservative", "fast", "cubic", "dnf", "fcl"};

std::vector<PlotPanel> report_panels() {
  return {
      {"wrong decisions (false negatives + false positives)", "run time [s]", "count",
       {{"exact", 2.0, 0}, {"conservative", 0.05, 3}, {"fast", 0.045, 3},
        {"cubic", 0.6, 40}, {"dnf", 0.07, 3}, {"fcl", 1.5, 120}}},
      {"maximum TOI error", "run time [s]", "TOI error",
       {{"exact", 2.0, 0}, {"conservative", 0.05, 1e-8}, {"fast", 0.045, 1e-8},
        {"cubic", 0.6, 1e-3}, {"dnf", 0.07, 1e-8}, {"fcl", 1.5, 0.2}}}};
}

TEST(SvgPlot, ReportPlotIsWellFormedAndShowsEveryText) {
  const std::string svg = scatter_svg("batchccd demo: accuracy against run time", report_panels());
  EXPECT_EQ(xml_error(svg), "");
  for (const std::string_view text :
       {">batchccd demo: accuracy against run time<",
        ">wrong decisions (false negatives + false positives)<", ">maximum TOI error<",
        ">run time [s]<", ">count<", ">TOI error<"})
    EXPECT_NE(svg.find(text), std::string::npos) << text;
  const std::vector<Text> labels = texts_of_class(svg, "label");
  for (const std::string& method : kMethods) {
    EXPECT_EQ(std::count_if(labels.begin(), labels.end(),
                            [&](const Text& label) { return label.content == method; }),
              2)
        << method;
  }
  EXPECT_EQ(markers(svg).size(), 12u);
  for (const std::string_view decade : {"0.01", "0.1", "1", "10"})
    EXPECT_NO_THROW(tick_labelled(texts_of_class(svg, "x-tick"), decade)) << decade;
  for (const std::string_view decade : {"0", "1", "10", "100", "1e3", "1e-8"})
    EXPECT_NO_THROW(tick_labelled(texts_of_class(svg, "y-tick"), decade)) << decade;
}

TEST(SvgPlot, EscapesTextForXml) {
  const std::string svg = scatter_svg(
      "a & b < c > d \"e\" 'f'",
      {{"t<1>", "x & y", "\"y\"", {{"m<&>'\"", 1, 2}, {"control\x01\ttext", 2, 3}}}});
  EXPECT_EQ(xml_error(svg), "");
  EXPECT_NE(svg.find(">a &amp; b &lt; c &gt; d &quot;e&quot; &apos;f&apos;<"), std::string::npos);
  EXPECT_NE(svg.find(">t&lt;1&gt;<"), std::string::npos);
  EXPECT_NE(svg.find(">x &amp; y<"), std::string::npos);
  EXPECT_NE(svg.find(">&quot;y&quot;<"), std::string::npos);
  EXPECT_NE(svg.find(">m&lt;&amp;&gt;&apos;&quot;<"), std::string::npos);
  EXPECT_EQ(svg.find("m<&"), std::string::npos);
  EXPECT_EQ(svg.find('\x01'), std::string::npos);
}

TEST(SvgPlot, ZerosGoOnTheRowAndColumnPastTheAxisBreak) {
  const std::string svg = scatter_svg(
      "zeros", {{"", "x", "y",
                 {{"zero-a", 1, 0}, {"zero-b", 100, 0}, {"low", 1, 1e-3}, {"high", 100, 1e3},
                  {"zero-x", 0, 5}}}});
  EXPECT_EQ(xml_error(svg), "");
  const std::vector<Marker> all = markers(svg);
  const std::vector<Text> y_ticks = texts_of_class(svg, "y-tick");
  const double zero_row = tick_labelled(y_ticks, "0").y;
  double lowest_decade = 0;
  for (const Text& tick : y_ticks) {
    if (tick.content != "0") lowest_decade = std::max(lowest_decade, tick.y);
  }
  for (const std::string_view label : {"zero-a", "zero-b"}) {
    EXPECT_NEAR(marker_of(all, label).y, zero_row, 6) << label;  // the tick's baseline is below the middle
    EXPECT_GT(marker_of(all, label).y, lowest_decade) << label;
  }
  EXPECT_EQ(marker_of(all, "zero-a").y, marker_of(all, "zero-b").y);
  EXPECT_LT(marker_of(all, "low").y, lowest_decade);
  EXPECT_EQ(marker_of(all, "zero-x").x, tick_labelled(texts_of_class(svg, "x-tick"), "0").x);
  EXPECT_LT(marker_of(all, "zero-x").x, marker_of(all, "low").x);
}

TEST(SvgPlot, LeavesOutPointsALogAxisCannotShowAndSaysSo) {
  const std::string svg = scatter_svg(
      "skipped", {{"", "x", "y",
                   {{"fine", 1, 1}, {"nan-y", 1, kNaN}, {"infinite-x", kInfinity, 1},
                    {"negative-y", 1, -2}, {"also-fine", 0.5, 0}}},
                  {"nothing placeable", "x", "y", {{"only-nan", kNaN, kNaN}}}});
  EXPECT_EQ(xml_error(svg), "");
  const std::vector<Marker> all = markers(svg);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].label, "fine");
  EXPECT_EQ(all[1].label, "also-fine");
  const std::vector<Text> notes = texts_of_class(svg, "note");
  ASSERT_EQ(notes.size(), 2u);
  for (const std::string_view reason : {"nan-y (y = nan)", "infinite-x (x = inf)", "negative-y (y = -2)"})
    EXPECT_NE(notes[0].content.find(reason), std::string::npos) << reason;
  EXPECT_NE(notes[1].content.find("only-nan (x = nan, y = nan)"), std::string::npos);
  expect_no_nonfinite_attributes(svg);
}

TEST(SvgPlot, DegenerateRangesStayInsideThePlot) {
  const std::vector<std::vector<PlotPoint>> cases = {
      {},
      {{"single", 0.3, 7}},
      {{"a", 1, 1}, {"b", 1, 1}, {"c", 1, 1}},
      {{"all-zero-a", 0, 0}, {"all-zero-b", 0, 0}},
      {{"tiny", 1e-300, 5e-324}, {"huge", 1e300, 1.7e308}},
  };
  for (const std::vector<PlotPoint>& points : cases) {
    const std::string svg = scatter_svg("degenerate", {{"panel", "x", "y", points}});
    SCOPED_TRACE(svg);
    EXPECT_EQ(xml_error(svg), "");
    expect_no_nonfinite_attributes(svg);
    const std::vector<Marker> all = markers(svg);
    EXPECT_EQ(all.size(), points.size());
    const double width = document_dimension(svg, "width");
    const double height = document_dimension(svg, "height");
    for (const Marker& marker : all) {
      EXPECT_GT(marker.x, 0);
      EXPECT_LT(marker.x, width);
      EXPECT_GT(marker.y, 0);
      EXPECT_LT(marker.y, height);
    }
    EXPECT_LE(texts_of_class(svg, "x-tick").size(), 9u);
    EXPECT_LE(texts_of_class(svg, "y-tick").size(), 9u);
  }
  const std::vector<Marker> spread =
      markers(scatter_svg("", {{"", "", "", cases.back()}}));
  EXPECT_GT(spread[1].x - spread[0].x, 100);  // 600 decades still spread over the axis
  EXPECT_GT(spread[0].y - spread[1].y, 100);
}

TEST(SvgPlot, LabelsOfClusteredPointsDoNotOverlap) {
  std::vector<PlotPanel> panels = report_panels();
  panels.push_back({"identical points", "x", "y",
                    {{"p1", 1, 1}, {"p2", 1, 1}, {"p3", 1, 1}, {"p4", 1, 1}, {"p5", 1, 1}}});
  const std::string svg = scatter_svg("clusters", panels);
  const std::vector<Text> labels = texts_of_class(svg, "label");
  ASSERT_EQ(labels.size(), 17u);
  // A box no larger than the glyphs' (11 px type), so only a real overlap fails.
  struct Box { double left, top, right, bottom; };
  std::vector<Box> boxes;
  for (const Text& label : labels) {
    const double width = 5.0 * static_cast<double>(label.content.size());
    const bool from_end = label.attributes.find("text-anchor=\"end\"") != std::string::npos;
    const double left = from_end ? label.x - width : label.x;
    boxes.push_back({left, label.y - 8, left + width, label.y + 2});
  }
  for (std::size_t first = 0; first < boxes.size(); ++first) {
    for (std::size_t second = first + 1; second < boxes.size(); ++second) {
      const Box& a = boxes[first];
      const Box& b = boxes[second];
      EXPECT_FALSE(a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom)
          << labels[first].content << " overlaps " << labels[second].content;
    }
  }
}

TEST(SvgPlot, EachLabelKeepsItsColourAcrossPanels) {
  std::vector<PlotPanel> panels = report_panels();
  std::reverse(panels[1].points.begin(), panels[1].points.end());
  const std::vector<Marker> all = markers(scatter_svg("colours", panels));
  ASSERT_EQ(all.size(), 12u);
  std::set<std::string> colours;
  for (std::size_t index = 0; index < 6; ++index) {
    const Marker& in_second_panel = all[11 - index];
    EXPECT_EQ(all[index].label, in_second_panel.label);
    EXPECT_EQ(all[index].fill, in_second_panel.fill) << all[index].label;
    colours.insert(all[index].fill);
  }
  EXPECT_EQ(colours.size(), 6u);
}

TEST(SvgPlot, SameInputGivesTheSameBytes) {
  const std::string first = scatter_svg("again", report_panels());
  EXPECT_EQ(scatter_svg("again", report_panels()), first);
  // A locale with a decimal comma must not reach the numbers; skipped where
  // no such locale is installed.
  for (const char* name : {"de_DE.UTF-8", "fr_FR.UTF-8"}) {
    if (std::setlocale(LC_ALL, name) == nullptr) continue;
    const std::string localized = scatter_svg("again", report_panels());
    std::setlocale(LC_ALL, "C");
    EXPECT_EQ(localized, first) << name;
  }
}

}  // namespace
}  // namespace batchccd::cli
