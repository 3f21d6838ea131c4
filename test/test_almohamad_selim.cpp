// Tests of almohamadSelimDiskDistance(): the 1994 report's algorithm as
// published (errata fixed). It returns a real pair of points, so its distance is
// an upper bound; it is exact only in some families. These tests pin both facts:
// the counterexamples reproduce the report's (wrong) values while the duality
// certificate exposes the error, the exact families give the closed-form
// distance, and on random poses the output is a consistent, motion-invariant
// upper bound. See docs/almohamad_selim.md.
#include <fcl_disk/almohamad_selim.h>
#include <fcl_disk/disk_pair.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {

using fcl_disk::almohamadSelimDiskDistance;
using fcl_disk::DiskDistanceResult;
using fcl_disk::DiskPairFeature;
using fcl_disk::dualLowerBound;

using Vec3d = fcl::Vector3<double>;
using Mat3d = fcl::Matrix3<double>;
using Pose = fcl::Transform3<double>;

// Tolerances, absolute, for scenes whose coordinates are at most ~25 (random
// pairs moved by a rigid motion). Observed maxima are about 10x smaller.
template <typename S>
struct Tolerance;

template <>
struct Tolerance<double> {
  // Everything is computed in double: a few roundings of O(25) quantities,
  // ulp(25) = 3.6e-15.
  static constexpr double kExactFamily = 1e-13;  // closed-form families
  static constexpr double kOnDisk = 1e-13;       // a returned point's offset from its disk
  static constexpr double kConsistency = 1e-13;  // |p_W2 - p_W1| vs distance vs lower_bound
  static constexpr double kInvariance = 1e-13;   // after a common rigid motion
  // Random pairs whose Step 3/4 comparison is this close to a tie are skipped in
  // the invariance test: rounding may legitimately flip the branch there.
  static constexpr double kBranchTieMargin = 1e-9;
};

template <>
struct Tolerance<float> {
  // Inputs and outputs are rounded to float (ulp(25) = 1.9e-6), the disks move
  // by that much; the computation itself is in double.
  static constexpr double kExactFamily = 4e-6;
  static constexpr double kOnDisk = 2e-6;
  static constexpr double kConsistency = 4e-6;
  static constexpr double kInvariance = 1e-5;
  static constexpr double kBranchTieMargin = 1e-3;
};

// How far the counterexamples' reference values (to 6 digits) are trusted.
constexpr double kReferenceValueTolerance = 1e-6;
// Rim samples for the in-test check of the counterexamples' true distances:
// sampling error ~ r (2 pi / n)^2 / 8 ~ 5e-10 for r = 1.
constexpr int kRimSamples = 200000;
constexpr unsigned kRandomSeed = 19940301;  // fixed: the tests are deterministic
constexpr int kRandomPairs = 2000;

/// A rotation whose third column (the disk normal) is n/|n|, with u along the
/// component of `in_plane_hint` orthogonal to n.
Mat3d rotationWithNormal(Vec3d n, const Vec3d& in_plane_hint = Vec3d::UnitX()) {
  n.normalize();
  // Below this the hint is too close to parallel to n to give a stable u.
  constexpr double kMinHintComponent = 1e-3;
  Vec3d hint = in_plane_hint - in_plane_hint.dot(n) * n;
  if (hint.norm() < kMinHintComponent) hint = Vec3d::UnitY() - Vec3d::UnitY().dot(n) * n;
  const Vec3d u = hint.normalized();
  Mat3d R;
  R.col(0) = u;
  R.col(1) = n.cross(u);
  R.col(2) = n;
  return R;
}

Pose makePose(const Mat3d& R, const Vec3d& c) {
  Pose X = Pose::Identity();
  X.linear() = R;
  X.translation() = c;
  return X;
}

Mat3d randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> gauss;
  const Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
  return q.normalized().toRotationMatrix();
}

/// A fixed generic rigid motion, so the families are not only tested in
/// axis-aligned frames.
Pose genericMotion() {
  const Eigen::AngleAxisd rotation(0.7, Vec3d(1.0, -2.0, 0.5).normalized());
  return makePose(rotation.toRotationMatrix(), Vec3d(3.0, -1.5, 2.0));
}

/// Closed-form distance from point x to the disk (radius r, pose X) in double.
double pointToDiskDistance(const Vec3d& x, double r, const Pose& X) {
  const Vec3d local = X.linear().transpose() * (x - X.translation());
  const double in_plane = std::hypot(local.x(), local.y());
  return std::hypot(std::max(in_plane - r, 0.0), local.z());
}

/// A pair of points on the disks found by sampling both rims, and the duality
/// certificate at its direction: together they bracket the true distance
/// (one of the nearest points of two disks always lies on a rim).
struct Bracket {
  double upper;
  double lower;
};
Bracket bracketTrueDistance(double r1, const Pose& X1, double r2, const Pose& X2) {
  double best = std::numeric_limits<double>::infinity();
  Vec3d best_from_1_to_2 = Vec3d::UnitZ();
  const auto scanRim = [&](double r_rim, const Pose& X_rim, double r_disk, const Pose& X_disk,
                           double sign) {
    for (int i = 0; i < kRimSamples; ++i) {
      const double angle = 2.0 * M_PI * i / kRimSamples;
      const Vec3d rim_point = X_rim * Vec3d(r_rim * std::cos(angle), r_rim * std::sin(angle), 0.0);
      Vec3d local = X_disk.linear().transpose() * (rim_point - X_disk.translation());
      const double in_plane = std::hypot(local.x(), local.y());
      if (in_plane > r_disk) local.head<2>() *= r_disk / in_plane;
      local.z() = 0.0;
      const Vec3d disk_point = X_disk * local;
      const double d = (rim_point - disk_point).norm();
      if (d < best) {
        best = d;
        best_from_1_to_2 = sign * (rim_point - disk_point);
      }
    }
  };
  scanRim(r1, X1, r2, X2, -1.0);  // rim point on disk 1: direction disk point - rim point
  scanRim(r2, X2, r1, X1, +1.0);
  return {best, dualLowerBound<double>(best_from_1_to_2.normalized(), r1, X1, r2, X2)};
}

template <typename S>
DiskDistanceResult<S> run(double r1, const Pose& X1, double r2, const Pose& X2) {
  return almohamadSelimDiskDistance<S>(static_cast<S>(r1), X1.cast<S>(), static_cast<S>(r2),
                                       X2.cast<S>());
}

/// Offset of p from the disk (radius r, pose X): its height above the plane and
/// how far its in-plane radius exceeds r.
struct OffDisk {
  double height;
  double outside_rim;
};
template <typename S>
OffDisk offDisk(const fcl::Vector3<S>& p, double r, const Pose& X) {
  const Vec3d local = X.linear().transpose() * (p.template cast<double>() - X.translation());
  return {std::abs(local.z()), std::hypot(local.x(), local.y()) - r};
}

template <typename S>
class AlmohamadSelimTest : public ::testing::Test {};
using ScalarTypes = ::testing::Types<float, double>;
TYPED_TEST_SUITE(AlmohamadSelimTest, ScalarTypes);

// Counterexample A (facts.md): the report answers 0.4, the true distance is
// 0.5 - 1/sqrt5: K2's highest rim point lies 0.0528 below K1's interior.
TYPED_TEST(AlmohamadSelimTest, CounterexampleAGivesReportValueAndCertificateShowsError) {
  using S = TypeParam;
  const Pose X1 = Pose::Identity();
  const Pose X2 = makePose(rotationWithNormal(Vec3d(0, 1, 2)), Vec3d(0, 0, -0.5));
  const double kReportValue = 0.4;
  const double kTrueDistance = 0.5 - 1.0 / std::sqrt(5.0);  // 0.052786

  // The true value, independently of any solver: sampled rims bracket it.
  const Bracket bracket = bracketTrueDistance(1.0, X1, 1.0, X2);
  EXPECT_NEAR(bracket.upper, kTrueDistance, kReferenceValueTolerance);
  EXPECT_NEAR(bracket.lower, kTrueDistance, kReferenceValueTolerance);

  const DiskDistanceResult<S> result = run<S>(1.0, X1, 1.0, X2);
  EXPECT_NEAR(result.distance, kReportValue, Tolerance<S>::kExactFamily);
  EXPECT_LE(result.lower_bound, kTrueDistance + kReferenceValueTolerance);
  EXPECT_GE(result.certifiedGap(), kReportValue - kTrueDistance - kReferenceValueTolerance);
  // Step 3 returns M0* = (0, -0.2, 0) inside K1 and W0* = (0, -0.2, -0.4) inside K2.
  EXPECT_EQ(result.feature, DiskPairFeature::face1_rim2);
}

// Counterexample B (facts.md): the report answers 0.353553 = 1/(2 sqrt2), the
// true (rim-rim) distance is 0.062393.
TYPED_TEST(AlmohamadSelimTest, CounterexampleBGivesReportValueAndCertificateShowsError) {
  using S = TypeParam;
  const Pose X1 = makePose(rotationWithNormal(Vec3d(0, 1, 0)), Vec3d::Zero());
  const Pose X2 = makePose(rotationWithNormal(Vec3d(1, 0, 1)), Vec3d(-1.5, 0, 0));
  const double kReportValue = 0.5 / std::sqrt(2.0);  // 0.353553
  const double kTrueDistance = 0.062393;

  const Bracket bracket = bracketTrueDistance(1.0, X1, 1.0, X2);
  EXPECT_NEAR(bracket.upper, kTrueDistance, kReferenceValueTolerance);
  EXPECT_NEAR(bracket.lower, kTrueDistance, kReferenceValueTolerance);

  const DiskDistanceResult<S> result = run<S>(1.0, X1, 1.0, X2);
  EXPECT_NEAR(result.distance, kReportValue, Tolerance<S>::kExactFamily);
  EXPECT_LE(result.lower_bound, kTrueDistance + kReferenceValueTolerance);
  EXPECT_GE(result.certifiedGap(), kReportValue - kTrueDistance - kReferenceValueTolerance);
}

// Coaxial stacks: parallel planes, centres on the common axis. Both centres are
// on the other disk's axis (Prop. 1/2 tie-break: in-plane norm 0 -> Case 2) and
// d(O, W0*) == d(Mp*, P) == h^2 (tie -> Step 4): the answer is the two centres.
TYPED_TEST(AlmohamadSelimTest, CoaxialStacksAreExact) {
  using S = TypeParam;
  const double kHeights[] = {0.3, 1.0, 2.5, -0.7};
  const double kRadiusPairs[][2] = {{1.0, 1.0}, {0.5, 2.0}, {2.0, 0.5}};
  const Vec3d kNormals2[] = {Vec3d::UnitZ(), -Vec3d::UnitZ()};
  const double kTwist = 0.4;  // in-plane rotation of disk 2: must not matter
  for (const Pose& motion : {Pose(Pose::Identity()), genericMotion()}) {
    for (double h : kHeights) {
      for (const auto& radii : kRadiusPairs) {
        for (const Vec3d& n2 : kNormals2) {
          const Pose X1 = motion * Pose::Identity();
          const Pose X2 =
              motion * makePose(rotationWithNormal(n2, Vec3d(std::cos(kTwist), std::sin(kTwist), 0)),
                                Vec3d(0, 0, h));
          const DiskDistanceResult<S> result = run<S>(radii[0], X1, radii[1], X2);
          SCOPED_TRACE(::testing::Message() << "h=" << h << " r1=" << radii[0] << " r2=" << radii[1]);
          EXPECT_NEAR(result.distance, std::abs(h), Tolerance<S>::kExactFamily);
          EXPECT_NEAR(result.lower_bound, std::abs(h), Tolerance<S>::kExactFamily);
          EXPECT_LE((result.p_W1.template cast<double>() - X1.translation()).norm(),
                    Tolerance<S>::kExactFamily);
          EXPECT_LE((result.p_W2.template cast<double>() - X2.translation()).norm(),
                    Tolerance<S>::kExactFamily);
          EXPECT_EQ(result.feature, DiskPairFeature::face1_rim2);
        }
      }
    }
  }
}

// Coplanar pairs: apart, the distance is L - r1 - r2 along the line of centres;
// overlapping (concentric included), it is 0.
TYPED_TEST(AlmohamadSelimTest, CoplanarPairsAreExact) {
  using S = TypeParam;
  const double kRadiusPairs[][2] = {{1.0, 1.0}, {0.5, 2.0}, {2.0, 0.5}};
  const double kCentreFractions[] = {0.0, 0.3, 0.99, 1.01, 1.5, 4.0};  // L / (r1 + r2)
  const double kDirection = 2.2;  // angle of the line of centres in the plane
  for (const Pose& motion : {Pose(Pose::Identity()), genericMotion()}) {
    for (const auto& radii : kRadiusPairs) {
      for (double fraction : kCentreFractions) {
        for (const Vec3d& n2 : {Vec3d(Vec3d::UnitZ()), Vec3d(-Vec3d::UnitZ())}) {
          const double L = fraction * (radii[0] + radii[1]);
          const Pose X1 = motion * Pose::Identity();
          const Pose X2 = motion * makePose(rotationWithNormal(n2),
                                            L * Vec3d(std::cos(kDirection), std::sin(kDirection), 0));
          const double expected = std::max(L - radii[0] - radii[1], 0.0);
          const DiskDistanceResult<S> result = run<S>(radii[0], X1, radii[1], X2);
          SCOPED_TRACE(::testing::Message() << "L=" << L << " r1=" << radii[0] << " r2=" << radii[1]);
          EXPECT_NEAR(result.distance, expected, Tolerance<S>::kExactFamily);
          EXPECT_LE(result.lower_bound, expected + Tolerance<S>::kExactFamily);
          if (expected > 0) {
            EXPECT_NEAR(result.lower_bound, expected, Tolerance<S>::kExactFamily);
            EXPECT_EQ(result.feature, DiskPairFeature::rim_rim);
          }
        }
      }
    }
  }
}

// Perpendicular pairs where Lemma 1 holds: (a) K2 upright above K1's centre,
// nearest points K1's centre and K2's lowest point; (b) K2 upright beside K1,
// crossing K1's plane, nearest points on the line of centres.
TYPED_TEST(AlmohamadSelimTest, PerpendicularConfigurationsWhereLemmaHoldsAreExact) {
  using S = TypeParam;
  const double kRadiusPairs[][2] = {{1.0, 1.0}, {0.5, 2.0}, {2.0, 0.5}};
  const double kGaps[] = {0.05, 0.5, 3.0};
  for (const Pose& motion : {Pose(Pose::Identity()), genericMotion()}) {
    for (const auto& radii : kRadiusPairs) {
      for (double gap : kGaps) {
        const double r1 = radii[0];
        const double r2 = radii[1];
        SCOPED_TRACE(::testing::Message() << "gap=" << gap << " r1=" << r1 << " r2=" << r2);
        const Pose X1 = motion * Pose::Identity();
        const Pose X2_above = motion * makePose(rotationWithNormal(Vec3d::UnitX(), Vec3d::UnitY()),
                                                Vec3d(0, 0, r2 + gap));
        const Pose X2_beside = motion * makePose(rotationWithNormal(Vec3d::UnitY()),
                                                 Vec3d(r1 + r2 + gap, 0, 0));
        for (const Pose& X2 : {X2_above, X2_beside}) {
          const DiskDistanceResult<S> result = run<S>(r1, X1, r2, X2);
          EXPECT_NEAR(result.distance, gap, Tolerance<S>::kExactFamily);
          EXPECT_NEAR(result.lower_bound, gap, Tolerance<S>::kExactFamily);
        }
      }
    }
  }
}

// The report compares d(O, W0*) < d(Mp*, P) strictly, so an exact tie goes to
// Step 4. Here the tie is exact in floating point (|R^T P|_xy = hypot(3, 4) = 5,
// (5 - 1)^2 = 4^2) and the branches differ: K2 stands upright in the XZ plane
// above K1's interior. Step 4 (Mp* = (3,0,0), Wp* = K2's lowest point (3,0,3))
// gives the true distance 3; Step 3 would give (2.4,0,0)-(2.4,0,3.2), 3.2.
TYPED_TEST(AlmohamadSelimTest, ExactTieGoesToStep4) {
  using S = TypeParam;
  const double kR1 = 4.0;
  const double kR2 = 1.0;
  const Pose X1 = Pose::Identity();
  const Pose X2 = makePose(rotationWithNormal(Vec3d::UnitY(), Vec3d::UnitX()), Vec3d(3, 0, 4));
  const DiskDistanceResult<S> result = run<S>(kR1, X1, kR2, X2);
  EXPECT_EQ(result.distance, S(3));
  EXPECT_EQ(result.p_W1, fcl::Vector3<S>(3, 0, 0));
  EXPECT_EQ(result.p_W2, fcl::Vector3<S>(3, 0, 3));
  EXPECT_EQ(result.feature, DiskPairFeature::face1_rim2);
}

// Random poses: a real pair of points, distance consistent with it, above the
// certificate, and covariant under a common rigid motion.
TYPED_TEST(AlmohamadSelimTest, RandomPosesGiveConsistentInvariantUpperBound) {
  using S = TypeParam;
  using Tol = Tolerance<S>;
  std::mt19937 rng(kRandomSeed);
  std::uniform_real_distribution<double> coordinate(-3.0, 3.0);
  std::uniform_real_distribution<double> radius(0.2, 1.5);
  std::uniform_real_distribution<double> motion_offset(-10.0, 10.0);
  int invariance_checked = 0;
  for (int i = 0; i < kRandomPairs; ++i) {
    const double r1 = radius(rng);
    const double r2 = radius(rng);
    const Pose X1 = makePose(randomRotation(rng), Vec3d(coordinate(rng), coordinate(rng), coordinate(rng)));
    const Pose X2 = makePose(randomRotation(rng), Vec3d(coordinate(rng), coordinate(rng), coordinate(rng)));
    const Pose motion = makePose(randomRotation(rng),
                                 Vec3d(motion_offset(rng), motion_offset(rng), motion_offset(rng)));
    SCOPED_TRACE(::testing::Message() << "pair " << i);

    const DiskDistanceResult<S> result = run<S>(r1, X1, r2, X2);
    const OffDisk off1 = offDisk(result.p_W1, r1, X1);
    const OffDisk off2 = offDisk(result.p_W2, r2, X2);
    EXPECT_LE(off1.height, Tol::kOnDisk);
    EXPECT_LE(off1.outside_rim, Tol::kOnDisk);
    EXPECT_LE(off2.height, Tol::kOnDisk);
    EXPECT_LE(off2.outside_rim, Tol::kOnDisk);
    EXPECT_NEAR((result.p_W2 - result.p_W1).template cast<double>().norm(), result.distance,
                Tol::kConsistency);
    EXPECT_GE(result.distance, result.lower_bound - Tol::kConsistency);
    EXPECT_EQ(result.iterations, 0);

    // Step 3 vs Step 4 compares d(c1, K2) with d(c2, K1); near a tie rounding
    // may pick the other branch, whose answer differs, so skip those pairs.
    const double branch_margin =
        std::abs(pointToDiskDistance(X1.translation(), r2, X2) - pointToDiskDistance(X2.translation(), r1, X1));
    if (branch_margin < Tol::kBranchTieMargin) continue;
    ++invariance_checked;
    const DiskDistanceResult<S> moved = run<S>(r1, motion * X1, r2, motion * X2);
    EXPECT_NEAR(moved.distance, result.distance, Tol::kInvariance);
    EXPECT_LE((moved.p_W1.template cast<double>() - motion * result.p_W1.template cast<double>()).norm(),
              Tol::kInvariance);
    EXPECT_LE((moved.p_W2.template cast<double>() - motion * result.p_W2.template cast<double>()).norm(),
              Tol::kInvariance);
  }
  EXPECT_GT(invariance_checked, kRandomPairs * 9 / 10);  // near-ties are rare
}

// Non-finite input must not crash; the distance and the bound are then NaN.
TYPED_TEST(AlmohamadSelimTest, NanInputGivesNanWithoutCrashing) {
  using S = TypeParam;
  const S nan = std::numeric_limits<S>::quiet_NaN();
  const fcl::Transform3<S> X1 = fcl::Transform3<S>::Identity();
  fcl::Transform3<S> X2 = fcl::Transform3<S>::Identity();
  X2.translation() << S(5), S(0), S(0);
  fcl::Transform3<S> X2_nan_centre = X2;
  X2_nan_centre.translation().x() = nan;
  fcl::Transform3<S> X2_nan_rotation = X2;
  X2_nan_rotation.linear()(0, 0) = nan;

  const DiskDistanceResult<S> results[] = {
      almohamadSelimDiskDistance<S>(S(1), X1, S(1), X2_nan_centre),
      almohamadSelimDiskDistance<S>(S(1), X1, S(1), X2_nan_rotation),
      almohamadSelimDiskDistance<S>(nan, X1, S(1), X2),
      almohamadSelimDiskDistance<S>(S(1), X1, std::numeric_limits<S>::infinity(), X2),
  };
  for (const DiskDistanceResult<S>& result : results) {
    EXPECT_TRUE(std::isnan(result.distance));
    EXPECT_TRUE(std::isnan(result.lower_bound));
  }
}

}  // namespace
