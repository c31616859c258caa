#include "geardyn/system/dof_map.hpp"

#include <gtest/gtest.h>

#include "geardyn/common/errors.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

TEST(DofMapTest, NumbersBodyMajorWithKindsAndNames) {
  const DofMap map({"pinion", "wheel"});
  EXPECT_EQ(map.num_bodies(), 2);
  EXPECT_EQ(map.num_dofs(), 12);
  EXPECT_TRUE(map.is_full());
  const BodyIndex wheel = map.GetBody("wheel");
  EXPECT_EQ(map.dof(wheel, BodyDof::kThetaZ), 11);
  EXPECT_EQ(map.dof_name(11), "wheel.θz");
  EXPECT_EQ(map.dof_kind(11), DofKind::kRotationAxial);
  EXPECT_EQ(map.dof_kind(0), DofKind::kTranslationTransverse);
  EXPECT_EQ(map.dof_kind(2), DofKind::kTranslationAxial);
  EXPECT_EQ(map.dof_kind(3), DofKind::kRotationTilt);
  EXPECT_EQ(map.dof_kind(4), DofKind::kRotationTilt);
  EXPECT_FALSE(map.FindBody("ring"));
}

TEST(DofMapTest, RestrictKeepsOrderAndMarksFixedDofs) {
  const DofMap map({"a", "b"});
  const DofMap planar = map.Restrict({0, 1, 5, 6, 7, 11});
  EXPECT_EQ(planar.num_dofs(), 6);
  EXPECT_FALSE(planar.is_full());
  EXPECT_EQ(planar.dof(BodyIndex(1), BodyDof::kThetaZ), 5);
  EXPECT_EQ(planar.FindDof(BodyIndex(1), BodyDof::kZ), -1);
  EXPECT_EQ(planar.full_index(5), 11);
  EXPECT_EQ(planar.dof_name(2), "a.θz");
  EXPECT_THROWS_MESSAGE(planar.dof(BodyIndex(0), BodyDof::kThetaX), InvalidInput,
                        "a.θx: held fixed");
}

TEST(DofMapTest, RejectsBadInput) {
  EXPECT_THROWS_MESSAGE(DofMap({"a", "a"}), InvalidInput, "duplicate");
  const DofMap map({"a"});
  EXPECT_THROWS_MESSAGE(map.Restrict({2, 1}), InvalidInput, "strictly increasing");
  EXPECT_THROWS_MESSAGE(map.Restrict({6}), InvalidInput, "out of range");
  EXPECT_THROWS_MESSAGE(map.GetBody("z"), InvalidInput, "body 'z': unknown");
}

}  // namespace
}  // namespace geardyn
