// Ground-truth files: a JSON array of booleans or one 0/1 a line.

#include <string>
#include <utility>
#include <vector>

#include "batchccd/io.hpp"
#include "io/text_input.hpp"

namespace batchccd {

namespace {

using io_detail::in_quotes;

// A cursor over the text of a JSON array that knows its line.
class JsonArrayReader {
 public:
  JsonArrayReader(std::string file, std::string_view text) : file_(std::move(file)), text_(text) {}

  std::vector<bool> read() {
    std::vector<bool> values;
    expect('[');
    skip_whitespace();
    bool closed = peek() == ']';
    while (!closed) {
      values.push_back(read_value());
      skip_whitespace();
      closed = peek() == ']';
      if (!closed) expect(',');
    }
    ++position_;  // past the ']'
    skip_whitespace();
    if (position_ < text_.size()) fail("unexpected text after the closing ']'");
    return values;
  }

 private:
  bool read_value() {
    skip_whitespace();
    if (position_ >= text_.size()) fail("unexpected end of file: expected a value");
    const std::size_t start = position_;
    while (position_ < text_.size() && is_word_character(text_[position_])) ++position_;
    const std::string_view word = text_.substr(start, position_ - start);
    if (word == "true" || word == "1") return true;
    if (word == "false" || word == "0") return false;
    fail("expected true, false, 0 or 1, found " + in_quotes(word.empty() ? text_.substr(position_, 1) : word));
  }

  void expect(char wanted) {
    skip_whitespace();
    if (position_ >= text_.size()) fail(std::string("unexpected end of file: expected '") + wanted + "'");
    if (text_[position_] != wanted)
      fail(std::string("expected '") + wanted + "', found " + in_quotes(text_.substr(position_, 1)));
    ++position_;
  }

  static bool is_word_character(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '-' ||
           c == '+';
  }

  void skip_whitespace() {
    while (position_ < text_.size()) {
      const char c = text_[position_];
      if (c != ' ' && c != '\t' && c != '\r' && c != '\n') return;
      if (c == '\n') ++line_;
      ++position_;
    }
  }

  char peek() const { return position_ < text_.size() ? text_[position_] : '\0'; }

  [[noreturn]] void fail(const std::string& problem) const { throw InputError(file_, line_, problem); }

  std::string file_;
  std::string_view text_;
  std::size_t position_ = 0;
  long line_ = 1;
};

std::vector<bool> read_bit_lines(const std::string& file, std::string_view text) {
  std::vector<bool> values;
  for (const io_detail::NumberedLine& line : io_detail::numbered_lines(text)) {
    const std::string_view field = io_detail::trim(line.text);
    const std::optional<bool> bit = io_detail::parse_bit(field);
    if (!bit) throw InputError(file, line.number, "expected 0 or 1, found " + in_quotes(field));
    values.push_back(*bit);
  }
  return values;
}

}  // namespace

std::vector<bool> read_truth(const std::filesystem::path& path) {
  const std::string text = io_detail::read_input_file(path);
  const std::string_view content = io_detail::trim(text);
  if (!content.empty() && content.front() == '[') return JsonArrayReader(path.string(), text).read();
  return read_bit_lines(path.string(), text);
}

}  // namespace batchccd
