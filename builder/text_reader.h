// text_reader.h: a cursor over a whole file's bytes for the text formats (OBJ, OFF, ASCII PLY).
// Numbers are parsed with std::from_chars (locale-free, no allocation); the cursor counts lines so that
// errors can say where the file went wrong.
#pragma once

#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "builder.h"

namespace vgeo {

// Reads a whole file, a regular one in pieces on up to `threads` threads; throws InputError when it
// cannot be opened or read.
FillLaterVector<char> readWholeFile(const std::string& path, int threads = 1);

// `text` without a UTF-8 byte order mark at its start (editors on Windows write one; read as part of
// the first line it dropped an OBJ's first vertex).
inline std::string_view withoutByteOrderMark(std::string_view text) {
  return text.substr(0, 3) == "\xEF\xBB\xBF" ? text.substr(3) : text;
}

// `text` cut into pieces of whole lines for `threads` threads to parse: four a thread (they parse at
// different speeds), each of 2^minPieceLog2 bytes or more, each but the last ending after a newline,
// in order, none empty unless the text is.
std::vector<std::string_view> linePieces(std::string_view text, int threads, int minPieceLog2);

class TextReader {
 public:
  // `firstLine`: the line `text` starts at in the file (error messages name file lines).
  TextReader(std::string_view text, const std::string& file, size_t firstLine = 1)
      : text_(text), file_(file), line_(firstLine) {}

  bool atEnd() { return pos_ >= text_.size(); }
  size_t line() const { return line_; }
  size_t offset() const { return pos_; }
  const std::string& file() const { return file_; }

  // Skips spaces and tabs (not newlines).
  void skipBlanks() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t' || text_[pos_] == '\r')) pos_++;
  }
  // Skips blanks, newlines and '#' comments.
  void skipWhitespaceAndComments() {
    while (pos_ < text_.size()) {
      char c = text_[pos_];
      if (c == '\n') {
        line_++;
        pos_++;
      } else if (c == ' ' || c == '\t' || c == '\r')
        pos_++;
      else if (c == '#')
        skipLine();
      else
        break;
    }
  }
  bool atLineEnd() {
    skipBlanks();
    return pos_ >= text_.size() || text_[pos_] == '\n' || text_[pos_] == '#';
  }
  // Moves past the next newline.
  void skipLine() {
    while (pos_ < text_.size() && text_[pos_] != '\n') pos_++;
    if (pos_ < text_.size()) {
      pos_++;
      line_++;
    }
  }
  // The next blank-separated token on this line (empty at the line's end).
  std::string_view token() {
    skipBlanks();
    size_t start = pos_;
    while (!endsToken(text_.data() + pos_)) pos_++;
    return text_.substr(start, pos_ - start);
  }
  // The next token as a number of type T; false when it is not one (a leading '+' is allowed). The
  // number is read in place: it is the whole token when what follows it ends the token.
  template <class T>
  bool tryNumber(T& value) {
    skipBlanks();
    const char* const last = text_.data() + text_.size();
    const char* p = text_.data() + pos_;
    if (p < last && *p == '+') p++;
    auto [end, ec] = std::from_chars(p, last, value);
    if (ec != std::errc() || !endsToken(end)) {
      token();  // past the token
      return false;
    }
    pos_ = size_t(end - text_.data());
    return true;
  }
  // A face index that is a plain positive decimal (digits only, up to 18, then the token's end), read
  // in place and skipped; false, with nothing skipped, for any other token (slashes, signs, zero).
  bool tryPlainIndex(int64_t& value) {
    skipBlanks();
    const char* p = text_.data() + pos_;
    const char* const last = text_.data() + text_.size();
    const char* q = p;
    int64_t v = 0;
    while (q < last && q - p < 18 && uint8_t(*q - '0') < 10) v = v * 10 + (*q++ - '0');
    if (v == 0 || !endsToken(q)) return false;
    value = v;
    pos_ = size_t(q - text_.data());
    return true;
  }
  // The next number anywhere ahead (newlines and comments skipped); throws with `what` when absent.
  template <class T>
  T number(const char* what) {
    skipWhitespaceAndComments();
    if (atEnd()) fail(std::string("truncated: expected ") + what);
    T value{};
    if (!tryNumber(value)) fail(std::string("expected ") + what);
    return value;
  }
  // Whether `p` (within the text or at its end) is where a token ends.
  bool endsToken(const char* p) const {
    return p == text_.data() + text_.size() || *p == ' ' || *p == '\t' || *p == '\r' || *p == '\n';
  }
  [[noreturn]] void fail(const std::string& cause) const {
    throw InputError(file_, "line " + std::to_string(line_) + ": " + cause);
  }

 private:
  std::string_view text_;
  std::string file_;
  size_t pos_ = 0;
  size_t line_;
};

}  // namespace vgeo
