// The Hill size bound (issue 12: `floquet --method hill` ran for minutes on the helical pair):
// dim·(2H+1) ≤ 800 rows, checked before any solve, at its edge; the message gives the size and the
// cost. Truth: the row count dim·(2H+1) of the Hill matrix (hill.cpp).
#include <gtest/gtest.h>

#include <string>

#include "floquet_test_support.hpp"
#include "geardyn/common/errors.hpp"
#include "support/expect_throws.hpp"

namespace geardyn::test {
namespace {

TEST(HillSizeTest, OptionsBoundHarmonicsAtTheirEdge) {
  FloquetOptions o;
  o.mesh_frequency_hz = 1.0;
  std::string why;
  o.hill_harmonics = 199;  // 2·(2·199 + 1) = 798 rows for the smallest state
  EXPECT_TRUE(o.IsValid(&why)) << why;
  o.hill_harmonics = 200;  // 802 rows even for one DOF
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("hill_harmonics"), std::string::npos) << why;
  EXPECT_NE(why.find("200"), std::string::npos) << why;
}

TEST(HillSizeTest, StateDimensionBoundsHarmonicsAtTheEdgeWithTheCost) {
  // Two DOFs: state dimension 4; H = 99 gives 4·199 = 796 rows (its estimate solve uses
  // round(99/1.5) = 66), H = 100 gives 804 rows.
  PeriodicSecondOrderSystem sys;
  sys.mass = MatrixX::Identity(2, 2);
  sys.period_s = 1.0;
  MatrixXc K0 = MatrixXc::Zero(2, 2), K1 = MatrixXc::Zero(2, 2);
  K0(0, 0) = 40.0;
  K0(1, 1) = 90.0;
  K1(0, 0) = 2.0;
  sys.stiffness_harmonics = {K0, K1};
  FloquetOptions o;
  o.method = FloquetMethod::kHill;
  o.hill_harmonics = 100;
  EXPECT_THROWS_MESSAGE(ComputeFloquet(sys, o), InvalidInput,
                        "hill_harmonics: H = 100 on a state of dimension 4 makes a complex Hill "
                        "matrix of size 804");
  o.hill_harmonics = 5;  // well inside: runs, and the multipliers are finite
  const FloquetResult r = ComputeFloquet(sys, o);
  EXPECT_TRUE(r.multipliers.allFinite());
}

}  // namespace
}  // namespace geardyn::test
