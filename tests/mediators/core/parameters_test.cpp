#include "tsr/med/parameters.hpp"

#include <gtest/gtest.h>

using namespace tsr::med;

TEST(Parameters, ParseGivesTypedValues) {
  EXPECT_EQ(Parameters::parse("spp=16").second, ParameterValue(std::int64_t{16}));
  EXPECT_EQ(Parameters::parse("t=0.25").second, ParameterValue(0.25));
  EXPECT_EQ(Parameters::parse("shadows=false").second, ParameterValue(false));
  EXPECT_EQ(Parameters::parse("mode=direct").second, ParameterValue(std::string("direct")));
  EXPECT_THROW(Parameters::parse("novalue"), ParameterError);
  EXPECT_THROW(Parameters::parse("=3"), ParameterError);
}

TEST(Parameters, TypedReadsCheckTypeAndRange) {
  Parameters p;
  p.set("spp", std::int64_t{0});
  p.set("name", std::string("x"));
  p.set("t", std::int64_t{2});
  EXPECT_EQ(p.getInt("missing", 7), 7);
  EXPECT_THROW(p.getInt("spp", 1, 1), ParameterError);
  EXPECT_THROW(p.getInt("name", 1), ParameterError);
  EXPECT_DOUBLE_EQ(p.getReal("t", 0), 2.0) << "integers read as reals";
  try {
    p.getBool("name", false);
    FAIL();
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("parameter name"), std::string::npos);
  }
}
