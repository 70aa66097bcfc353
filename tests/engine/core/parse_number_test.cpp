// The checked number parser: exact values, refusals with the accepted range, no exception.
#include "engine/core/parse_number.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <string>

namespace ptlab {
namespace {

TEST(ParseNumber, AcceptsDecimalNumbersInRange) {
  double d = 0;
  EXPECT_EQ(ParseNumber<double>("1.5e3", 0, 1e4, &d), "");
  EXPECT_EQ(d, 1500.0);
  EXPECT_EQ(ParseNumber<double>("+2", -5, 5, &d), "");
  EXPECT_EQ(d, 2.0);
  EXPECT_EQ(ParseNumber<double>("1e-320", 0, 1, &d), "");  // subnormal: no exception
  EXPECT_GT(d, 0.0);
  float f = 0;
  EXPECT_EQ(ParseNumber<float>("1e20", -1e20f, 1e20f, &f), "");
  EXPECT_EQ(f, 1e20f);
  int i = 0;
  EXPECT_EQ(ParseNumber<int>("-7", -10, 10, &i), "");
  EXPECT_EQ(i, -7);
  uint64_t u = 0;
  EXPECT_EQ(ParseNumber<uint64_t>("18446744073709551615", &u), "");
  EXPECT_EQ(u, UINT64_MAX);
}

TEST(ParseNumber, OutOfRangeSaysTheRange) {
  float f = 3;
  EXPECT_EQ(ParseNumber<float>("1e38", -1e20f, 1e20f, &f), "'1e38' is out of range [-1e20, 1e20]");
  EXPECT_EQ(f, 3.0f);  // untouched on error
  double d = 0;
  EXPECT_EQ(ParseNumber<double>("1e400", -1, 1, &d), "'1e400' is out of range [-1, 1]");
  EXPECT_EQ(ParseNumber<double>("-0.5", 0, 65536, &d), "'-0.5' is out of range [0, 65536]");
  int i = 0;
  EXPECT_EQ(ParseNumber<int>("99999999999", 1, 1 << 20, &i),
            "'99999999999' is out of range [1, 1048576]");
  uint64_t u = 0;
  EXPECT_EQ(ParseNumber<uint64_t>("-1", &u), "'-1' is out of range [0, 18446744073709551615]");
}

TEST(ParseNumber, RefusesNonNumbersAndNonFiniteValues) {
  double d = 0;
  for (const char* text : {"", "abc", "1x", "1.2.3", "0x10", " 1", "1 ", "+", "++1", "+-1"})
    EXPECT_NE(ParseNumber<double>(text, -1e9, 1e9, &d).find("is not a number"), std::string::npos)
        << text;
  for (const char* text : {"nan", "inf", "-inf", "NaN", "infinity"})
    EXPECT_NE(ParseNumber<double>(text, -1e9, 1e9, &d).find("is not a finite number"),
              std::string::npos)
        << text;
  int i = 0;
  for (const char* text : {"1.0", "1e3", "0x1"})
    EXPECT_NE(ParseNumber<int>(text, 0, 100, &i).find("is not an integer; expected an integer in [0, 100]"),
              std::string::npos)
        << text;
  float f = 0;
  EXPECT_NE(ParseNumber<float>("1e-50", 0, 1, &f).find("too close to 0 for a 32-bit float"),
            std::string::npos);
}

TEST(ParseNumber, MessagesEscapeNulAndControlBytes) {
  double d = 0;
  const std::string text("1\0x\n", 4);
  const std::string message = ParseNumber<double>(text, 0, 1, &d);
  EXPECT_EQ(message.find('\0'), std::string::npos);
  EXPECT_EQ(message.find('\n'), std::string::npos);
  EXPECT_NE(message.find("'1\\0x\\n'"), std::string::npos) << message;
  EXPECT_EQ(QuoteForMessage(std::string(100, 'a'), 5), "'aaaaa...'");
}

TEST(ParseNumber, NonFiniteDataIsKeptWhereATestJudgesIt) {
  double x = 0;
  EXPECT_TRUE(ParseDoubleOrNonFinite("NaN", &x));
  EXPECT_TRUE(std::isnan(x));
  EXPECT_TRUE(ParseDoubleOrNonFinite("-inf", &x));
  EXPECT_EQ(x, -HUGE_VAL);
  EXPECT_TRUE(ParseDoubleOrNonFinite("1e400", &x));
  EXPECT_EQ(x, HUGE_VAL);
  EXPECT_TRUE(ParseDoubleOrNonFinite("-1e-400", &x));
  EXPECT_EQ(x, 0.0);
  EXPECT_FALSE(ParseDoubleOrNonFinite("zero", &x));
}

TEST(ParseNumber, FormatLimitWritesNumbersAsPeopleDo) {
  EXPECT_EQ(FormatLimit(1e20), "1e20");
  EXPECT_EQ(FormatLimit(-1e-6), "-1e-6");
  EXPECT_EQ(FormatLimit(0.5), "0.5");
  EXPECT_EQ(FormatLimit(65536), "65536");
}

}  // namespace
}  // namespace ptlab
