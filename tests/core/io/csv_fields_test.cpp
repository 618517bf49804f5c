#include "core/io/csv_fields.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

namespace neurocloth {
namespace {

TEST(CsvFields, FiniteNumberReadsTheWholeField) {
  EXPECT_EQ(finite_number("1.5").value, 1.5);
  EXPECT_EQ(finite_number("-2e3").value, -2000);
  EXPECT_EQ(finite_number("12.0").refusal, "");
  // An underflow reads as the nearest double, so a denormal written reads back.
  const double tiny = std::numeric_limits<double>::denorm_min();
  const FieldNumber d = finite_number("4.9406564584124654e-324");
  EXPECT_EQ(d.refusal, "");
  EXPECT_EQ(d.value, tiny);
}

TEST(CsvFields, FiniteNumberSaysWhyAFieldIsNotOne) {
  EXPECT_EQ(finite_number("").refusal, "not a number: ''");
  EXPECT_EQ(finite_number("1.5m").refusal, "not a number: '1.5m'");
  EXPECT_EQ(finite_number("two").refusal, "not a number: 'two'");
  // strtod stops at a NUL: the rest of the field is not a number.
  EXPECT_EQ(finite_number(std::string("1\0x", 3)).refusal, "not a number: '1\\x00x'");
  for (const char* bad : {"nan", "inf", "-Infinity", "1e999"})
    EXPECT_EQ(finite_number(bad).refusal, std::string("NaN or infinite: '") + bad + "'") << bad;
}

}  // namespace
}  // namespace neurocloth
