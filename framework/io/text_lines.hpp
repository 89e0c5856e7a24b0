// Private to framework/io: the line reader and number parsing shared by the text formats (ascii PLY,
// OBJ, OFF, XYZ). Lines are string_views into the loaded buffer and numbers are parsed with
// std::from_chars, so large files load without a stream operation per token; every error it raises
// names the file and the current line. Header-only (all inline) so that the PCD target, which cannot
// link dtsl_io, can share it.
#pragma once

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>

#include "framework/core/error.hpp"

namespace dtsl::io_detail {

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/// Walks a text buffer line by line (LF or CRLF line ends), numbering lines from 1.
class LineReader {
 public:
  /// Reads `text` from byte `start`; `lines_before` is the number of the line preceding `start`.
  LineReader(const std::string& path, std::string_view text, std::size_t start = 0, long lines_before = 0)
      : path_(path), text_(text), pos_(start), number_(lines_before) {}

  /// Moves to the next line; false (and no change) at the end of the text.
  bool next();
  std::string_view line() const { return line_; }
  long number() const { return number_; }
  /// Byte offset just past the current line's newline (where a binary body starts after a header).
  std::size_t end_offset() const { return pos_; }
  const std::string& path() const { return path_; }

  [[noreturn]] void fail(const std::string& problem) const { throw FileError(path_, problem, number_); }

 private:
  const std::string& path_;
  std::string_view text_;
  std::size_t pos_;
  long number_;
  std::string_view line_;
};

/// Whitespace-separated tokens of one line.
class Tokens {
 public:
  explicit Tokens(std::string_view text) : rest_(text) {}
  bool next(std::string_view& token);
  /// How many tokens are left (does not consume them).
  std::size_t count() const;

 private:
  std::string_view rest_;
};

/// `line` cut at the first `marker` (a comment), with trailing blanks removed.
std::string_view strip_comment(std::string_view line, char marker = '#');
bool is_blank(std::string_view line);
/// `text` without leading and trailing blanks.
std::string_view trim(std::string_view text);

enum class NumberStatus { ok, malformed, out_of_range };
/// Parses the whole token as a finite double (a leading '+' is allowed). NaN, infinity and overflow
/// give out_of_range; underflow gives the rounded value.
NumberStatus to_double(std::string_view token, double& value);
/// Parses the whole token as a decimal integer (a leading '+' is allowed).
NumberStatus to_integer(std::string_view token, long long& value);

/// The token in quotes for messages, shortened if long (a hostile token may be megabytes).
std::string quoted(std::string_view token);

/// to_double / to_integer that throw a FileError at the reader's line, naming `what` was expected.
double parse_double(const LineReader& at, std::string_view token, const char* what);
long long parse_integer(const LineReader& at, std::string_view token, const char* what);

// ---- implementation ------------------------------------------------------------------------------


inline bool LineReader::next() {
  if (pos_ >= text_.size()) return false;
  const char* begin = text_.data() + pos_;
  const void* nl = std::memchr(begin, '\n', text_.size() - pos_);
  const std::size_t len = nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - begin) : text_.size() - pos_;
  line_ = std::string_view(begin, len);
  if (!line_.empty() && line_.back() == '\r') line_.remove_suffix(1);
  pos_ += nl ? len + 1 : len;
  ++number_;
  return true;
}

inline bool Tokens::next(std::string_view& token) {
  std::size_t i = 0;
  while (i < rest_.size() && is_space(rest_[i])) ++i;
  std::size_t j = i;
  while (j < rest_.size() && !is_space(rest_[j])) ++j;
  token = rest_.substr(i, j - i);
  rest_.remove_prefix(j);
  return !token.empty();
}

inline std::size_t Tokens::count() const {
  Tokens copy(*this);
  std::size_t n = 0;
  std::string_view t;
  while (copy.next(t)) ++n;
  return n;
}

inline std::string_view strip_comment(std::string_view line, char marker) {
  const std::size_t hash = line.find(marker);
  if (hash != std::string_view::npos) line = line.substr(0, hash);
  while (!line.empty() && is_space(line.back())) line.remove_suffix(1);
  return line;
}

inline bool is_blank(std::string_view line) {
  for (char c : line)
    if (!is_space(c)) return false;
  return true;
}

inline std::string_view trim(std::string_view text) {
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
  return text;
}

// from_chars rejects a leading '+', which some writers emit.
inline std::string_view drop_plus(std::string_view t) {
  if (t.size() > 1 && t[0] == '+' && t[1] != '-' && t[1] != '+') t.remove_prefix(1);
  return t;
}

inline NumberStatus to_double(std::string_view token, double& value) {
  token = drop_plus(token);
  if (token.empty()) return NumberStatus::malformed;
  const char* end = token.data() + token.size();
  double v = 0.0;
  const auto r = std::from_chars(token.data(), end, v);
  if (r.ptr != end || r.ec == std::errc::invalid_argument) return NumberStatus::malformed;
  if (r.ec == std::errc::result_out_of_range) {
    // Overflow or underflow: strtod tells them apart (HUGE_VAL vs a tiny or zero value).
    const std::string copy(token);
    v = std::strtod(copy.c_str(), nullptr);
  }
  if (!std::isfinite(v)) return NumberStatus::out_of_range;
  value = v;
  return NumberStatus::ok;
}

inline NumberStatus to_integer(std::string_view token, long long& value) {
  token = drop_plus(token);
  if (token.empty()) return NumberStatus::malformed;
  const char* end = token.data() + token.size();
  long long v = 0;
  const auto r = std::from_chars(token.data(), end, v);
  if (r.ec == std::errc::invalid_argument || r.ptr != end) return NumberStatus::malformed;
  if (r.ec == std::errc::result_out_of_range) return NumberStatus::out_of_range;
  value = v;
  return NumberStatus::ok;
}

inline std::string quoted(std::string_view token) {
  constexpr std::size_t max = 40;
  if (token.size() <= max) return "'" + std::string(token) + "'";
  return "'" + std::string(token.substr(0, max)) + "...'";
}

inline double parse_double(const LineReader& at, std::string_view token, const char* what) {
  double v = 0.0;
  switch (to_double(token, v)) {
    case NumberStatus::ok:
      return v;
    case NumberStatus::malformed:
      at.fail(std::string("expected a number for ") + what + ", got " + quoted(token));
    case NumberStatus::out_of_range:
      break;
  }
  at.fail(std::string(what) + " is NaN or infinite: " + quoted(token));
}

inline long long parse_integer(const LineReader& at, std::string_view token, const char* what) {
  long long v = 0;
  switch (to_integer(token, v)) {
    case NumberStatus::ok:
      return v;
    case NumberStatus::malformed:
      at.fail(std::string("expected an integer for ") + what + ", got " + quoted(token));
    case NumberStatus::out_of_range:
      break;
  }
  at.fail(std::string(what) + " is out of range: " + quoted(token));
}

}  // namespace dtsl::io_detail
