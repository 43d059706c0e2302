#include "format/json_input.h"

#include <algorithm>
#include <cctype>
#include <iterator>
#include <stdexcept>
#include <unordered_map>
#include <utility>
#include <vector>

#include "util/quoted_text.h"

namespace fenestra {

using nlohmann::json;

namespace {

// The text read through a pointer that records how far the parser has read: SAX callbacks other
// than parse_error are given no position.
struct TrackedChars {
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  const char* at;
  const char** furthest;

  reference operator*() const { return *at; }
  TrackedChars& operator++() {
    *furthest = ++at;
    return *this;
  }
  TrackedChars operator++(int) {
    TrackedChars before = *this;
    ++*this;
    return before;
  }
  bool operator==(const TrackedChars& o) const { return at == o.at; }
  bool operator!=(const TrackedChars& o) const { return at != o.at; }
};

enum class Failure { kNone, kSyntax, kDuplicate, kDepth };

// nlohmann's token text with its "<U+000A>" for control characters undone: quoted_text writes
// them its own way.
std::string unescaped(const std::string& token) {
  std::string out;
  for (std::size_t i = 0; i < token.size(); ++i) {
    if (token.compare(i, 3, "<U+") == 0 && i + 8 <= token.size() && token[i + 7] == '>') {
      const std::string hex = token.substr(i + 3, 4);
      if (hex.find_first_not_of("0123456789ABCDEFabcdef") == std::string::npos) {
        out += static_cast<char>(std::stoi(hex, nullptr, 16));
        i += 7;
        continue;
      }
    }
    out += token[i];
  }
  return out;
}

// nlohmann's DOM builder, also keeping the key path of the value being read, refusing duplicate
// keys and deep nesting, and, on an error, where it happened.
class LocatingParser : public nlohmann::detail::json_sax_dom_parser<json> {
  using Base = nlohmann::detail::json_sax_dom_parser<json>;

 public:
  LocatingParser(json& root, const char* begin, const char* const* furthest)
      : Base(root, false), begin_(begin), furthest_(furthest) {}

  bool null() { return Base::null() && after_value(); }
  bool boolean(bool v) { return Base::boolean(v) && after_value(); }
  bool number_integer(number_integer_t v) { return Base::number_integer(v) && after_value(); }
  bool number_unsigned(number_unsigned_t v) { return Base::number_unsigned(v) && after_value(); }
  bool number_float(number_float_t v, const string_t& s) { return Base::number_float(v, s) && after_value(); }
  bool string(string_t& v) { return Base::string(v) && after_value(); }
  bool binary(binary_t& v) { return Base::binary(v) && after_value(); }
  bool start_object(std::size_t n) {
    if (too_deep()) return false;
    frames_.push_back({false, 0, "", {}});
    return Base::start_object(n);
  }
  bool key(string_t& k) {
    Frame& f = frames_.back();
    f.key = k;
    const auto [first, inserted] = f.seen.emplace(k, read());
    if (!inserted) {
      failure_ = Failure::kDuplicate;
      position_ = read();
      first_position_ = first->second;
      path_ = path();
      return false;
    }
    return Base::key(k);
  }
  bool end_object() {
    frames_.pop_back();
    return Base::end_object() && after_value();
  }
  bool start_array(std::size_t n) {
    if (too_deep()) return false;
    frames_.push_back({true, 0, "", {}});
    return Base::start_array(n);
  }
  bool end_array() {
    frames_.pop_back();
    return Base::end_array() && after_value();
  }
  bool parse_error(std::size_t position, const std::string& token, const nlohmann::detail::exception& e) {
    failure_ = Failure::kSyntax;
    position_ = position;
    token_ = unescaped(token);
    id_ = e.id;
    reason_ = e.what();
    path_ = path();
    return false;
  }

  Failure failure() const { return failure_; }
  std::size_t position() const { return position_; }
  std::size_t first_position() const { return first_position_; }
  const std::string& token() const { return token_; }
  int id() const { return id_; }
  const std::string& reason() const { return reason_; }
  const std::string& error_path() const { return path_; }

 private:
  struct Frame {
    bool array;
    std::size_t index;
    std::string key;
    std::unordered_map<std::string, std::size_t> seen;  // key -> where it was read
  };
  std::size_t read() const { return static_cast<std::size_t>(*furthest_ - begin_); }
  bool too_deep() {
    if (frames_.size() < kMaxJsonDepth) return false;
    failure_ = Failure::kDepth;
    position_ = read();
    path_ = path();
    return true;
  }
  bool after_value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
    return true;
  }
  std::string path() const {
    std::string p;
    for (const Frame& f : frames_) {
      if (f.array)
        p += "[" + std::to_string(f.index) + "]";
      else if (!f.key.empty())
        p += (p.empty() ? "" : ".") + f.key;
    }
    return quoted_text(p);
  }

  const char* begin_;
  const char* const* furthest_;
  std::vector<Frame> frames_;
  Failure failure_ = Failure::kNone;
  std::size_t position_ = 0, first_position_ = 0;
  int id_ = 0;
  std::string token_, reason_, path_;
};

// The text after the first `prefix` up to `end` (to the end of `s` when `end` is empty), or "".
std::string between(const std::string& s, const std::string& prefix, const std::string& end = "") {
  const std::size_t a = s.find(prefix);
  if (a == std::string::npos) return "";
  const std::size_t from = a + prefix.size(), to = end.empty() ? std::string::npos : s.find(end, from);
  return s.substr(from, to == std::string::npos ? std::string::npos : to - from);
}

const char* const kValue = "a value (a number, string, true, false, null, object or array)";

// What the lexer refused, in words.
std::string lexer_words(const std::string& lexer) {
  static const std::pair<const char*, const char*> kWords[] = {
      {"invalid literal", "expected "},  // + kValue
      {"invalid number; expected digit after '-'", "a number needs a digit after '-'"},
      {"invalid number; expected digit after '.'", "a number needs a digit after '.'"},
      {"invalid number; expected '+', '-', or digit after exponent", "a number needs digits after its exponent (e)"},
      {"invalid number; expected digit after exponent sign", "a number needs digits after its exponent (e)"},
      {"invalid string: missing closing quote", "a string has no closing '\"'"},
      {"invalid string: ill-formed UTF-8 byte", "the text is not UTF-8 (a byte that UTF-8 does not allow)"},
      {"invalid string: '\\u' must be followed by 4 hex digits", "'\\u' in a string needs four hexadecimal digits"},
      {"invalid string: surrogate", "a string has an unpaired UTF-16 surrogate (\\uD800 to \\uDFFF)"},
      {"invalid string: forbidden character after backslash",
       "a backslash in a string must start an escape (\\\", \\\\, \\/, \\b, \\f, \\n, \\r, \\t or \\uXXXX)"},
      {"invalid string: control character",
       "a string holds a control character, which JSON writes escaped (a line break as \\n, a tab as \\t)"},
      {"invalid BOM", "the file starts with a broken byte order mark"},
      {"invalid comment", "JSON has no comments"},
  };
  for (const auto& [nlohmann_text, words] : kWords)
    if (lexer.rfind(nlohmann_text, 0) == 0)
      return std::string(words) + (std::string(words) == "expected " ? kValue : "");
  return "expected " + std::string(kValue);
}

// nlohmann's name of a token as the parser expected it, in words.
std::string expected_words(const std::string& context, const std::string& expected) {
  if (expected == "'[', '{', or a literal") return "expected " + std::string(kValue);
  if (expected == "string literal") return "expected a key in double quotes";
  if (expected == "':'") return "expected ':' after the key";
  if (expected == "'}'") return "expected ',' or '}' after the value";
  if (expected == "']'") return "expected ',' or ']' after the value";
  if (expected == "end of input") return "expected nothing after the end of the " +
                                         std::string(context == "value" ? "top-level value" : "text");
  return "expected " + expected;
}

// The end of nlohmann's token text, which runs from the last string or number read: "tru}" of
// "\"type\": tru}", "}" of "1,}".
std::string token_tail(const std::string& token) {
  const std::size_t cut = token.find_last_of(" \t\r\n,:[{");
  return cut == std::string::npos ? token : cut + 1 < token.size() ? token.substr(cut + 1) : token.substr(cut);
}

// The word the parser stopped at: the tail without the mark that ended it ("tru" of "tru}").
std::string last_word(const std::string& token) {
  std::string word = token_tail(token);
  if (word.size() > 1 && std::string("}],:").find(word.back()) != std::string::npos) word.pop_back();
  return word;
}

struct SyntaxError {
  std::string words;
  std::size_t length;  // bytes of the text shown as found, which ends where the parser stopped
};

// "syntax error while parsing object key - unexpected '}'; expected string literal" and the like,
// with the token the parser stopped at, in words.
SyntaxError syntax_error(const std::string& message, const std::string& token, int id, const std::string& rest) {
  if (id == 406 || message.find("number overflow") != std::string::npos)
    return {"the number " + quoted_text(token) + " is out of range (beyond +-1.8e308)", token.size()};
  const std::string context = between(message, "while parsing ", " - ");
  const std::string detail = between(message, " - ");
  auto found = [&](bool whole) -> SyntaxError {
    if (token.empty()) return {"the end of the file", 0};
    return {"'" + quoted_text(whole ? token : last_word(token)) + "'", whole ? token.size() : token_tail(token).size()};
  };
  const std::size_t last = detail.find("; last read: '");
  if (last != std::string::npos) {
    const std::string lexer = detail.substr(0, last);
    if (lexer != "invalid literal") {
      const SyntaxError f = found(lexer.rfind("invalid string", 0) == 0);
      return {lexer_words(lexer) + ", found " + f.words, f.length};
    }
    // The whole word, of which the lexer read up to the first letter it could not take.
    std::string word = last_word(token);
    if (!token.empty() && std::isalnum(static_cast<unsigned char>(token.back())))
      for (std::size_t i = 0; i < rest.size() && i < kMaxQuotedChars && std::isalnum(static_cast<unsigned char>(rest[i])); ++i)
        word += rest[i];
    std::string words = lexer_words(lexer) + ", found '" + quoted_text(word) + "'";
    const std::string low = [&] {
      std::string l = word;
      for (char& c : l) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      return l;
    }();
    if (low == "true" || low == "false" || low == "null" || low == "none")
      words += " (JSON writes true, false and null in lower case)";
    else if (low.rfind("nan", 0) == 0 || low.rfind("inf", 0) == 0 || std::isdigit(static_cast<unsigned char>(low[0])))
      words += " (JSON numbers are finite and decimal: no NaN, Infinity or hexadecimal)";
    return {words, token_tail(token).size()};
  }
  const std::string unexpected = between(detail, "unexpected ", "; expected");
  const std::string expected = between(detail, "; expected ");
  const SyntaxError f = found(unexpected == "string literal" || unexpected == "number literal");
  std::string words = (expected.empty() ? "unexpected" : expected_words(context, expected)) + ", found " + f.words;
  if (context == "object key" && last_word(token) == "}") words += " (JSON allows no comma before '}')";
  return {words, f.length};
}

// Line and column (from 1) of the byte before `offset`: nlohmann counts what it has read.
std::pair<std::size_t, std::size_t> line_and_column(const std::string& text, std::size_t offset) {
  const std::size_t end = std::min(offset, text.size());
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < end; ++i) {
    if (text[i] == '\n')
      ++line, column = 1;
    else
      ++column;
  }
  return {line, column > 1 ? column - 1 : 1};
}

}  // namespace

std::string json_error_text(const std::exception& e) {
  std::string s = e.what();
  if (s.rfind("[json.exception.", 0) == 0) {
    const size_t end = s.find("] ");
    if (end != std::string::npos) s.erase(0, end + 2);
  }
  // "parse error at line 1, column 10: syntax error while parsing value - ..." -> the reason only;
  // the caller states the position.
  if (s.rfind("parse error at line ", 0) == 0) {
    const size_t colon = s.find(": ");
    if (colon != std::string::npos) s.erase(0, colon + 2);
  }
  // "type must be number, but is string" -> "expected a number, got a string"
  if (s.rfind("type must be ", 0) == 0) {
    const std::string want = between(s, "type must be ", ", but is "), got = between(s, ", but is ");
    if (!want.empty() && !got.empty()) return "expected a " + want + ", got " + (got == "null" ? "" : "a ") + got;
  }
  return s;
}

json parse_json_text(const std::string& text, const std::string& what, const std::string& name) {
  const std::string source = what + " '" + quoted_text(name) + "'";
  json root;
  const char* furthest = text.data();
  LocatingParser parser(root, text.data(), &furthest);
  bool ok = false;
  try {
    const TrackedChars first{text.data(), &furthest}, last{text.data() + text.size(), &furthest};
    ok = json::sax_parse(first, last, &parser);
  } catch (const json::exception& e) {
    throw std::invalid_argument(source + " is not valid JSON: " + json_error_text(e));
  }
  if (ok && parser.failure() == Failure::kNone) return root;
  const auto [line, column] = line_and_column(text, parser.position());
  const std::string at = "line " + std::to_string(line) + ", column " + std::to_string(column);
  const std::string under = parser.error_path().empty() ? "" : " (under key " + parser.error_path() + ")";
  switch (parser.failure()) {
    case Failure::kDuplicate:
      throw std::invalid_argument(source + ", line " + std::to_string(line) + ": " + parser.error_path() +
                                  ": the key is given twice (first on line " +
                                  std::to_string(line_and_column(text, parser.first_position()).first) +
                                  "); give each key once");
    case Failure::kDepth:
      throw std::invalid_argument(source + ", " + at + under + ": lists and objects nest deeper than " +
                                  std::to_string(kMaxJsonDepth) + " levels");
    default: {
      const std::size_t end = std::min(parser.position(), text.size());
      const SyntaxError e = syntax_error(parser.reason(), parser.token(), parser.id(), text.substr(end, kMaxQuotedChars));
      // Where the text shown as found begins.
      const auto [from_line, from_column] = line_and_column(text, end - std::min(end, e.length) + 1);
      throw std::invalid_argument(source + " is not valid JSON: line " + std::to_string(from_line) + ", column " +
                                  std::to_string(from_column) + under + ": " + e.words);
    }
  }
}

}  // namespace fenestra
