#include "core/io/json_locator.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "core/io/json_fields.h"

namespace neurocloth {
namespace {

using Where = std::pair<int, int>;

// Positions below were counted by hand on this text (line, column, both 1-based).
const std::string kNested =
    "{\n"                                // 1
    "  \"a\": {\n"                       // 2: a's object at column 8
    "    \"b\": [10, {\"c\": true}],\n"  // 3
    "    \"d\": \"x\"\n"                 // 4
    "  },\n"                             // 5
    "  \"e\": [[1, 2], [3, 4]],\n"       // 6
    "  \"f\": -1.5e3\n"                  // 7
    "}\n";

TEST(JsonLocator, RootStartsAtTheFirstCharacter) {
  const JsonLocator at(kNested);
  EXPECT_EQ(at.find(""), Where(1, 1));
  const JsonLocator indented("\n\n   {}");
  EXPECT_EQ(indented.find(""), Where(3, 4));
}

TEST(JsonLocator, NestedMembers) {
  const JsonLocator at(kNested);
  EXPECT_EQ(at.find("a"), Where(2, 8));
  EXPECT_EQ(at.find("a.b"), Where(3, 10));
  EXPECT_EQ(at.find("a.d"), Where(4, 10));
  EXPECT_EQ(at.find("e"), Where(6, 8));
  EXPECT_EQ(at.find("f"), Where(7, 8));
}

TEST(JsonLocator, ArrayElements) {
  const JsonLocator at(kNested);
  EXPECT_EQ(at.find("a.b[0]"), Where(3, 11));
  EXPECT_EQ(at.find("a.b[1]"), Where(3, 15));
  EXPECT_EQ(at.find("a.b[1].c"), Where(3, 21));
  EXPECT_EQ(at.find("e[0]"), Where(6, 9));
  EXPECT_EQ(at.find("e[1]"), Where(6, 17));
  EXPECT_EQ(at.find("e[1][0]"), Where(6, 18));
  EXPECT_EQ(at.find("e[1][1]"), Where(6, 21));
}

TEST(JsonLocator, UnknownFieldIsZeroZero) {
  const JsonLocator at(kNested);
  EXPECT_EQ(at.find("missing"), Where(0, 0));
  EXPECT_EQ(at.find("a.missing"), Where(0, 0));
  EXPECT_EQ(at.find("a.b[2]"), Where(0, 0));  // one past the end
  EXPECT_EQ(at.find("e[0][5]"), Where(0, 0));
  EXPECT_EQ(at.find("b"), Where(0, 0));  // exists only nested, as a.b
  const JsonLocator empty("");
  EXPECT_EQ(empty.find(""), Where(0, 0));
}

// Escaped quotes must neither end a string early nor let the structural
// characters inside a string (",}]{") be read as structure.
const std::string kEscapes =
    "{\n"
    "  \"k\\\"ey\": \"va\\\"l, }] {\",\n"  // 2: {"k\"ey": "va\"l, }] {"}
    "  \"path\": \"C:\\\\\",\n"            // 3: a string ending in an escaped backslash
    "  \"next\": [1, \"\\\"\", 2]\n"       // 4: a string that is just an escaped quote
    "}\n";

TEST(JsonLocator, EscapedQuoteInKeyIsPartOfTheKey) {
  const JsonLocator at(kEscapes);
  EXPECT_EQ(at.find("k\"ey"), Where(2, 12));
}

TEST(JsonLocator, EscapesInStringsDoNotDerailLaterFields) {
  const JsonLocator at(kEscapes);
  EXPECT_EQ(at.find("path"), Where(3, 11));
  EXPECT_EQ(at.find("next"), Where(4, 11));
  EXPECT_EQ(at.find("next[1]"), Where(4, 15));
  EXPECT_EQ(at.find("next[2]"), Where(4, 21));
}

TEST(JsonLocator, MemberAndElementNames) {
  EXPECT_EQ(JsonLocator::member("", "cloth"), "cloth");
  EXPECT_EQ(JsonLocator::member("cloth", "grid"), "cloth.grid");
  EXPECT_EQ(JsonLocator::element("cloth.pins", 2), "cloth.pins[2]");
  EXPECT_EQ(JsonLocator::element(JsonLocator::element("cloth.pins", 2), 0), "cloth.pins[2][0]");
}

TEST(JsonLocator, CrlfLineEndingsCountOneLineEach) {
  const JsonLocator at("{\r\n  \"a\": 1,\r\n  \"b\": 2\r\n}\r\n");
  EXPECT_EQ(at.find("a").first, 2);
  EXPECT_EQ(at.find("b"), Where(3, 8));
}

// nlohmann::json accepts a UTF-8 byte order mark (editors on Windows write one),
// so the locator must too, or every error in such a file loses its line.
TEST(JsonLocator, SkipsUtf8ByteOrderMark) {
  const std::string text = "\xEF\xBB\xBF{\n  \"a\": 1\n}\n";
  ASSERT_TRUE(nlohmann::json::accept(text));
  const JsonLocator at(text);
  EXPECT_EQ(at.find("a"), Where(2, 8));
}

// The locator's keys must match nlohmann's decoded keys, or an error about a key
// spelled with an escape (an unknown key, typically) has no line.
TEST(JsonLocator, DecodesEscapesInKeysLikeTheParser) {
  const std::string text = "{\n  \"caf\\u00e9\": 1,\n  \"tab\\tkey\": 2\n}\n";
  const nlohmann::json doc = nlohmann::json::parse(text);
  ASSERT_TRUE(doc.contains("caf\xC3\xA9"));
  ASSERT_TRUE(doc.contains("tab\tkey"));
  const JsonLocator at(text);
  EXPECT_EQ(at.find("caf\xC3\xA9"), Where(2, 16));
  EXPECT_EQ(at.find("tab\tkey"), Where(3, 15));
}

// JsonFields is the locator's user: a failure names the located line and column.
TEST(JsonLocator, JsonFieldsErrorsCarryTheLocatedPosition) {
  const JsonFields in(kNested, "doc.json");
  try {
    in.integer(in.root()["a"]["d"], "a.d");
    FAIL() << "a string was read as an integer";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "doc.json");
    EXPECT_EQ(e.field(), "a.d");
    EXPECT_EQ(e.line(), 4);
    EXPECT_EQ(e.column(), 10);
    EXPECT_NE(std::string(e.what()).find("doc.json:4:10: field 'a.d'"), std::string::npos)
        << e.what();
  }
}

// JSON leaves a repeated key undefined and the parser keeps the last one
// silently: the locator finds the second, so a reader can name it.
TEST(JsonLocator, FindsTheFirstKeyWrittenTwiceInOneObject) {
  EXPECT_TRUE(JsonLocator(kNested).duplicate().field.empty());
  const JsonLocator at("{\"a\": {\"b\": 1,\n  \"c\": 2, \"b\": 3}, \"d\": {\"b\": 4}, \"d\": 5}");
  EXPECT_EQ(at.duplicate().field, "a.b");
  EXPECT_EQ(at.duplicate().line, 2);
  EXPECT_EQ(at.duplicate().column, 11);
  // The same key in two objects is no duplicate.
  EXPECT_TRUE(JsonLocator("[{\"a\": 1}, {\"a\": 2}]").duplicate().field.empty());
  // Escapes count as the parser decodes them: "\u0061" is "a".
  EXPECT_EQ(JsonLocator("{\"a\": 1, \"\\u0061\": 2}").duplicate().field, "a");
}

TEST(JsonFields, ADuplicateKeyIsAnInputErrorWithItsLine) {
  try {
    JsonFields("{\n  \"x\": 1,\n  \"x\": 2\n}", "dup.json");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "dup.json");
    EXPECT_EQ(e.field(), "x");
    EXPECT_EQ(e.line(), 3);
    EXPECT_NE(e.message().find("twice"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace neurocloth
