#include "geardyn/common/check.hpp"

#include <gtest/gtest.h>

#include "geardyn/common/summary.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

TEST(CheckTest, ThrowUnlessNamesTheFieldAndValue) {
  const int teeth = -3;
  const auto check_positive = [](int value) {
    GEARDYN_THROW_UNLESS(value > 0, "teeth: must be positive, got " << value);
  };
  EXPECT_THROWS_MESSAGE(check_positive(teeth), InvalidInput, "teeth: must be positive, got -3");
  EXPECT_NO_THROW(check_positive(-teeth));
}

TEST(CheckTest, DemandThrowsInternalErrorWithLocation) {
  const auto demand = [](int two) { GEARDYN_DEMAND(two == 3); };
  EXPECT_THROWS_MESSAGE(demand(2), InternalError, "two == 3 at .*check_test");
}

TEST(CheckTest, CheckSizeReportsBothSizes) {
  const auto check_size = [](int size) { GEARDYN_CHECK_SIZE(size, 12, "q"); };
  EXPECT_THROWS_MESSAGE(check_size(3), InvalidInput, "q: size 3 .* 12");
}

TEST(SummaryTest, ReportCarriesStatusMessageAndWarnings) {
  Summary s;
  EXPECT_TRUE(s.ok());
  s.status = Status::kNotConverged;
  s.message = "Newton stalled";
  s.warnings.push_back("rigid-body mode");
  EXPECT_FALSE(s.ok());
  const std::string report = s.BriefReport();
  EXPECT_NE(report.find("not_converged"), std::string::npos);
  EXPECT_NE(report.find("Newton stalled"), std::string::npos);
  EXPECT_NE(report.find("warning: rigid-body mode"), std::string::npos);
}

}  // namespace
}  // namespace geardyn
