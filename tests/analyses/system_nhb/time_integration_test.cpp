/// @file
/// @brief The system nonlinear HB (system_nonlinear_hb.hpp) against an independent GSL rk8pd
/// time integration of the same equation on all DOFs (system_time_integration.hpp), on the
/// Kahraman–Blankenship rig with a slice mesh: one frequency with strong contact loss (a single
/// stable periodic solution there) and one in full contact.
#include <gtest/gtest.h>

#include "analyses/system_nhb/kb_rig_fixture.hpp"
#include "analyses/system_nhb/system_time_integration.hpp"
#include "geardyn/analyses/system_nonlinear_hb.hpp"

namespace geardyn {
namespace {

void CompareAt(double mesh_frequency_hz, bool expect_contact_loss) {
  const SystemModel model = testing::KbRigSliceModel();
  SystemNhbOptions options;
  options.hb.harmonics = 32;
  Summary summary;
  const SystemNhbPoint hb = SolveSystemNonlinearHb(model, mesh_frequency_hz, options, &summary);
  ASSERT_TRUE(summary.ok()) << summary.BriefReport();
  ASSERT_EQ(hb.point.stable, FloquetVerdict::kStable) << "max |μ| = " << hb.point.max_multiplier;
  const SystemNhbMeshOutput& m = hb.meshes.at(0);

  testing::SystemTimeIntegrator ti(model);
  const testing::SystemTiStats st = ti.Run(mesh_frequency_hz, 400, 10);
  ASSERT_TRUE(st.ok);
  EXPECT_NEAR(m.rms_dte, st.rms, 0.01 * st.rms) << mesh_frequency_hz << " Hz";
  EXPECT_NEAR(m.mean_dte, st.mean, 0.01 * std::abs(st.mean)) << mesh_frequency_hz << " Hz";
  EXPECT_NEAR(m.peak_to_peak_dte, st.peak_to_peak, 0.02 * st.peak_to_peak);
  EXPECT_NEAR(m.contact_loss_fraction, st.contact_loss_fraction, 0.02);
  if (expect_contact_loss) {
    EXPECT_GT(st.contact_loss_fraction, 0.1);
  } else {
    EXPECT_EQ(st.contact_loss_fraction, 0.0);
  }
}

TEST(SystemNonlinearHb, ContactLossOrbitMatchesTimeIntegration) { CompareAt(1700.0, true); }

TEST(SystemNonlinearHb, FullContactOrbitMatchesTimeIntegration) { CompareAt(900.0, false); }

}  // namespace
}  // namespace geardyn
