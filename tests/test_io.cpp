// The readers of batchccd/io.hpp: exact rationals, query CSV, truth, PLY,
// candidate lists and scenes; every malformed input must give an InputError
// naming file, line and problem. The last tests read ../shared/data in place.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "batchccd/candidates.hpp"
#include "batchccd/io.hpp"
#include "shared_data.hpp"
#include "temporary_directory.hpp"

namespace batchccd {
namespace {

namespace fs = std::filesystem;

// ------------------------------------------------------------------ helpers

// A fresh directory per test, removed afterwards.
using IoTest = test_support::TemporaryDirectoryTest;

// Checks that read() throws an InputError for file at line whose message
// has the "FILE:LINE: " prefix and mentions problem.
template <class Read>
::testing::AssertionResult fails_with(Read&& read, const fs::path& file, long line, const std::string& problem) {
  try {
    read();
  } catch (const InputError& error) {
    const std::string message = error.what();
    const std::string prefix = file.string() + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": ";
    if (error.file() != file.string())
      return ::testing::AssertionFailure() << "file " << error.file() << " in: " << message;
    if (error.line() != line) return ::testing::AssertionFailure() << "line " << error.line() << " in: " << message;
    if (!message.starts_with(prefix))
      return ::testing::AssertionFailure() << "no prefix " << prefix << " in: " << message;
    if (message.find(problem) == std::string::npos)
      return ::testing::AssertionFailure() << "no '" << problem << "' in: " << message;
    return ::testing::AssertionSuccess();
  } catch (const std::exception& error) {
    return ::testing::AssertionFailure() << "not an InputError: " << error.what();
  }
  return ::testing::AssertionFailure() << "nothing thrown";
}

std::string rejection(std::string_view numerator, std::string_view denominator) {
  try {
    exact_double_from_rational(numerator, denominator);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "(accepted)";
}

// Decimal text of factor * 2^exponent, for numbers beyond 64 bits.
std::string decimal_power_of_two(int exponent, std::uint64_t factor = 1) {
  std::string digits = std::to_string(factor);  // most significant first
  for (int i = 0; i < exponent; ++i) {
    int carry = 0;
    for (auto it = digits.rbegin(); it != digits.rend(); ++it) {
      const int doubled = 2 * (*it - '0') + carry;
      *it = static_cast<char>('0' + doubled % 10);
      carry = doubled / 10;
    }
    if (carry > 0) digits.insert(digits.begin(), static_cast<char>('0' + carry));
  }
  return digits;
}

// Bytes of a binary PLY in a chosen byte order.
class PlyBytes {
 public:
  explicit PlyBytes(std::endian order) : order_(order) {}
  PlyBytes& text(std::string_view text) {
    bytes_ += text;
    return *this;
  }
  template <class T>
  PlyBytes& value(T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (order_ != std::endian::native) std::reverse(raw, raw + sizeof(T));
    bytes_.append(raw, sizeof(T));
    return *this;
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::endian order_;
  std::string bytes_;
};

std::string query_rows(int queries, bool with_truth, const std::string& separator = ",") {
  std::string text;
  for (int q = 0; q < queries; ++q)
    for (int row = 0; row < 8; ++row) {
      const int value = 8 * q + row;
      text += std::to_string(value) + separator + "2" + separator + std::to_string(-value) + separator + "4" +
              separator + "3" + separator + "1";
      if (with_truth) text += separator + std::to_string(q % 2);
      text += "\n";
    }
  return text;
}

// ------------------------------------------------------------------ InputError

TEST(InputErrorTest, MessageNamesFileLineAndProblem) {
  const InputError with_line("a/b.csv", 12, "bad thing");
  EXPECT_STREQ(with_line.what(), "a/b.csv:12: bad thing");
  EXPECT_EQ(with_line.file(), "a/b.csv");
  EXPECT_EQ(with_line.line(), 12);
  const InputError without_line("mesh.ply", 0, "no such file");
  EXPECT_STREQ(without_line.what(), "mesh.ply: no such file");
}

// ------------------------------------------------------------------ rationals

TEST(RationalTest, SmallFractionsAreExact) {
  EXPECT_EQ(exact_double_from_rational("1", "2"), 0.5);
  EXPECT_EQ(exact_double_from_rational("-3", "4"), -0.75);
  EXPECT_EQ(exact_double_from_rational("+5", "1"), 5.0);
  EXPECT_EQ(exact_double_from_rational("  7 ", " 8\t"), 0.875);
  EXPECT_EQ(exact_double_from_rational("0", "5"), 0.0);  // zero over anything positive
  EXPECT_EQ(exact_double_from_rational("6", "3"), 2.0);  // reduced first
  EXPECT_EQ(exact_double_from_rational("3", "6"), 0.5);
  EXPECT_EQ(exact_double_from_rational("-0", "1"), 0.0);
  EXPECT_EQ(exact_double_from_rational("6004799503160661", "36028797018963968"), std::ldexp(6004799503160661.0, -55));
}

TEST(RationalTest, NumbersBeyondSixtyFourBitsAreExact) {
  const std::string two_to_111 = decimal_power_of_two(111);
  EXPECT_EQ(two_to_111, "2596148429267413814265248164610048");
  EXPECT_EQ(exact_double_from_rational(two_to_111, two_to_111), 1.0);
  EXPECT_EQ(exact_double_from_rational("6004799503160661", two_to_111), std::ldexp(6004799503160661.0, -111));
  EXPECT_EQ(exact_double_from_rational("-" + decimal_power_of_two(100, 3), two_to_111), -3.0 / 2048.0);
  EXPECT_EQ(exact_double_from_rational(decimal_power_of_two(200, 5), "1"), std::ldexp(5.0, 200));
  // A huge fraction that reduces to a plain one.
  EXPECT_EQ(exact_double_from_rational(decimal_power_of_two(150, 9), decimal_power_of_two(150, 3)), 3.0);
}

TEST(RationalTest, TheEndsOfTheDoubleRangeAreExact) {
  const std::uint64_t largest_significand = (std::uint64_t{1} << 53) - 1;
  EXPECT_EQ(exact_double_from_rational(decimal_power_of_two(971, largest_significand), "1"),
            std::numeric_limits<double>::max());
  EXPECT_EQ(exact_double_from_rational("1", decimal_power_of_two(1074)), std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(exact_double_from_rational("-3", decimal_power_of_two(1074)),
            -3 * std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(exact_double_from_rational("1", decimal_power_of_two(1022)), std::numeric_limits<double>::min());
}

TEST(RationalTest, ValuesThatAreNotDoublesAreRejectedWithTheValue) {
  EXPECT_NE(rejection("1", "3").find("'1/3'"), std::string::npos) << rejection("1", "3");
  EXPECT_NE(rejection("1", "3").find("power of two"), std::string::npos);
  // 2^53 + 1 needs 54 significant bits.
  EXPECT_NE(rejection("9007199254740993", "1").find("54 significant bits"), std::string::npos)
      << rejection("9007199254740993", "1");
  EXPECT_NE(rejection("9007199254740993", "4").find("54 significant bits"), std::string::npos);
  EXPECT_NE(rejection("1", decimal_power_of_two(1075)).find("2^-1074"), std::string::npos);
  const std::uint64_t largest_significand = (std::uint64_t{1} << 53) - 1;
  EXPECT_NE(rejection(decimal_power_of_two(972, largest_significand), "1").find("range"), std::string::npos);
  EXPECT_NE(rejection(decimal_power_of_two(1024), "1").find("range"), std::string::npos);
}

TEST(RationalTest, BadDenominatorsAndGarbageAreRejected) {
  EXPECT_NE(rejection("1", "0").find("positive"), std::string::npos) << rejection("1", "0");
  EXPECT_NE(rejection("0", "0").find("positive"), std::string::npos);
  EXPECT_NE(rejection("1", "-2").find("positive"), std::string::npos);
  for (const char* garbage : {"", " ", "abc", "1.5", "1e3", "nan", "inf", "-inf", "0x10", "1 2", "--1", "+", "-"}) {
    EXPECT_NE(rejection(garbage, "1").find("not a decimal integer"), std::string::npos) << garbage;
    EXPECT_NE(rejection("1", garbage).find("not a decimal integer"), std::string::npos) << garbage;
  }
  EXPECT_NE(rejection("abc", "1").find("'abc'"), std::string::npos);
}

// ------------------------------------------------------------------ kind_from_path

TEST(KindFromPathTest, ComponentsAndWordsNameTheKind) {
  EXPECT_EQ(kind_from_path("scenes/armadillo/queries_vf.csv"), Kind::vertex_face);
  EXPECT_EQ(kind_from_path("scenes/armadillo/queries_ee.csv"), Kind::edge_edge);
  EXPECT_EQ(kind_from_path("vf.csv"), Kind::vertex_face);
  EXPECT_EQ(kind_from_path("ee.csv"), Kind::edge_edge);
  EXPECT_EQ(kind_from_path("data/spikes/edge-edge/data_0_0.csv"), Kind::edge_edge);
  EXPECT_EQ(kind_from_path("data/spikes/vertex-face/data_0_0.csv"), Kind::vertex_face);
  EXPECT_EQ(kind_from_path("vertex-face/run/ee/data.csv"), Kind::edge_edge);  // the last component wins
  EXPECT_EQ(kind_from_path("edge-edge/x/data_vf.csv"), Kind::vertex_face);
  EXPECT_EQ(kind_from_path("ee/data.csv"), Kind::edge_edge);
  EXPECT_EQ(kind_from_path("QUERIES-VF.CSV"), Kind::vertex_face);
  EXPECT_EQ(kind_from_path("data/vertex-edge/data_0_0.csv"), Kind::vertex_edge);
  EXPECT_EQ(kind_from_path("data/point_edge/q.csv"), Kind::vertex_edge);
  EXPECT_EQ(kind_from_path("rods/queries_ve.csv"), Kind::vertex_edge);
  EXPECT_EQ(kind_from_path("data/vertex-vertex/data_0_0.csv"), Kind::vertex_vertex);
  EXPECT_EQ(kind_from_path("Point-Point.csv"), Kind::vertex_vertex);
  EXPECT_EQ(kind_from_path("particles/vv.csv"), Kind::vertex_vertex);
  EXPECT_EQ(kind_from_path("vv/point-edge.csv"), Kind::vertex_edge);      // the last component wins
  EXPECT_EQ(kind_from_path("vertex-edge-vv.csv"), Kind::vertex_vertex);  // and in it the last mention
  EXPECT_EQ(kind_from_path("point-face.csv"), std::nullopt);
  EXPECT_EQ(kind_from_path("vertex--edge.csv"), std::nullopt);  // two separators: no pair
  EXPECT_EQ(kind_from_path("eve/vvs/data.csv"), std::nullopt);
  EXPECT_EQ(kind_from_path("free/veef/data.csv"), std::nullopt);  // "ee" inside a word is no word
  EXPECT_EQ(kind_from_path("vertex-faces.csv"), std::nullopt);
  EXPECT_EQ(kind_from_path("data.csv"), std::nullopt);
  EXPECT_EQ(kind_from_path(""), std::nullopt);
}

// ------------------------------------------------------------------ query CSV

TEST_F(IoTest, QueryCsvWithTruthKeepsRowOrder) {
  const fs::path path = write("q_vf.csv", query_rows(2, true));
  const QueryFile file = read_query_csv(path, Kind::vertex_face);
  EXPECT_EQ(file.path, path.string());
  EXPECT_EQ(file.kind, Kind::vertex_face);
  ASSERT_EQ(file.queries.size(), 2u);
  ASSERT_TRUE(file.truth.has_value());
  EXPECT_EQ(*file.truth, (std::vector<bool>{false, true}));
  for (int q = 0; q < 2; ++q)
    for (int row = 0; row < 8; ++row) {
      const double value = 8 * q + row;
      EXPECT_EQ(file.queries[q].points[row], Vec3(value / 2, -value / 4, 3.0)) << q << " " << row;
    }
}

TEST_F(IoTest, QueryCsvWithoutTruthSpacesAndCrlf) {
  std::string text = query_rows(3, false, ", ");
  std::string crlf;
  for (const char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  const fs::path path = write("q.csv", crlf + "\r\n");  // and a trailing empty line
  const QueryFile file = read_query_csv(path, Kind::edge_edge);
  EXPECT_EQ(file.kind, Kind::edge_edge);
  ASSERT_EQ(file.queries.size(), 3u);
  EXPECT_FALSE(file.truth.has_value());
  EXPECT_EQ(file.queries[2].points[7], Vec3(23.0 / 2, -23.0 / 4, 3.0));
}

TEST_F(IoTest, QueryCsvSevenColumnsWithSpaces) {
  const fs::path path = write("q.csv", query_rows(1, true, " , "));
  const QueryFile file = read_query_csv(path, Kind::vertex_face);
  ASSERT_EQ(file.queries.size(), 1u);
  EXPECT_EQ(*file.truth, std::vector<bool>{false});
}

TEST_F(IoTest, EmptyQueryCsvHasNoQueries) {
  const fs::path path = write("q.csv", "");
  const QueryFile file = read_query_csv(path, Kind::vertex_face);
  EXPECT_TRUE(file.queries.empty());
}

TEST_F(IoTest, QueryCsvMalformedRowsNameFileLineAndProblem) {
  auto with_line = [](std::string text, int line_index, const std::string& replacement) {
    std::vector<std::string> lines;
    std::size_t start = 0;
    while (start < text.size()) {
      const std::size_t end = text.find('\n', start);
      lines.push_back(text.substr(start, end - start));
      start = end + 1;
    }
    lines[static_cast<std::size_t>(line_index - 1)] = replacement;
    std::string joined;
    for (const std::string& line : lines) joined += line + "\n";
    return joined;
  };
  const std::string good = query_rows(2, true);
  struct Case {
    int line;
    std::string row;
    std::string problem;
  };
  const std::vector<Case> cases{
      {3, "1,2,3,4,5,6", "expected 7 columns"},
      {4, "1,2,3,4,5,6,0,9", "expected 7 columns"},
      {1, "1,2,3,4,5", "expected 6 or 7 columns"},
      {5, "1,2,x,4,5,6,0", "column 3"},
      {5, "1,2,x,4,5,6,0", "'x'"},
      {6, "nan,1,0,1,0,1,0", "column 1"},
      {7, "0,1,inf,1,0,1,0", "column 3"},
      {2, "1,3,0,1,0,1,0", "column 1: '1/3' is not a double"},
      {2, "0,1,0,1,1,0,0", "column 5"},
      {8, "1,2,3,4,5,8,1", "truth 1 differs"},
      {9, "1,2,3,4,5,8,2", "truth must be 0 or 1"},
      {10, "", "empty line"},
      {11, "1;2;3;4;5;6;0", "expected 7 columns"},
  };
  for (const Case& bad : cases) {
    const fs::path path = write("bad.csv", with_line(good, bad.line, bad.row));
    EXPECT_TRUE(fails_with([&] { read_query_csv(path, Kind::vertex_face); }, path, bad.line, bad.problem)) << bad.row;
  }
}

TEST_F(IoTest, QueryCsvRowCountNotAMultipleOfEight) {
  const std::string nine_rows = query_rows(1, true) + "1,2,3,4,5,6,0\n";
  const fs::path path = write("q.csv", nine_rows + "\n");
  EXPECT_TRUE(fails_with([&] { read_query_csv(path, Kind::vertex_face); }, path, 9, "not a multiple of 8"));
  const fs::path short_path = write("short.csv", "1,2,3,4,5,6\n1,2,3,4,5,6\n");
  EXPECT_TRUE(fails_with([&] { read_query_csv(short_path, Kind::edge_edge); }, short_path, 2,
                         "the last query has 2 of its 8 rows"));
}

// Rows of a point-kind query file: point k of query q is (8q + k, -(8q + k), 1) / 4.
std::string point_rows(int queries, int rows_per_query) {
  std::string text;
  for (int q = 0; q < queries; ++q)
    for (int row = 0; row < rows_per_query; ++row) {
      const int value = 8 * q + row;
      text += std::to_string(value) + ",4," + std::to_string(-value) + ",4,1,4," + std::to_string(q % 2) + "\n";
    }
  return text;
}

Vec3 point_of_row(int q, int row) { return Vec3(8 * q + row, -(8 * q + row), 1) / 4; }

TEST_F(IoTest, VertexEdgeQueriesHaveSixRowsInQueryLayout) {
  const fs::path path = write("ve.csv", point_rows(2, 6));
  const QueryFile file = read_query_csv(path, Kind::vertex_edge);
  EXPECT_EQ(file.kind, Kind::vertex_edge);
  ASSERT_EQ(file.queries.size(), 2u);
  EXPECT_EQ(*file.truth, (std::vector<bool>{false, true}));
  for (int q = 0; q < 2; ++q) {
    // p, e0, e1 at t0 (rows 0-2), at t1 (rows 3-5); the point is a zero-length edge.
    const std::array<int, 8> rows{0, 0, 1, 2, 3, 3, 4, 5};
    for (int k = 0; k < 8; ++k) EXPECT_EQ(file.queries[q].points[k], point_of_row(q, rows[k])) << q << " " << k;
    const std::array<Vec3, 3> t0{point_of_row(q, 0), point_of_row(q, 1), point_of_row(q, 2)};
    const std::array<Vec3, 3> t1{point_of_row(q, 3), point_of_row(q, 4), point_of_row(q, 5)};
    EXPECT_EQ(file.queries[q].points, make_query(Kind::vertex_edge, t0, t1).points);
  }
}

TEST_F(IoTest, VertexVertexQueriesHaveFourRowsInQueryLayout) {
  const fs::path path = write("vv.csv", point_rows(3, 4));
  const QueryFile file = read_query_csv(path, Kind::vertex_vertex);
  ASSERT_EQ(file.queries.size(), 3u);
  EXPECT_EQ(*file.truth, (std::vector<bool>{false, true, false}));
  const std::array<int, 8> rows{0, 0, 1, 1, 2, 2, 3, 3};  // p, q at t0, then at t1
  for (int q = 0; q < 3; ++q)
    for (int k = 0; k < 8; ++k) EXPECT_EQ(file.queries[q].points[k], point_of_row(q, rows[k])) << q << " " << k;
}

TEST_F(IoTest, PointKindRowCountsAndTruthAreCheckedPerQuery) {
  // 8 rows are one vf query but one ve query and 2 of the next.
  const fs::path eight = write("eight.csv", point_rows(1, 8));
  EXPECT_EQ(read_query_csv(eight, Kind::vertex_face).queries.size(), 1u);
  EXPECT_EQ(read_query_csv(eight, Kind::vertex_vertex).queries.size(), 2u);
  EXPECT_TRUE(fails_with([&] { read_query_csv(eight, Kind::vertex_edge); }, eight, 8,
                         "row count 8 is not a multiple of 6 (ve queries have 6 rows; the last query has 2 of its "
                         "6 rows)"));
  const fs::path six = write("six.csv", point_rows(1, 6));
  EXPECT_TRUE(fails_with([&] { read_query_csv(six, Kind::vertex_vertex); }, six, 6,
                         "not a multiple of 4 (vv queries have 4 rows; the last query has 2 of its 4 rows)"));
  EXPECT_TRUE(fails_with([&] { read_query_csv(six, Kind::edge_edge); }, six, 6, "not a multiple of 8"));
  // The truth must agree on a query's rows: line 5 starts the second vv query, line 4 does not.
  const std::string rows = point_rows(2, 4);
  EXPECT_EQ(*read_query_csv(write("two.csv", rows), Kind::vertex_vertex).truth, (std::vector<bool>{false, true}));
  const std::size_t line_4 = rows.find("3,4,-3,4,1,4,0\n");
  ASSERT_NE(line_4, std::string::npos);
  std::string split_text = rows;
  split_text[line_4 + 13] = '1';
  const fs::path split = write("split.csv", split_text);
  EXPECT_TRUE(fails_with([&] { read_query_csv(split, Kind::vertex_vertex); }, split, 4,
                         "column 7: truth 1 differs from the truth 0 of the earlier rows"));
  const fs::path bad_value = write("bad.csv", point_rows(1, 5) + "1,3,0,1,0,1,0\n");
  EXPECT_TRUE(fails_with([&] { read_query_csv(bad_value, Kind::vertex_edge); }, bad_value, 6,
                         "column 1: '1/3' is not a double"));
}

TEST_F(IoTest, MissingFilesAreNamed) {
  const fs::path missing = directory() / "missing.csv";
  EXPECT_TRUE(fails_with([&] { read_query_csv(missing, Kind::vertex_face); }, missing, 0, "no such file"));
  EXPECT_TRUE(fails_with([&] { read_truth(missing); }, missing, 0, "no such file"));
  EXPECT_TRUE(fails_with([&] { read_ply(missing); }, missing, 0, "no such file"));
  EXPECT_TRUE(fails_with([&] { read_vertex_face_pairs(missing); }, missing, 0, "no such file"));
  EXPECT_TRUE(fails_with([&] { read_edge_edge_pairs(missing); }, missing, 0, "no such file"));
  EXPECT_TRUE(fails_with([&] { read_ply(directory()); }, directory(), 0, "directory"));
}

// ------------------------------------------------------------------ truth

TEST_F(IoTest, TruthAsJsonArray) {
  EXPECT_EQ(read_truth(write("a.json", "[true, false,\n  1,0 ,true]\n")),
            (std::vector<bool>{true, false, true, false, true}));
  EXPECT_EQ(read_truth(write("b.json", "\n  [\n]\n")), std::vector<bool>{});
  EXPECT_EQ(read_truth(write("c.json", "[false]")), std::vector<bool>{false});
  EXPECT_EQ(read_truth(write("d.json", "[\r\n  true,\r\n  false\r\n]\r\n")), (std::vector<bool>{true, false}));
}

TEST_F(IoTest, TruthAsLines) {
  EXPECT_EQ(read_truth(write("a.txt", "1\n0\n1\n")), (std::vector<bool>{true, false, true}));
  EXPECT_EQ(read_truth(write("b.txt", "0\r\n1\r\n\r\n")), (std::vector<bool>{false, true}));
  EXPECT_EQ(read_truth(write("c.txt", " 1 \n0")), (std::vector<bool>{true, false}));
  EXPECT_EQ(read_truth(write("d.txt", "")), std::vector<bool>{});
}

TEST_F(IoTest, MalformedTruthNamesTheLine) {
  struct Case {
    std::string text;
    long line;
    std::string problem;
  };
  const std::vector<Case> cases{
      {"[true,\n maybe]", 2, "'maybe'"},
      {"[true,\nfalse", 2, "unexpected end of file"},
      {"[true,\n]", 2, "found ']'"},
      {"[true] x", 1, "after the closing"},
      {"[true false]", 1, "expected ','"},
      {"[2]", 1, "'2'"},
      {"[\"true\"]", 1, "found '\"'"},
      {"1\n2\n", 2, "expected 0 or 1, found '2'"},
      {"1\n\n0\n", 2, "found ''"},
      {"yes\n", 1, "'yes'"},
      {"1,0\n", 1, "'1,0'"},
      {"true\n", 1, "'true'"},
  };
  for (const Case& bad : cases) {
    const fs::path path = write("truth.txt", bad.text);
    EXPECT_TRUE(fails_with([&] { read_truth(path); }, path, bad.line, bad.problem)) << bad.text;
  }
}

// ------------------------------------------------------------------ PLY

// Two triangles over four vertices, shared by the PLY tests.
const Eigen::MatrixXd expected_vertices =
    (Eigen::MatrixXd(4, 3) << 0, 0, 0, 1.5, 0, 0, 0, -2.25, 0, 0.5, 0.5, 1).finished();
const Eigen::MatrixXi expected_faces = (Eigen::MatrixXi(2, 3) << 0, 1, 2, 3, 2, 1).finished();

TEST_F(IoTest, AsciiPlyWithExtraPropertiesAndElements) {
  const fs::path path = write("mesh.ply",
                              "ply\n"
                              "format ascii 1.0\n"
                              "comment made by hand\n"
                              "obj_info anything\n"
                              "element camera 1\n"
                              "property float view\n"
                              "property list uchar int frames\n"
                              "element vertex 4\n"
                              "property float nx\n"
                              "property double x\n"
                              "property float y\n"
                              "property uchar red\n"
                              "property double z\n"
                              "element edge 2\n"
                              "property list uint8 int32 vertex_pair\n"
                              "element face 2\n"
                              "property uchar flags\n"
                              "property list uchar int vertex_indices\n"
                              "end_header\n"
                              "0.5 3 1 2 3\n"
                              "0 0 0 255 0\n"
                              "1 1.5 0 0 0\n"
                              "2 0 -2.25 10 0e0\n"
                              "3 0.5 5e-1 7 +1\n"
                              "2 0 1\n"
                              "\n"
                              "2 1 2\n"
                              "7 3 0 1 2\n"
                              "8 3 3 2 1\n");
  const PlyMesh mesh = read_ply(path);
  EXPECT_EQ(mesh.vertices, expected_vertices);
  EXPECT_EQ(mesh.faces, expected_faces);
}

template <class Coordinate>
std::string binary_ply(std::endian order, const std::string& coordinate_type) {
  const std::string format = order == std::endian::little ? "binary_little_endian" : "binary_big_endian";
  PlyBytes ply(order);
  ply.text("ply\r\nformat " + format + " 1.0\n")
      .text("element face 2\nproperty list int uint16 vertex_index\nproperty int16 tag\n")
      .text("element vertex 4\nproperty " + coordinate_type + " x\nproperty " + coordinate_type + " y\n")
      .text("property float32 nx\nproperty uint8 red\nproperty " + coordinate_type + " z\n")
      .text("element material 2\nproperty list uint32 float64 weights\nproperty char kind\n")
      .text("end_header\n");
  for (int f = 0; f < 2; ++f) {
    ply.value<std::int32_t>(3);
    for (int corner = 0; corner < 3; ++corner) ply.value(static_cast<std::uint16_t>(expected_faces(f, corner)));
    ply.value<std::int16_t>(-7);
  }
  for (int v = 0; v < 4; ++v) {
    ply.value(static_cast<Coordinate>(expected_vertices(v, 0))).value(static_cast<Coordinate>(expected_vertices(v, 1)));
    ply.value(0.25f).value<std::uint8_t>(200).value(static_cast<Coordinate>(expected_vertices(v, 2)));
  }
  ply.value<std::uint32_t>(2).value(1.0).value(2.0).value<std::int8_t>(-1);
  ply.value<std::uint32_t>(0).value<std::int8_t>(1);
  return ply.bytes();
}

TEST_F(IoTest, BinaryPlyInBothByteOrdersFloatAndDouble) {
  const std::vector<std::pair<std::string, std::string>> files{
      {"le_double.ply", binary_ply<double>(std::endian::little, "double")},
      {"be_double.ply", binary_ply<double>(std::endian::big, "float64")},
      {"le_float.ply", binary_ply<float>(std::endian::little, "float")},
      {"be_float.ply", binary_ply<float>(std::endian::big, "float32")},
      {"be_int.ply", binary_ply<std::int32_t>(std::endian::big, "int")},  // exact for the integers only
  };
  for (const auto& [name, bytes] : files) {
    const PlyMesh mesh = read_ply(write(name, bytes));
    EXPECT_EQ(mesh.faces, expected_faces) << name;
    if (name == "be_int.ply") {
      EXPECT_EQ(mesh.vertices, expected_vertices.cast<int>().cast<double>()) << name;
    } else {
      EXPECT_EQ(mesh.vertices, expected_vertices) << name;
    }
  }
}

TEST_F(IoTest, PlyWithoutFacesHasAnEmptyFaceMatrix) {
  const PlyMesh mesh = read_ply(write("points.ply",
                                      "ply\nformat ascii 1.0\nelement vertex 1\nproperty int x\n"
                                      "property short y\nproperty ushort z\nend_header\n-1 -2 3\n"));
  EXPECT_EQ(mesh.vertices, Eigen::RowVector3d(-1, -2, 3));
  EXPECT_EQ(mesh.faces.rows(), 0);
  EXPECT_EQ(mesh.faces.cols(), 3);
}

const std::string ascii_header =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";

TEST_F(IoTest, MalformedAsciiPlyNamesTheLine) {
  struct Case {
    std::string body;
    long line;
    std::string problem;
  };
  const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
  const std::vector<Case> cases{
      {vertices + "4 0 1 2 0\n", 13, "face 0: a face with 4 vertices: only triangles are supported"},
      {vertices + "3 0 1 3\n", 13, "face 0: vertex index 3 is out of range (the mesh has 3 vertices)"},
      {vertices + "3 0 -1 2\n", 13, "vertex index -1 is out of range"},
      {vertices + "3 0 1\n", 13, "expected more than 3 values"},
      {vertices + "3 0 1 2 5\n", 13, "expected 4 values on this line, found 5"},
      {vertices + "-3 0 1 2\n", 13, "out of the range of its property type"},
      {vertices + "3 0 1.5 2\n", 13, "expected an integer, found '1.5'"},
      {"0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", 11, "vertex 1: coordinate y is not finite"},
      {"0 0 0\n1 0 0\n0 1 inf\n3 0 1 2\n", 12, "vertex 2: coordinate z is not finite"},
      {"0 0 0\n1 0 zero\n0 1 0\n3 0 1 2\n", 11, "expected a number, found 'zero'"},
      {"0 0 0\n1 0 1e999\n0 1 0\n3 0 1 2\n", 11, "out of the double range"},
      {"0 0 0\n1 0 0\n", 11, "truncated"},
      {vertices, 12, "face 0: truncated"},
  };
  for (const Case& bad : cases) {
    const fs::path path = write("bad.ply", ascii_header + bad.body);
    EXPECT_TRUE(fails_with([&] { read_ply(path); }, path, bad.line, bad.problem)) << bad.body;
  }
}

TEST_F(IoTest, MalformedPlyHeadersNameTheLine) {
  struct Case {
    std::string text;
    long line;
    std::string problem;
  };
  const std::string vertex = "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n";
  const std::vector<Case> cases{
      {"", 0, "not a PLY file"},
      {"PLY\n", 1, "not a PLY file"},
      {"ply\nformat ascii 1.0\n" + vertex, 0, "no end_header"},
      {"ply\nformat binary_middle_endian 1.0\n" + vertex + "end_header\n", 2, "unknown format 'binary_middle_endian'"},
      {"ply\nformat ascii 2.0\n" + vertex + "end_header\n", 2, "unsupported PLY version '2.0'"},
      {"ply\n" + vertex + "end_header\n", 6, "no format line"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty int128 x\nend_header\n", 4, "unknown property type 'int128'"},
      {"ply\nformat ascii 1.0\nproperty float x\nend_header\n", 3, "before any element"},
      {"ply\nformat ascii 1.0\nelement vertex -1\nend_header\n", 3, "element count '-1'"},
      {"ply\nformat ascii 1.0\nelement vertex\nend_header\n", 3, "expected 'element NAME COUNT'"},
      {"ply\nformat ascii 1.0\nvertices 3\nend_header\n", 3, "unknown header keyword 'vertices'"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n", 3,
       "no property 'z'"},
      {"ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n", 0,
       "no vertex element"},
      {"ply\nformat ascii 1.0\n" + vertex + "element face 1\nproperty list uchar int corners\nend_header\n", 7,
       "no vertex_indices"},
      {"ply\nformat ascii 1.0\n" + vertex + "element face 1\nproperty list uchar float vertex_indices\nend_header\n", 7,
       "must hold integers"},
      {"ply\nformat ascii 1.0\n" + vertex + "element face 1\nproperty list float int vertex_indices\nend_header\n", 8,
       "count type must be an integer"},
      {"ply\nformat ascii 1.0\n" + vertex + "property double x\nend_header\n", 7, "a second property named 'x'"},
      {"ply\nformat ascii 1.0\n" + vertex + vertex + "end_header\n", 7, "a second element named 'vertex'"},
      {"ply\nformat ascii 1.0\nelement vertex 3000000000\nproperty float x\nproperty float y\nproperty float z\n"
       "end_header\n",
       3, "at most 2147483647"},
  };
  for (const Case& bad : cases) {
    const fs::path path = write("bad.ply", bad.text);
    EXPECT_TRUE(fails_with([&] { read_ply(path); }, path, bad.line, bad.problem)) << bad.text;
  }
}

TEST_F(IoTest, MalformedBinaryPlyNamesTheFile) {
  const std::string good = binary_ply<double>(std::endian::little, "double");
  const std::string header_end = "end_header\n";
  const std::size_t body = good.find(header_end) + header_end.size();
  auto with_body_bytes = [&](std::size_t offset, std::string bytes) {
    std::string changed = good;
    changed.replace(body + offset, bytes.size(), bytes);
    return changed;
  };
  const std::string quad_count{'\4', '\0', '\0', '\0'};
  const std::string index_nine{'\x09', '\0'};
  const std::string huge_list{'\xff', '\xff', '\xff', '\x0f'};
  std::string nan_bytes(8, '\0');
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::memcpy(nan_bytes.data(), &nan, 8);
  const std::size_t face_size = 4 + 3 * 2 + 2;
  const std::size_t vertex_size = 8 + 8 + 4 + 1 + 8;
  struct Case {
    std::string bytes;
    std::string problem;
  };
  const std::vector<Case> cases{
      {good.substr(0, good.size() - 1), "material 1: truncated file"},
      {good.substr(0, body + 20), "truncated file: the header declares 4 vertex entries"},
      {with_body_bytes(face_size, quad_count), "face 1: a face with 4 vertices: only triangles"},
      {with_body_bytes(4 + 2, index_nine), "face 0: vertex index 9 is out of range"},
      {with_body_bytes(2 * face_size + vertex_size + 8, nan_bytes), "vertex 1: coordinate y is not finite"},
      {with_body_bytes(2 * face_size + 4 * vertex_size, huge_list), "material 0: truncated file"},
  };
  for (const Case& bad : cases) {
    const fs::path path = write("bad.ply", bad.bytes);
    EXPECT_TRUE(fails_with([&] { read_ply(path); }, path, 0, bad.problem)) << bad.problem;
  }
}

TEST_F(IoTest, AbsurdDeclaredCountsFailBeforeAllocating) {
  const fs::path path = write("huge.ply",
                              "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\nproperty double x\n"
                              "property double y\nproperty double z\nend_header\n0123456789");
  EXPECT_TRUE(fails_with([&] { read_ply(path); }, path, 0, "more than the 10 bytes"));
  const fs::path skipped = write("huge_other.ply",
                                 "ply\nformat binary_big_endian 1.0\nelement junk 18446744073709551615\n"
                                 "property uchar a\nelement vertex 0\nproperty float x\nproperty float y\n"
                                 "property float z\nend_header\n");
  EXPECT_TRUE(fails_with([&] { read_ply(skipped); }, skipped, 0, "truncated file"));
  const fs::path overflow = write("overflow.ply", "ply\nformat ascii 1.0\nelement vertex 99999999999999999999\n");
  EXPECT_TRUE(fails_with([&] { read_ply(overflow); }, overflow, 3, "element count"));
}

// Every prefix and many corrupted copies of a valid file: an InputError or a
// mesh, never a crash or another exception.
TEST_F(IoTest, CorruptedPlyNeverCrashes) {
  const std::vector<std::string> originals{binary_ply<double>(std::endian::little, "double"),
                                           binary_ply<float>(std::endian::big, "float"),
                                           ascii_header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"};
  std::mt19937 random(12345);
  const fs::path path = directory() / "corrupt.ply";
  auto survives = [&](const std::string& bytes) {
    write("corrupt.ply", bytes);
    try {
      const PlyMesh mesh = read_ply(path);
      for (Eigen::Index i = 0; i < mesh.faces.size(); ++i)
        if (mesh.faces(i) < 0 || mesh.faces(i) >= mesh.vertices.rows()) return false;
      return mesh.vertices.allFinite();
    } catch (const InputError&) {
      return true;
    }
  };
  for (const std::string& original : originals) {
    for (std::size_t length = 0; length < original.size(); ++length)
      EXPECT_TRUE(survives(original.substr(0, length))) << length;
    for (int trial = 0; trial < 300; ++trial) {
      std::string bytes = original;
      const int flips = 1 + static_cast<int>(random() % 4);
      for (int flip = 0; flip < flips; ++flip) bytes[random() % bytes.size()] = static_cast<char>(random() % 256);
      EXPECT_TRUE(survives(bytes)) << trial;
    }
  }
}

// ------------------------------------------------------------------ candidate lists

TEST_F(IoTest, CandidateListsReadWithOptionalSpaces) {
  EXPECT_EQ(read_vertex_face_pairs(write("vf.csv", "1,2\n3, 4\r\n 5 ,6\n\n")),
            (std::vector<std::array<int, 2>>{{1, 2}, {3, 4}, {5, 6}}));
  EXPECT_EQ(read_edge_edge_pairs(write("ee.csv", "0,1,2,3\n2147483647, 4,5 ,6")),
            (std::vector<std::array<int, 4>>{{0, 1, 2, 3}, {2147483647, 4, 5, 6}}));
  EXPECT_TRUE(read_vertex_face_pairs(write("empty.csv", "")).empty());
  EXPECT_EQ(read_vertex_edge_triples(write("ve.csv", "0,1,2\n 7 , 8,9\r\n")),
            (std::vector<std::array<int, 3>>{{0, 1, 2}, {7, 8, 9}}));
  EXPECT_EQ(read_vertex_vertex_pairs(write("vv.csv", "4,5\n5,5\n")),
            (std::vector<std::array<int, 2>>{{4, 5}, {5, 5}}));
}

TEST_F(IoTest, MalformedPointCandidateListsNameTheLine) {
  const fs::path ve = write("ve.csv", "0,1,2\n0,1\n");
  EXPECT_TRUE(fails_with([&] { read_vertex_edge_triples(ve); }, ve, 2, "expected 3 comma-separated ids, found 2"));
  write("ve.csv", "0,1,2\n0,1,2\n0,1,-2\n");
  EXPECT_TRUE(fails_with([&] { read_vertex_edge_triples(ve); }, ve, 3, "column 3: negative id '-2'"));
  const fs::path vv = write("vv.csv", "0,1\n0,1,2\n");
  EXPECT_TRUE(fails_with([&] { read_vertex_vertex_pairs(vv); }, vv, 2, "expected 2 comma-separated ids, found 3"));
  write("vv.csv", "0,1\n\n1,0\n");
  EXPECT_TRUE(fails_with([&] { read_vertex_vertex_pairs(vv); }, vv, 2, "empty line"));
}

TEST_F(IoTest, MalformedCandidateListsNameTheLine) {
  struct Case {
    std::string text;
    bool edge_edge;
    long line;
    std::string problem;
  };
  const std::vector<Case> cases{
      {"1,2\n1,2,3\n", false, 2, "expected 2 comma-separated ids, found 3"},
      {"1\n", false, 1, "expected 2 comma-separated ids, found 1"},
      {"1,2,3,4\n1,2,3\n", true, 2, "expected 4 comma-separated ids, found 3"},
      {"1,2\n3,x\n", false, 2, "column 2: expected a non-negative integer, found 'x'"},
      {"1,2\n3,1.5\n", false, 2, "found '1.5'"},
      {"1,2\n\n3,4\n", false, 2, "empty line"},
      {"1,-2\n", false, 1, "column 2: negative id '-2'"},
      {"1,2,3,4\n1,2,3,99999999999\n", true, 2, "column 4: id '99999999999' is too large"},
      {"1,2,3,4\n1,2,3,2147483648\n", true, 2, "too large"},
      {"1,\n", false, 1, "found ''"},
  };
  for (const Case& bad : cases) {
    const fs::path path = write("ids.csv", bad.text);
    if (bad.edge_edge) {
      EXPECT_TRUE(fails_with([&] { read_edge_edge_pairs(path); }, path, bad.line, bad.problem)) << bad.text;
    } else {
      EXPECT_TRUE(fails_with([&] { read_vertex_face_pairs(path); }, path, bad.line, bad.problem)) << bad.text;
    }
  }
}

// A control byte inside a bad field (a NUL, an escape sequence, a bell) is
// quoted as \xHH: a NUL would end what() before the rest of the message,
// the others would reach the user's terminal.
TEST_F(IoTest, ControlBytesInABadFieldAreEscaped) {
  using namespace std::string_literals;
  const auto expect_escaped = [&](auto read, const fs::path& path, long line, const std::string& problem) {
    EXPECT_TRUE(fails_with(read, path, line, problem));
    try {
      read();
    } catch (const InputError& error) {
      const std::string_view message = error.what();
      EXPECT_TRUE(message.ends_with(problem)) << message;
      EXPECT_TRUE(std::none_of(message.begin(), message.end(),
                               [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
          << message;
    }
  };
  const fs::path ids = write("ids.csv", "1,2\n3,4\0x\n"s);
  expect_escaped([&] { read_vertex_face_pairs(ids); }, ids, 2,
                 R"(column 2: expected a non-negative integer, found '4\x00x')");
  write("ids.csv", "1,2,3,4\n1,2,\x1b[31m3\x7f,4\n");
  expect_escaped([&] { read_edge_edge_pairs(ids); }, ids, 2,
                 R"(column 3: expected a non-negative integer, found '\x1b[31m3\x7f')");
  const fs::path queries = write("q.csv", query_rows(1, true).replace(0, 1, "0\0"s));
  expect_escaped([&] { read_query_csv(queries, Kind::vertex_face); }, queries, 1,
                 R"(column 1: numerator '0\x00' is not a decimal integer)");
  const fs::path truth = write("truth.txt", "0\n1\n\a\n");
  expect_escaped([&] { read_truth(truth); }, truth, 3, R"(expected 0 or 1, found '\x07')");
}

// ------------------------------------------------------------------ scenes

// t0.ply and t1.ply of a 4-vertex, 2-face mesh; t1 moves every vertex up by 1.
void write_scene_meshes(const fs::path& scene, int t1_vertices = 4) {
  std::string t0 =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\n"
      "property double z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
  std::string t1 = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(t1_vertices) +
                   "\nproperty double x\nproperty double y\nproperty double z\nend_header\n";
  for (int v = 0; v < 4; ++v) {
    t0 += std::to_string(v) + " 0 0\n";
    if (v < t1_vertices) t1 += std::to_string(v) + " 0 1\n";
  }
  t0 += "3 0 1 2\n3 3 2 1\n";
  test_support::write_file(scene / "t0.ply", t0);
  test_support::write_file(scene / "t1.ply", t1);
}

TEST_F(IoTest, SceneReadsMeshesCandidatesAndTruth) {
  write_scene_meshes(directory());
  write("vf.csv", "0,1\n3,0\n");
  write("ee.csv", "0,1,2,3\n");
  write("vf_truth.txt", "1\n0\n");
  write("ee_truth.txt", "[true]");
  EXPECT_TRUE(is_scene_directory(directory()));
  const Scene scene = read_scene(directory());
  EXPECT_EQ(scene.path, directory().string());
  ASSERT_EQ(scene.positions_t0.rows(), 4);
  EXPECT_EQ(scene.positions_t0.row(3), Eigen::RowVector3d(3, 0, 0));
  EXPECT_EQ(scene.positions_t1.row(3), Eigen::RowVector3d(3, 0, 1));
  EXPECT_EQ(scene.faces, expected_faces);
  EXPECT_EQ(scene.candidates.vertex_face, (std::vector<std::array<int, 2>>{{0, 1}, {3, 0}}));
  EXPECT_EQ(scene.candidates.edge_edge, (std::vector<std::array<int, 4>>{{0, 1, 2, 3}}));
  EXPECT_EQ(scene.vertex_face_truth, (std::vector<bool>{true, false}));
  EXPECT_EQ(scene.edge_edge_truth, std::vector<bool>{true});
}

TEST_F(IoTest, SceneWithoutCandidateFilesHasEmptyLists) {
  write_scene_meshes(directory());
  const Scene scene = read_scene(directory());
  EXPECT_TRUE(scene.candidates.vertex_face.empty());
  EXPECT_TRUE(scene.candidates.edge_edge.empty());
  EXPECT_TRUE(scene.candidates.vertex_edge.empty());
  EXPECT_TRUE(scene.candidates.vertex_vertex.empty());
  EXPECT_FALSE(scene.vertex_face_truth.has_value());
  EXPECT_FALSE(scene.edge_edge_truth.has_value());
  EXPECT_FALSE(scene.vertex_edge_truth.has_value());
  EXPECT_FALSE(scene.vertex_vertex_truth.has_value());
}

TEST_F(IoTest, SceneReadsPointEdgeAndPointPointCandidates) {
  write_scene_meshes(directory());
  write("ve.csv", "0,1,2\n3,2,1\n");
  write("vv.csv", "0,3\n");
  write("ve_truth.txt", "0\n1\n");
  write("vv_truth.txt", "[false]");
  const Scene scene = read_scene(directory());
  EXPECT_EQ(scene.candidates.vertex_edge, (std::vector<std::array<int, 3>>{{0, 1, 2}, {3, 2, 1}}));
  EXPECT_EQ(scene.candidates.vertex_vertex, (std::vector<std::array<int, 2>>{{0, 3}}));
  EXPECT_EQ(scene.vertex_edge_truth, (std::vector<bool>{false, true}));
  EXPECT_EQ(scene.vertex_vertex_truth, std::vector<bool>{false});
  EXPECT_TRUE(scene.candidates.vertex_face.empty());
  EXPECT_FALSE(scene.edge_edge_truth.has_value());
}

TEST_F(IoTest, ScenePointCandidatesAreCheckedAgainstTheMesh) {
  write_scene_meshes(directory());
  const fs::path ve = write("ve.csv", "0,1,2\n3,4,1\n");
  EXPECT_TRUE(
      fails_with([&] { read_scene(directory()); }, ve, 2, "vertex id 4 is out of range (the mesh has 4 vertices)"));
  write("ve.csv", "0,1,2\n0,1\n");
  EXPECT_TRUE(fails_with([&] { read_scene(directory()); }, ve, 2, "expected 3 comma-separated ids"));
  write("ve.csv", "0,1,2\n");
  const fs::path vv = write("vv.csv", "0,1\n2,3\n9,0\n");
  EXPECT_TRUE(fails_with([&] { read_scene(directory()); }, vv, 3, "vertex id 9 is out of range"));
  write("vv.csv", "0,1\n");
  const fs::path ve_truth = write("ve_truth.txt", "1\n0\n");
  EXPECT_TRUE(fails_with([&] { read_scene(directory()); }, ve_truth, 0, "has 2 entries but ve.csv has 1 candidates"));
  fs::remove(ve_truth);
  const fs::path vv_truth = write("vv_truth.txt", "1\nyes\n");
  EXPECT_TRUE(fails_with([&] { read_scene(directory()); }, vv_truth, 2, "expected 0 or 1, found 'yes'"));
  write("vv_truth.txt", "[]");
  EXPECT_TRUE(fails_with([&] { read_scene(directory()); }, vv_truth, 0, "has 0 entries but vv.csv has 1 candidates"));
}

TEST_F(IoTest, SceneIndicesAreCheckedAgainstTheMesh) {
  write_scene_meshes(directory());
  const fs::path vf = write("vf.csv", "0,1\n4,0\n");
  EXPECT_TRUE(
      fails_with([&] { read_scene(directory()); }, vf, 2, "vertex id 4 is out of range (the mesh has 4 vertices)"));
  write("vf.csv", "0,1\n3,2\n");
  EXPECT_TRUE(fails_with([&] { read_scene(directory()); }, vf, 2, "face id 2 is out of range (the mesh has 2 faces)"));
  write("vf.csv", "0,1\n");
  const fs::path ee = write("ee.csv", "0,1,2,3\n0,1,2,3\n0,1,7,3\n");
  EXPECT_TRUE(fails_with([&] { read_scene(directory()); }, ee, 3, "vertex id 7 is out of range"));
}

TEST_F(IoTest, SceneTruthLengthMustMatchTheCandidates) {
  write_scene_meshes(directory());
  write("vf.csv", "0,1\n3,0\n");
  const fs::path vf_truth = write("vf_truth.txt", "1\n");
  EXPECT_TRUE(fails_with([&] { read_scene(directory()); }, vf_truth, 0, "has 1 entries but vf.csv has 2 candidates"));
  write("vf_truth.txt", "1\n1\n");
  const fs::path ee_truth = write("ee_truth.txt", "[true]");  // and no ee.csv
  EXPECT_TRUE(fails_with([&] { read_scene(directory()); }, ee_truth, 0, "has 1 entries but ee.csv has 0 candidates"));
}

TEST_F(IoTest, SceneMeshesMustHaveEqualVertexCounts) {
  write_scene_meshes(directory(), 3);
  EXPECT_TRUE(fails_with([&] { read_scene(directory()); }, directory() / "t1.ply", 0, "has 3 vertices but t0.ply has 4"));
}

TEST_F(IoTest, NotASceneDirectory) {
  EXPECT_FALSE(is_scene_directory(directory()));
  EXPECT_FALSE(is_scene_directory(directory() / "missing"));
  write("t0.ply", "ply\n");
  EXPECT_FALSE(is_scene_directory(directory()));
  EXPECT_FALSE(is_scene_directory(directory() / "t0.ply"));
  EXPECT_TRUE(fails_with([&] { read_scene(directory()); }, directory(), 0, "not a scene directory"));
}

// ------------------------------------------------------------------ shared data

#define SKIP_WITHOUT_SHARED_DATA(sub) \
  if (!fs::is_directory(testing::kSharedData / (sub))) GTEST_SKIP() << (testing::kSharedData / (sub)) << " absent"

TEST(SharedDataTest, EverySampleQueryFileReads) {
  SKIP_WITHOUT_SHARED_DATA("sample-queries");
  int files = 0;
  for (const fs::path& path : testing::shared_query_files()) {
    const std::optional<Kind> kind = kind_from_path(path);
    ASSERT_TRUE(kind.has_value()) << path;
    EXPECT_EQ(*kind, path.parent_path().filename() == "vertex-face" ? Kind::vertex_face : Kind::edge_edge);
    const QueryFile file = read_query_csv(path, *kind);
    EXPECT_FALSE(file.queries.empty()) << path;
    ASSERT_TRUE(file.truth.has_value()) << path;
    EXPECT_EQ(file.truth->size(), file.queries.size());
    ++files;
  }
  EXPECT_GT(files, 0);
}

TEST(SharedDataTest, ArmadilloSceneCounts) {
  SKIP_WITHOUT_SHARED_DATA("scenes/armadillo-rollers-326");
  const Scene scene = read_scene(testing::kSharedData / "scenes/armadillo-rollers-326");
  EXPECT_EQ(scene.positions_t0.rows(), 12135);
  EXPECT_EQ(scene.positions_t1.rows(), 12135);
  EXPECT_EQ(scene.faces.rows(), 24242);
  EXPECT_EQ(scene.candidates.vertex_face.size(), 4652u);
  EXPECT_EQ(scene.candidates.edge_edge.size(), 19313u);
  ASSERT_TRUE(scene.vertex_face_truth && scene.edge_edge_truth);
  EXPECT_EQ(std::count(scene.vertex_face_truth->begin(), scene.vertex_face_truth->end(), true), 4650);
  EXPECT_EQ(std::count(scene.edge_edge_truth->begin(), scene.edge_edge_truth->end(), true), 19308);
}

// The flat query files of a scene hold exactly the points of its mesh;
// counts in `compared` those it compared (a scene may have either or both).
void expect_queries_match_mesh(const fs::path& directory, int& compared) {
  const Scene scene = read_scene(directory);
  const MeshView mesh{scene.positions_t0, scene.positions_t1, scene.faces};
  if (fs::exists(directory / "queries_vf.csv")) {
    ++compared;
    const QueryFile file = read_query_csv(directory / "queries_vf.csv", Kind::vertex_face);
    ASSERT_EQ(file.queries.size(), scene.candidates.vertex_face.size());
    EXPECT_EQ(file.truth, scene.vertex_face_truth);
    for (std::size_t i = 0; i < file.queries.size(); ++i)
      ASSERT_EQ(file.queries[i].points, vertex_face_query(mesh, scene.candidates.vertex_face[i]).points)
          << directory << " vf " << i;
  }
  if (fs::exists(directory / "queries_ee.csv")) {
    ++compared;
    const QueryFile file = read_query_csv(directory / "queries_ee.csv", Kind::edge_edge);
    ASSERT_EQ(file.queries.size(), scene.candidates.edge_edge.size());
    EXPECT_EQ(file.truth, scene.edge_edge_truth);
    for (std::size_t i = 0; i < file.queries.size(); ++i)
      ASSERT_EQ(file.queries[i].points, edge_edge_query(mesh, scene.candidates.edge_edge[i]).points)
          << directory << " ee " << i;
  }
}

TEST(SharedDataTest, SceneQueryFilesMatchTheirMeshes) {
  SKIP_WITHOUT_SHARED_DATA("scenes");
  int scenes = 0, compared = 0, query_files = 0;
  for (const fs::path& directory : testing::shared_scene_directories()) {
    expect_queries_match_mesh(directory, compared);
    for (const auto& file : fs::directory_iterator(directory))
      query_files += file.path().filename().string().starts_with("queries_");
    ++scenes;
  }
  EXPECT_GT(scenes, 0);
  // Every flat query file was compared: none under a name the check skips.
  EXPECT_GT(compared, 0);
  EXPECT_EQ(compared, query_files);
}

}  // namespace
}  // namespace batchccd
