// Hand-made cases, one or more per configuration, with closed-form answers.
// Each case is written in a convenient frame and re-run under several common
// rigid motions (identity, a 90-degree turn, a generic rotation, a nearly-identity
// rotation, and a far translation), in float and double, as FCL's tests do.
#include <fcl_disk/disk_intersection.h>
#include <fcl_disk/exact_distance.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "test_random.h"
#include "test_tolerances.h"

namespace {

using fcl_disk::DiskPairFeature;
using Vec3 = Eigen::Vector3d;

struct Case {
  std::string name;
  double r1;
  Vec3 c1, n1;
  double r2;
  Vec3 c2, n2;
  double expected_distance;
  DiskPairFeature expected_feature;
};

Eigen::Isometry3d pose(const Vec3& centre, const Vec3& normal) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = centre;
  X.linear() =
      Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), normal.normalized()).toRotationMatrix();
  return X;
}

const double kInvSqrt5 = 1.0 / std::sqrt(5.0);

std::vector<Case> handMadeCases() {
  const Vec3 z = Vec3::UnitZ(), x = Vec3::UnitX(), y = Vec3::UnitY();
  return {
      {"coaxial stack", 1.0, Vec3::Zero(), z, 2.0, Vec3(0, 0, 1.5), z, 1.5,
       DiskPairFeature::face1_rim2},
      {"coaxial stack, flipped normal", 1.0, Vec3::Zero(), z, 0.5, Vec3(0, 0, -0.25), -z, 0.25,
       DiskPairFeature::face1_rim2},
      {"parallel, projections overlap", 1.0, Vec3::Zero(), z, 1.0, Vec3(1.5, 0, 0.7), z, 0.7,
       DiskPairFeature::face1_rim2},
      {"parallel, projections apart", 1.0, Vec3::Zero(), z, 0.5, Vec3(2.5, 0, 0.75), z,
       std::sqrt(1.0 * 1.0 + 0.75 * 0.75), DiskPairFeature::rim_rim},
      {"coplanar apart", 1.0, Vec3::Zero(), z, 2.0, Vec3(0, 4.5, 0), z, 1.5,
       DiskPairFeature::rim_rim},
      {"coplanar touching", 1.0, Vec3::Zero(), z, 2.0, Vec3(3, 0, 0), z, 0.0,
       DiskPairFeature::intersecting},
      {"coplanar overlapping", 1.0, Vec3::Zero(), z, 1.0, Vec3(1, 1, 0), z, 0.0,
       DiskPairFeature::intersecting},
      {"coplanar, one inside the other", 3.0, Vec3::Zero(), z, 1.0, Vec3(1, 0.5, 0), -z, 0.0,
       DiskPairFeature::intersecting},
      {"concentric", 1.0, Vec3::Zero(), z, 0.25, Vec3::Zero(), z, 0.0,
       DiskPairFeature::intersecting},
      {"interlocked chain links", 1.0, Vec3::Zero(), z, 1.0, Vec3(0.5, 0, 0), x, 0.0,
       DiskPairFeature::intersecting},
      {"crossing at an angle", 1.0, Vec3::Zero(), z, 0.8, Vec3(0.3, 0.2, 0.1), Vec3(1, 2, 3), 0.0,
       DiskPairFeature::intersecting},
      {"rim touching face", 1.0, Vec3::Zero(), z, 1.0, Vec3(0.2, 0, 1), x, 0.0,
       DiskPairFeature::intersecting},
      {"T: rim above face", 1.0, Vec3::Zero(), z, 1.0, Vec3(0.3, 0, 2), x, 1.0,
       DiskPairFeature::face1_rim2},
      {"T: face beside rim", 1.0, Vec3(0.3, 0, 2), x, 1.0, Vec3::Zero(), z, 1.0,
       DiskPairFeature::rim1_face2},
      {"perpendicular, face of 2 nearest", 1.0, Vec3::Zero(), z, 1.0, Vec3(3, 0, 0), x, 2.0,
       DiskPairFeature::rim1_face2},
      {"perpendicular rim-rim", 1.0, Vec3::Zero(), z, 1.0, Vec3(3, 0, 0), y, 1.0,
       DiskPairFeature::rim_rim},
      // facts.md counterexample A: K2's highest rim point lies over K1's face.
      {"counterexample A", 1.0, Vec3::Zero(), z, 1.0, Vec3(0, 0, -0.5), Vec3(0, 1, 2),
       0.5 - kInvSqrt5, DiskPairFeature::face1_rim2},
      {"radius ratio 1e6, small over big", 1e3, Vec3::Zero(), z, 1e-3, Vec3(10, -20, 0.5),
       Vec3(1, 1, 0), 0.5 - 1e-3, DiskPairFeature::face1_rim2},  // K2 upright: lowest point r2 below
      {"tiny separation over face", 1.0, Vec3::Zero(), z, 1.0, Vec3(0.1, 0, 1e-12), z, 1e-12,
       DiskPairFeature::face1_rim2},
      {"huge separation", 1.0, Vec3::Zero(), z, 1.0, Vec3(1e6, 0, 0), z, 1e6 - 2.0,
       DiskPairFeature::rim_rim},
  };
}

// Common rigid motions applied to both disks (FCL's test style).
std::vector<std::pair<std::string, Eigen::Isometry3d>> rigidMotions() {
  std::vector<std::pair<std::string, Eigen::Isometry3d>> motions;
  motions.emplace_back("identity", Eigen::Isometry3d::Identity());
  Eigen::Isometry3d quarter = Eigen::Isometry3d::Identity();
  quarter.linear() = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitY()).toRotationMatrix();
  motions.emplace_back("90 degrees about y", quarter);
  Eigen::Isometry3d generic = Eigen::Isometry3d::Identity();
  generic.linear() = Eigen::AngleAxisd(1.1, Vec3(0.3, -0.5, 0.8).normalized()).toRotationMatrix();
  generic.translation() = Vec3(-2.0, 0.7, 3.1);
  motions.emplace_back("generic", generic);
  Eigen::Isometry3d nearly = Eigen::Isometry3d::Identity();
  nearly.linear() = Eigen::AngleAxisd(1e-9, Vec3(1, 1, 0).normalized()).toRotationMatrix();
  motions.emplace_back("nearly identity", nearly);
  Eigen::Isometry3d far = generic;
  far.translation() = Vec3(1e5, -3e5, 2e5);
  motions.emplace_back("generic, far from origin", far);
  return motions;
}

template <typename S>
class ExactCases : public ::testing::Test {};
using ScalarTypes = ::testing::Types<double, float>;
TYPED_TEST_SUITE(ExactCases, ScalarTypes);

/// Distance of a world point from a disk given by pose and radius (double).
double offDisk(const Vec3& point, const Eigen::Isometry3d& X, double r) {
  const Vec3 local = X.inverse() * point;
  return std::max(std::abs(local.z()), local.head<2>().norm() - r);
}

TYPED_TEST(ExactCases, MatchClosedFormsUnderRigidMotions) {
  using S = TypeParam;
  using Eps = fcl_disk_test::Eps<S>;
  for (const Case& c : handMadeCases()) {
    for (const auto& [motion_name, motion] : rigidMotions()) {
      SCOPED_TRACE(c.name + " / " + motion_name);
      const Eigen::Isometry3d X1 = motion * pose(c.c1, c.n1);
      const Eigen::Isometry3d X2 = motion * pose(c.c2, c.n2);
      const fcl::Transform3<S> X1s = X1.cast<S>(), X2s = X2.cast<S>();
      const auto result = fcl_disk::exactDiskDistance(S(c.r1), X1s, S(c.r2), X2s);

      // Error budget: the solver's bound plus the rounding of the moved pose in S
      // (both relative to the scene, which includes |c| for far poses).
      const double scale = fcl_disk_test::sceneSize(
          c.r1, c.r2, (c.c2 - c.c1).norm(), X1.translation().norm(), X2.translation().norm());
      const double tolerance = (Eps::kExactDistanceRelative + Eps::kPoseRoundingRelative) * scale;
      EXPECT_NEAR(double(result.distance), c.expected_distance, tolerance);
      const Eigen::Isometry3d X1r = X1s.template cast<double>(), X2r = X2s.template cast<double>();
      EXPECT_LE(offDisk(result.p_W1.template cast<double>(), X1r, c.r1), tolerance);
      EXPECT_LE(offDisk(result.p_W2.template cast<double>(), X2r, c.r2), tolerance);
      EXPECT_NEAR((result.p_W2 - result.p_W1).template cast<double>().norm(),
                  double(result.distance), tolerance);
      EXPECT_LE(double(result.certifiedGap()), tolerance);
      // The feature is a property of the configuration, except exactly at
      // touching contact where rounding may report a 1e-16 gap instead.
      // Parallel planes stay parallel under every motion, though a rotated
      // pose tilts them by rounding (~1e-16): the face case takes such a tilt
      // as none (docs/exact_distance.md, section 3.2).
      if (c.expected_distance > tolerance) {
        EXPECT_EQ(result.feature, c.expected_feature);
      }
      const bool intersecting = fcl_disk::intersectDisks(S(c.r1), X1s, S(c.r2), X2s);
      if (c.expected_distance > tolerance) {
        EXPECT_FALSE(intersecting);
      }
      if (c.expected_distance == 0.0 && std::string(motion_name) == "identity") {
        EXPECT_TRUE(intersecting);
      }
    }
  }
}

TYPED_TEST(ExactCases, ContactPointLiesOnBothDisksAndDepthSeparates) {
  using S = TypeParam;
  using Eps = fcl_disk_test::Eps<S>;
  for (const Case& c : handMadeCases()) {
    if (c.expected_distance != 0.0) continue;
    for (const auto& [motion_name, motion] : rigidMotions()) {
      SCOPED_TRACE(c.name + " / " + motion_name);
      const fcl::Transform3<S> X1 = (motion * pose(c.c1, c.n1)).template cast<S>();
      const fcl::Transform3<S> X2 = (motion * pose(c.c2, c.n2)).template cast<S>();
      fcl_disk::DiskContact<S> contact;
      if (!fcl_disk::intersectDisks(S(c.r1), X1, S(c.r2), X2, &contact)) {
        // Only exact touching may round to "apart", and then by a hair.
        EXPECT_LE(double(fcl_disk::exactDiskDistance(S(c.r1), X1, S(c.r2), X2).distance),
                  Eps::kIntersectionBandRelative * std::max(1.0, X1.translation().template cast<double>().norm()));
        continue;
      }
      const double scale = fcl_disk_test::sceneSize(c.r1, c.r2, (c.c2 - c.c1).norm(),
                                                    X1.translation().template cast<double>().norm(),
                                                    X2.translation().template cast<double>().norm());
      const double tolerance = (Eps::kExactDistanceRelative + Eps::kPoseRoundingRelative) * scale;
      const Vec3 pos = contact.pos.template cast<double>();
      EXPECT_LE(offDisk(pos, X1.template cast<double>(), c.r1), tolerance);
      EXPECT_LE(offDisk(pos, X2.template cast<double>(), c.r2), tolerance);
      EXPECT_NEAR(contact.normal.template cast<double>().norm(), 1.0, Eps::kUnitNormal);
      EXPECT_GE(double(contact.penetration_depth), 0.0);
      // Moving disk 2 by depth (plus a margin) along the normal separates them,
      // and then they are just apart (distance ~ the margin).
      const double margin = Eps::kSeparationStepRelative * scale;
      fcl::Transform3<S> moved = X2;
      moved.translation() += (S(double(contact.penetration_depth) + margin)) * contact.normal;
      EXPECT_FALSE(fcl_disk::intersectDisks(S(c.r1), X1, S(c.r2), moved));
      const double moved_distance =
          double(fcl_disk::exactDiskDistance(S(c.r1), X1, S(c.r2), moved).distance);
      EXPECT_LE(moved_distance, margin + tolerance);
    }
  }
}

// Tilts from 1e-12 rad up: the distance of two parallel-offset disks, one tilted
// about the line joining the centres, changes only at second order in the tilt.
TEST(ExactCasesDouble, NearParallelTiltsDownTo1e12) {
  for (double tilt : {1e-3, 1e-6, 1e-9, 1e-12}) {
    SCOPED_TRACE(tilt);
    const Vec3 n2 = Eigen::AngleAxisd(tilt, Vec3::UnitX()) * Vec3::UnitZ();
    // Projections overlap: face case, distance h - r2 sin(tilt).
    const auto over = fcl_disk::exactDiskDistance(1.0, pose(Vec3::Zero(), Vec3::UnitZ()), 1.0,
                                                  pose(Vec3(0, 0.5, 0.3), n2));
    EXPECT_NEAR(over.distance, 0.3 - std::sin(tilt), 1e-12 * 3.0);
    EXPECT_LE(over.certifiedGap(), 1e-12 * 3.0);
  }
}

// Parallel disks whose poses share a frame Q, the second turned about its
// normal (R2 = Q Rz): parallel in exact arithmetic, tilted by the rounding of
// Q Rz (~1e-16). With overlapping projections they are the face case of
// parallel planes, distance h, the points the middle of the overlap of the
// diameters along the line of centres (docs/exact_distance.md, section 3.2).
TEST(ExactCasesDouble, ParallelUpToRoundingTakesTheParallelFaceCase) {
  fcl_disk_test::Random random(20261201);
  for (int i = 0; i < 2000; ++i) {
    const double r1 = random.uniform(0.2, 2.0), r2 = random.uniform(0.2, 2.0);
    const double h = (random.chance(0.5) ? 1.0 : -1.0) * random.logUniform(1e-9, 10.0);
    const double heading = random.uniform(0.0, 2.0 * M_PI);
    const double offset = random.uniform(0.0, 0.95 * (r1 + r2));
    const Vec3 along(std::cos(heading), std::sin(heading), 0.0);
    Eigen::Isometry3d X1 = Eigen::Isometry3d::Identity(), X2 = Eigen::Isometry3d::Identity();
    X1.linear() = random.rotation();
    X1.translation() = random.inBall(2.0);
    const double spin = random.uniform(0.0, 2.0 * M_PI);
    X2.linear() = X1.linear() * Eigen::AngleAxisd(spin, Vec3::UnitZ()).toRotationMatrix();
    X2.translation() = X1 * Vec3(offset * along + Vec3(0.0, 0.0, h));
    SCOPED_TRACE(i);
    const auto result = fcl_disk::exactDiskDistance(r1, X1, r2, X2);
    const double scale = r1 + r2 + std::hypot(offset, h) + X1.translation().norm();
    EXPECT_TRUE(result.feature == DiskPairFeature::face1_rim2 ||
                result.feature == DiskPairFeature::rim1_face2);
    EXPECT_NEAR(result.distance, std::abs(h), 1e-13 * scale);
    EXPECT_LE(result.certifiedGap(), 1e-14 * scale);
    const double middle = 0.5 * (std::max(-r1, offset - r2) + std::min(r1, offset + r2));
    EXPECT_LE((result.p_W1 - X1 * Vec3(middle * along)).norm(), 1e-13 * scale);
    EXPECT_LE((result.p_W2 - X1 * Vec3(middle * along + Vec3(0.0, 0.0, h))).norm(), 1e-13 * scale);
  }
}

}  // namespace
