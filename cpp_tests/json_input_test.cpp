// Reading user text: JSON syntax errors in words with file, line and key; duplicate keys and deep
// nesting refused; echoed text capped; unknown keys named with the closest known one; numbers
// only in the forms their format defines.
#include <gtest/gtest.h>

#include "format/json_input.h"
#include "format/json_keys.h"
#include "util/byte_size.h"
#include "util/decimal_number.h"
#include "util/quoted_text.h"

namespace fenestra {
namespace {

std::string parse_error(const std::string& text) {
  try {
    parse_json_text(text, "scene", "x.json");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted: " << text;
  return "";
}

// No wording of nlohmann's reaches the user.
void expect_in_words(const std::string& m) {
  for (const char* library : {"syntax error", "last read", "literal", "json.exception", "parse error", "<U+"})
    EXPECT_EQ(m.find(library), std::string::npos) << m;
}

TEST(JsonInput, SyntaxErrorsAreInWordsWithLineColumnAndKey) {
  const std::string m = parse_error("{\"sky\": {\n  \"type\": tru}}");
  EXPECT_NE(m.find("scene 'x.json' is not valid JSON: line 2, column 11 (under key sky.type): expected a value "
                   "(a number, string, true, false, null, object or array), found 'tru'"),
            std::string::npos)
      << m;
  expect_in_words(m);
  const std::pair<const char*, const char*> cases[] = {
      {"{\"a\": 1,}", "expected a key in double quotes, found '}'"},
      {"{\"a\" 1}", "expected ':' after the key, found '1'"},
      {"{\"a\": 1 \"b\": 2}", "expected ',' or '}' after the value, found '\"b\"'"},
      {"[1 2]", "expected ',' or ']' after the value, found '2'"},
      {"{\"a\": \"abc", "a string has no closing '\"'"},
      {"{\"a\": 1e}", "a number needs digits after its exponent (e), found '1e'"},
      {"{\"a\": 0x10}", "found '0x10' (JSON numbers are finite and decimal"},
      {"{\"a\": NaN}", "found 'NaN'"},
      {"{\"a\": True}", "found 'True' (JSON writes true, false and null in lower case)"},
      {"{\"a\": \"x\ny\"}", "a string holds a control character"},
      {"{\"a\": \"\xff\"}", "not UTF-8"},
      {"{\"a\": 1e400}", "the number 1e400 is out of range"},
      {"", "found the end of the file"},
      {"{} 1", "expected nothing after the end of the top-level value, found '1'"},
  };
  for (const auto& [text, words] : cases) {
    const std::string e = parse_error(text);
    EXPECT_NE(e.find(words), std::string::npos) << text << "\n" << e;
    expect_in_words(e);
  }
}

TEST(JsonInput, DuplicateKeysAreRefusedWithTheirPathAndLines) {
  const std::string m = parse_error("{\"sky\": {\"type\": \"uniform\",\n \"radiance\": 1,\n \"type\": \"envmap\"}}");
  EXPECT_NE(m.find("scene 'x.json', line 3: sky.type: the key is given twice (first on line 1)"), std::string::npos)
      << m;
  // The same key in two objects is no duplicate.
  EXPECT_NO_THROW(parse_json_text(R"({"a": {"type": 1}, "b": {"type": 2}, "c": [{"x": 1}, {"x": 2}]})", "scene", "x"));
}

TEST(JsonInput, DeepNestingIsRefusedWithAShortMessage) {
  for (const std::string open : {"[", "{\"a\": "}) {
    std::string text;
    for (int i = 0; i < 1000000; ++i) text += open;
    const std::string m = parse_error(text);
    EXPECT_NE(m.find("nest deeper than 64 levels"), std::string::npos) << m.substr(0, 300);
    EXPECT_LT(m.size(), 400u) << m.substr(0, 300);  // was 3 MB: the whole key path
  }
  std::string ok = "{\"a\": ";
  for (int i = 0; i < 63; ++i) ok += "[";
  for (int i = 0; i < 63; ++i) ok += "]";
  EXPECT_NO_THROW(parse_json_text(ok + "}", "scene", "x"));
}

TEST(JsonInput, EchoedTextIsCappedAndPrintable) {
  EXPECT_EQ(quoted_text("room.obj"), "room.obj");
  EXPECT_EQ(quoted_text(std::string("room.obj\0x", 10)), "room.obj\\u0000x");
  EXPECT_EQ(quoted_text("a\xff"), "a\\xFF");
  const std::string long_text(1000, 'z');
  EXPECT_EQ(quoted_text(long_text), std::string(kMaxQuotedChars, 'z') + "...");
  EXPECT_EQ(quoted_text(std::string(100, '\xc3')).substr(0, 8), "\\xC3\\xC3");  // a cut sequence: not UTF-8
  EXPECT_EQ(quoted_text(std::string(90, 'a') + "\xc3\xa9"), std::string(80, 'a') + "...");
  // Paths keep both ends: where they start and the file they name.
  EXPECT_EQ(quoted_path("/tmp/out/result.json"), "/tmp/out/result.json");
  const std::string deep = "/home/" + std::string(300, 'd') + "/result.json";
  const std::string shown_path = quoted_path(deep);
  EXPECT_EQ(shown_path.size(), kQuotedPathHead + 3 + kQuotedPathTail);
  EXPECT_EQ(shown_path.substr(0, 10), "/home/dddd");
  EXPECT_EQ(shown_path.substr(shown_path.size() - 12), "/result.json");
  EXPECT_EQ(quoted_path(std::string(kMaxQuotedPathChars, 'p')), std::string(kMaxQuotedPathChars, 'p'));
  EXPECT_EQ(quoted_path(std::string("a\0b", 3)), "a\\u0000b");
  nlohmann::json big = nlohmann::json::array();
  for (int i = 0; i < 1000000; ++i) big.push_back(i);
  const std::string shown = quoted_json(big);
  EXPECT_LE(shown.size(), kMaxQuotedChars + 3);
  EXPECT_EQ(shown.substr(0, 8), "[0, 1, 2");
  EXPECT_EQ(quoted_json(nlohmann::json::parse(R"({"a": [1, 2]})")), R"({"a": [1, 2]})");
  // A JSON syntax error in a long string quotes a fragment of it.
  EXPECT_LT(parse_error("{\"a\": \"" + std::string(1 << 20, 'x')).size(), 300u);
}

TEST(JsonKeys, TheClosestKnownKeyIsSuggested) {
  EXPECT_EQ(closest_word("element_sise", {"materials", "groups", "element_size", "thickness"}), "element_size");
  EXPECT_EQ(closest_word("reflectence", {"type", "reflectance"}), "reflectance");
  EXPECT_EQ(closest_word("rendr", {"fenestra", "render", "solver"}), "render");
  EXPECT_EQ(closest_word("Element_Size", {"element_size"}), "element_size");
  EXPECT_EQ(closest_word("reflectnace", {"reflectance"}), "reflectance");  // a swap counts one
  EXPECT_EQ(closest_word("xyz", {"type", "radiance"}), "");
  EXPECT_EQ(closest_word("illuminance", {"metric", "illuminance_lux"}), "illuminance_lux");  // a part left out
  EXPECT_EQ(closest_word("area_fraction", {"min_area_fraction"}), "min_area_fraction");
  EXPECT_EQ(closest_word("paths", {"paths_per_sensor", "seed"}), "paths_per_sensor");
  EXPECT_EQ(closest_word("max", {"max_bounces"}), "");  // too short a part to say
  EXPECT_EQ(closest_word("", {"type"}), "");
  const auto unknown = find_unknown_key(nlohmann::json::parse(R"({"materials": [], "element_sise": 0.1})"),
                                        {"materials", "groups", "element_size", "thickness"});
  ASSERT_TRUE(unknown);
  EXPECT_EQ(unknown->key, "element_sise");
  EXPECT_EQ(unknown->message,
            "unknown key; did you mean `element_size`? (known: materials, groups, element_size, thickness)");
  EXPECT_FALSE(find_unknown_key(nlohmann::json::parse(R"({"groups": []})"), {"materials", "groups"}));
  EXPECT_EQ(find_unknown_key(nlohmann::json::parse(R"({"zzz": 1})"), {"type"})->message,
            "unknown key; (known: type)");
}

TEST(DecimalNumbers, OnlyTheDecimalFormIsANumber) {
  for (const char* yes : {"0", "-1", "+2.5", "2.", ".5", "1e3", "1E-3", "-0", "1.5e+10"})
    EXPECT_TRUE(is_decimal_number(yes)) << yes;
  for (const char* no : {"", "0x10", "inf", "-inf", "nan", "1e", "1e+", ".", "-", "1.2.3", "+-1", "1 ", " 1", "1,5",
                         "0x1p4", "infinity", "1d3", "١"})
    EXPECT_FALSE(is_decimal_number(no)) << no;
  EXPECT_FALSE(is_decimal_number("-1", false));
}

TEST(DecimalNumbers, SizesTakeTheDecimalFormOnly) {
  EXPECT_EQ(parse_byte_size("8G", "--max-memory"), 8000000000ull);
  EXPECT_EQ(parse_byte_size("1.5GB", "--max-memory"), 1500000000ull);
  EXPECT_EQ(parse_byte_size("2GiB", "--max-memory"), 2147483648ull);
  EXPECT_EQ(parse_byte_size("1e9", "--max-memory"), 1000000000ull);
  EXPECT_EQ(parse_byte_size("512", "--max-memory"), 512ull);
  for (const char* bad : {"0x10G", "0x10", "infG", "1eG", "1e", "-1G", " 8G", "8 G", "1.2.3G", "G", ""})
    EXPECT_THROW(parse_byte_size(bad, "--max-memory"), std::invalid_argument) << bad;
}

}  // namespace
}  // namespace fenestra
