#include "io/json_input.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace fenestra {

using nlohmann::json;

namespace {

// nlohmann's DOM builder, also keeping the key path of the value being read and, on an error,
// where it happened (json::parse alone reports no position for an out-of-range number).
class LocatingParser : public nlohmann::detail::json_sax_dom_parser<json> {
  using Base = nlohmann::detail::json_sax_dom_parser<json>;

 public:
  explicit LocatingParser(json& root) : Base(root, false) {}

  bool null() { return Base::null() && after_value(); }
  bool boolean(bool v) { return Base::boolean(v) && after_value(); }
  bool number_integer(number_integer_t v) { return Base::number_integer(v) && after_value(); }
  bool number_unsigned(number_unsigned_t v) { return Base::number_unsigned(v) && after_value(); }
  bool number_float(number_float_t v, const string_t& s) { return Base::number_float(v, s) && after_value(); }
  bool string(string_t& v) { return Base::string(v) && after_value(); }
  bool binary(binary_t& v) { return Base::binary(v) && after_value(); }
  bool start_object(std::size_t n) {
    frames_.push_back({false, 0, ""});
    return Base::start_object(n);
  }
  bool key(string_t& k) {
    frames_.back().key = k;
    return Base::key(k);
  }
  bool end_object() {
    frames_.pop_back();
    return Base::end_object() && after_value();
  }
  bool start_array(std::size_t n) {
    frames_.push_back({true, 0, ""});
    return Base::start_array(n);
  }
  bool end_array() {
    frames_.pop_back();
    return Base::end_array() && after_value();
  }
  bool parse_error(std::size_t position, const std::string& token, const nlohmann::detail::exception& e) {
    failed_ = true;
    position_ = position;
    token_ = token;
    reason_ = json_error_text(e);
    path_ = path();
    return false;
  }

  bool failed() const { return failed_; }
  std::size_t position() const { return position_; }
  const std::string& reason() const { return reason_; }
  const std::string& error_path() const { return path_; }

 private:
  struct Frame {
    bool array;
    std::size_t index;
    std::string key;
  };
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
    return p;
  }
  std::vector<Frame> frames_;
  bool failed_ = false;
  std::size_t position_ = 0;
  std::string token_, reason_, path_;
};

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
  return s;
}

json parse_json_text(const std::string& text, const std::string& what, const std::string& name) {
  json root;
  LocatingParser parser(root);
  bool ok = false;
  try {
    ok = json::sax_parse(text, &parser);
  } catch (const json::exception& e) {
    throw std::invalid_argument(what + " '" + name + "' is not valid JSON: " + json_error_text(e));
  }
  if (ok && !parser.failed()) return root;
  // Line and column of the byte where the parser stopped.
  const std::size_t end = std::min(parser.position(), text.size());
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < end; ++i) {
    if (text[i] == '\n')
      ++line, column = 1;
    else
      ++column;
  }
  std::string where = "line " + std::to_string(line) + ", column " + std::to_string(column > 1 ? column - 1 : 1);
  if (!parser.error_path().empty()) where += " (under key " + parser.error_path() + ")";
  throw std::invalid_argument(what + " '" + name + "' is not valid JSON: " + where + ": " +
                              (parser.reason().empty() ? std::string("syntax error") : parser.reason()));
}

}  // namespace fenestra
