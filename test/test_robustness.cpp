// Bad input: invalid radii, NaN and infinite poses, rotations that are not
// orthonormal, through the solvers, the intersection test and every FCL entry
// point that can see a Disk (docs/robustness.md). Debian's FCL aborts on NaN in
// GJK, so every test here that reaches FCL with a NaN would crash the process if
// a guard were missing.
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <fcl_disk/fcl_disk.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "pair_in_frame1.h"  // src/: TransposedProduct
#include "test_random.h"

namespace {

template <typename S>
using Transform3 = fcl::Transform3<S>;
template <typename S>
using Vector3 = fcl::Vector3<S>;

template <typename S>
Transform3<S> tiltedPose(const Vector3<S>& centre, const Vector3<S>& normal) {
  Transform3<S> X = Transform3<S>::Identity();
  X.translation() = centre;
  X.linear() = Eigen::Quaternion<S>::FromTwoVectors(Vector3<S>::UnitZ(), normal.normalized())
                   .toRotationMatrix();
  return X;
}

/// A separated, a crossing and a coplanar-overlapping pair: every answer path.
template <typename S>
std::vector<std::pair<Transform3<S>, Transform3<S>>> basePairs() {
  return {{tiltedPose<S>({0, 0, 0}, {0, 0, 1}), tiltedPose<S>({0.5, 0.2, 1.5}, {1, 2, 3})},
          {tiltedPose<S>({0, 0, 0}, {0, 0, 1}), tiltedPose<S>({0.3, 0, 0.1}, {1, 0, 0})},
          {tiltedPose<S>({0, 0, 0}, {0, 0, 1}), tiltedPose<S>({0.8, 0, 0}, {0, 0, 1})}};
}

/// Every single-entry corruption of a pose by a non-finite value: each
/// translation and rotation entry, set to NaN, +inf and -inf.
template <typename S>
std::vector<std::pair<std::string, Transform3<S>>> nonFiniteVariants(const Transform3<S>& X) {
  const S values[] = {std::numeric_limits<S>::quiet_NaN(), std::numeric_limits<S>::infinity(),
                      -std::numeric_limits<S>::infinity()};
  std::vector<std::pair<std::string, Transform3<S>>> out;
  for (S value : values) {
    for (int row = 0; row < 3; ++row) {
      for (int col = 0; col < 4; ++col) {
        Transform3<S> bad = X;
        bad.matrix()(row, col) = value;
        out.emplace_back("entry (" + std::to_string(row) + "," + std::to_string(col) + ") = " +
                             std::to_string(double(value)),
                         bad);
      }
    }
  }
  return out;
}

template <typename S>
void expectAllNaN(const fcl_disk::DiskDistanceResult<S>& r) {
  EXPECT_TRUE(std::isnan(r.distance));
  EXPECT_TRUE(std::isnan(r.lower_bound));
  EXPECT_TRUE(r.p_W1.array().isNaN().all());
  EXPECT_TRUE(r.p_W2.array().isNaN().all());
}

/// What every entry point must answer for a pair that describes no disk pair:
/// NaN from both solvers, no intersection, NaN through fcl::distance (objects and
/// geometries, both GJK solver types, signed and unsigned) and no contact from
/// fcl::collide.
template <typename S>
void expectNoAnswerAnywhere(S r1, const Transform3<S>& X1, S r2, const Transform3<S>& X2) {
  expectAllNaN(fcl_disk::exactDiskDistance(r1, X1, r2, X2));
  expectAllNaN(fcl_disk::almohamadSelimDiskDistance(r1, X1, r2, X2));
  EXPECT_FALSE(fcl_disk::intersectDisks(r1, X1, r2, X2));
  if (!(fcl_disk::isValidDiskRadius(r1) && fcl_disk::isValidDiskRadius(r2))) return;  // no Disk
  auto disk1 = std::make_shared<fcl_disk::Disk<S>>(r1);
  auto disk2 = std::make_shared<fcl_disk::Disk<S>>(r2);
  fcl::CollisionObject<S> a(disk1, X1), b(disk2, X2);
  for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
    for (bool signed_distance : {false, true}) {
      fcl::DistanceRequest<S> request;
      request.gjk_solver_type = solver;
      request.enable_signed_distance = signed_distance;
      fcl::DistanceResult<S> by_objects, by_geometries;
      EXPECT_TRUE(std::isnan(fcl::distance(&a, &b, request, by_objects)));
      EXPECT_TRUE(std::isnan(by_objects.min_distance));
      EXPECT_TRUE(by_objects.nearest_points[0].array().isNaN().all());
      EXPECT_TRUE(std::isnan(
          fcl::distance(disk1.get(), X1, disk2.get(), X2, request, by_geometries)));
      EXPECT_TRUE(std::isnan(by_geometries.min_distance));
    }
    fcl::CollisionRequest<S> request;
    request.gjk_solver_type = solver;
    request.enable_contact = true;
    fcl::CollisionResult<S> result;
    EXPECT_EQ(fcl::collide(&a, &b, request, result), 0u);
    EXPECT_FALSE(result.isCollision());
  }
}

template <typename S>
class Robustness : public ::testing::Test {};
using ScalarTypes = ::testing::Types<float, double>;
TYPED_TEST_SUITE(Robustness, ScalarTypes);

TYPED_TEST(Robustness, InvalidRadiusThrowsNamingTheValue) {
  using S = TypeParam;
  const S too_small = fcl_disk::kMinDiskRadius<S> / S(2);
  const S too_large = fcl_disk::kMaxDiskLength<S> * S(2);
  for (S radius : {S(0), S(-1.5), std::numeric_limits<S>::quiet_NaN(),
                   std::numeric_limits<S>::infinity(), -std::numeric_limits<S>::infinity(),
                   too_small, too_large, std::numeric_limits<S>::denorm_min(),
                   std::numeric_limits<S>::max()}) {
    try {
      fcl_disk::Disk<S> disk(radius);
      ADD_FAILURE() << "no exception for radius " << radius;
    } catch (const std::invalid_argument& error) {
      std::ostringstream value;
      value << radius;
      EXPECT_NE(std::string(error.what()).find(value.str()), std::string::npos) << error.what();
    }
  }
}

TYPED_TEST(Robustness, RadiusRangeEndsAreDisks) {
  using S = TypeParam;
  for (S radius : {fcl_disk::kMinDiskRadius<S>, fcl_disk::kMaxDiskLength<S>}) {
    EXPECT_NO_THROW(fcl_disk::Disk<S> disk(radius)) << radius;
  }
}

TYPED_TEST(Robustness, InvalidRadiusInSolversGivesNaN) {
  using S = TypeParam;
  for (const auto& [X1, X2] : basePairs<S>()) {
    for (S radius : {S(0), S(-1), std::numeric_limits<S>::quiet_NaN(),
                     std::numeric_limits<S>::infinity(), fcl_disk::kMinDiskRadius<S> / S(2),
                     fcl_disk::kMaxDiskLength<S> * S(2)}) {
      SCOPED_TRACE(radius);
      expectNoAnswerAnywhere<S>(radius, X1, S(1), X2);
      expectNoAnswerAnywhere<S>(S(1), X1, radius, X2);
    }
  }
}

TYPED_TEST(Robustness, NonFinitePoseGivesNaNEverywhere) {
  using S = TypeParam;
  for (const auto& [X1, X2] : basePairs<S>()) {
    for (const auto& [what, bad] : nonFiniteVariants<S>(X1)) {
      SCOPED_TRACE("disk 1 " + what);
      expectNoAnswerAnywhere<S>(S(1), bad, S(0.7), X2);
    }
    for (const auto& [what, bad] : nonFiniteVariants<S>(X2)) {
      SCOPED_TRACE("disk 2 " + what);
      expectNoAnswerAnywhere<S>(S(1), X1, S(0.7), bad);
    }
  }
}

// Squares of lengths beyond kMaxDiskLength overflow inside the solvers: a
// translation out of range is invalid input (NaN), never a made-up inf or 0.
// At the range's ends the answers are finite and exact: two disks of radius
// kMaxDiskLength / 4 a full kMaxDiskLength apart along x (one at -max/2, one at
// +max/2), and two disks of radius kMinDiskRadius 3 * kMinDiskRadius apart.
TYPED_TEST(Robustness, TranslationOutOfRangeGivesNaN) {
  using S = TypeParam;
  const S too_far = fcl_disk::kMaxDiskLength<S> * S(2);
  for (const auto& [X1, X2] : basePairs<S>()) {
    for (int axis = 0; axis < 3; ++axis) {
      for (S value : {too_far, -too_far}) {
        SCOPED_TRACE("axis " + std::to_string(axis) + " = " + std::to_string(double(value)));
        Transform3<S> bad = X2;
        bad.translation()[axis] = value;
        expectNoAnswerAnywhere<S>(S(1), X1, S(0.7), bad);
        expectNoAnswerAnywhere<S>(S(1), bad, S(0.7), X1);
      }
    }
  }
}

TYPED_TEST(Robustness, RangeEndsGiveExactAnswers) {
  using S = TypeParam;
  const S big = fcl_disk::kMaxDiskLength<S>;
  const S tiny = fcl_disk::kMinDiskRadius<S>;
  const struct {
    S radius;
    S x1, x2;
    S distance;
  } cases[] = {{big / 4, -big / 2, big / 2, big / 2}, {tiny, S(0), 3 * tiny, tiny}};
  for (const auto& c : cases) {
    Transform3<S> X1 = Transform3<S>::Identity(), X2 = Transform3<S>::Identity();
    X1.translation().x() = c.x1;
    X2.translation().x() = c.x2;
    // Coplanar along x: the distance is x2 - x1 - 2 r, the points on the rims.
    for (const auto& result : {fcl_disk::exactDiskDistance(c.radius, X1, c.radius, X2),
                               fcl_disk::almohamadSelimDiskDistance(c.radius, X1, c.radius, X2)}) {
      EXPECT_NEAR(result.distance, c.distance, 4 * std::numeric_limits<S>::epsilon() * c.distance);
      EXPECT_NEAR(result.p_W2.x() - result.p_W1.x(), c.distance,
                  4 * std::numeric_limits<S>::epsilon() * c.distance);
    }
    EXPECT_FALSE(fcl_disk::intersectDisks(c.radius, X1, c.radius, X2));
    auto disk1 = std::make_shared<fcl_disk::Disk<S>>(c.radius);
    auto disk2 = std::make_shared<fcl_disk::Disk<S>>(c.radius);
    fcl::DistanceRequest<S> request;
    fcl::DistanceResult<S> result;
    EXPECT_NEAR(fcl::distance(disk1.get(), X1, disk2.get(), X2, request, result), c.distance,
                4 * std::numeric_limits<S>::epsilon() * c.distance);
  }
}

// A Disk's radius is a public member of fcl::Cylinder; one set to NaN after
// construction must still give NaN, not a made-up number.
TYPED_TEST(Robustness, RadiusCorruptedAfterConstructionGivesNaN) {
  using S = TypeParam;
  auto disk1 = std::make_shared<fcl_disk::Disk<S>>(S(1));
  auto disk2 = std::make_shared<fcl_disk::Disk<S>>(S(1));
  auto sphere = std::make_shared<fcl::Sphere<S>>(S(0.5));
  disk1->radius = std::numeric_limits<S>::quiet_NaN();
  const auto [X1, X2] = basePairs<S>().front();
  for (auto other : {std::shared_ptr<fcl::CollisionGeometry<S>>(disk2),
                     std::shared_ptr<fcl::CollisionGeometry<S>>(sphere)}) {
    fcl::CollisionObject<S> a(disk1, X1), b(other, X2);
    fcl::DistanceRequest<S> request;
    fcl::DistanceResult<S> result;
    EXPECT_TRUE(std::isnan(fcl::distance(&a, &b, request, result)));
    fcl::CollisionRequest<S> collision_request;
    fcl::CollisionResult<S> collision_result;
    EXPECT_EQ(fcl::collide(&a, &b, collision_request, collision_result), 0u);
  }
}

/// The shapes FCL pairs a Disk with through its GEOM_CYLINDER row and column.
template <typename S>
std::vector<std::pair<std::string, std::shared_ptr<fcl::CollisionGeometry<S>>>> otherShapes() {
  return {{"sphere", std::make_shared<fcl::Sphere<S>>(S(0.4))},
          {"box", std::make_shared<fcl::Box<S>>(S(0.3), S(0.6), S(0.2))},
          {"capsule", std::make_shared<fcl::Capsule<S>>(S(0.2), S(0.5))},
          {"cone", std::make_shared<fcl::Cone<S>>(S(0.3), S(0.5))},
          {"ellipsoid", std::make_shared<fcl::Ellipsoid<S>>(S(0.3), S(0.4), S(0.5))},
          {"cylinder", std::make_shared<fcl::Cylinder<S>>(S(0.3), S(0.5))}};
}

// FCL's GJK asserts on NaN (Debian keeps asserts): a NaN pose on either side of
// a Disk-versus-shape pair must be answered before FCL sees it.
TYPED_TEST(Robustness, DiskVersusOtherShapesWithNonFinitePoseGivesNaN) {
  using S = TypeParam;
  auto disk = std::make_shared<fcl_disk::Disk<S>>(S(1));
  const auto [X1, X2] = basePairs<S>().front();
  for (const auto& [name, shape] : otherShapes<S>()) {
    for (int corrupt = 0; corrupt < 2; ++corrupt) {
      for (S value : {std::numeric_limits<S>::quiet_NaN(), std::numeric_limits<S>::infinity()}) {
        Transform3<S> disk_pose = X1, shape_pose = X2;
        (corrupt == 0 ? disk_pose : shape_pose).translation().x() = value;
        SCOPED_TRACE(name + (corrupt == 0 ? ": disk pose " : ": shape pose ") +
                     std::to_string(double(value)));
        fcl::CollisionObject<S> disk_object(disk, disk_pose), shape_object(shape, shape_pose);
        for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
          for (bool disk_first : {true, false}) {
            const auto* a = disk_first ? &disk_object : &shape_object;
            const auto* b = disk_first ? &shape_object : &disk_object;
            fcl::DistanceRequest<S> request;
            request.gjk_solver_type = solver;
            fcl::DistanceResult<S> result;
            EXPECT_TRUE(std::isnan(fcl::distance(a, b, request, result)));
            EXPECT_TRUE(std::isnan(result.min_distance));
            fcl::CollisionRequest<S> collision_request;
            collision_request.gjk_solver_type = solver;
            fcl::CollisionResult<S> collision_result;
            EXPECT_EQ(fcl::collide(a, b, collision_request, collision_result), 0u);
          }
        }
      }
    }
  }
}

// Valid poses on the same pairs still reach FCL's own answer (the guard only
// intercepts bad input).
TYPED_TEST(Robustness, DiskVersusOtherShapesWithValidPoseIsAnswered) {
  using S = TypeParam;
  auto disk = std::make_shared<fcl_disk::Disk<S>>(S(1));
  const auto [X1, X2] = basePairs<S>().front();
  for (const auto& [name, shape] : otherShapes<S>()) {
    SCOPED_TRACE(name);
    fcl::CollisionObject<S> a(disk, X1), b(shape, X2);
    fcl::DistanceRequest<S> request;
    fcl::DistanceResult<S> result;
    const S d = fcl::distance(&a, &b, request, result);
    EXPECT_TRUE(std::isfinite(d));
    EXPECT_GT(d, S(0));
  }
}

// ---- rotations that are not orthonormal --------------------------------------

template <typename S>
Transform3<S> withLinear(Transform3<S> X, const fcl::Matrix3<S>& linear) {
  X.linear() = linear;
  return X;
}

TYPED_TEST(Robustness, RotationFarFromOrthonormalGivesNaN) {
  using S = TypeParam;
  // Ten times the tolerance: a scale, a shear, a projection and a zero matrix.
  const S defect = 10 * fcl_disk::kRotationDefectTolerance<S>;
  for (const auto& [X1, X2] : basePairs<S>()) {
    fcl::Matrix3<S> shear = fcl::Matrix3<S>::Identity();
    shear(0, 1) = defect;
    const fcl::Matrix3<S> R = X2.linear();
    const std::vector<std::pair<std::string, fcl::Matrix3<S>>> bad = {
        {"scaled", (1 + defect) * R},
        {"sheared", R * shear},
        {"flattened", R * Vector3<S>(1, 1, 0).asDiagonal()},
        {"zero", fcl::Matrix3<S>::Zero()}};
    for (const auto& [name, linear] : bad) {
      SCOPED_TRACE(name);
      EXPECT_FALSE(fcl_disk::isValidDiskPose(withLinear(X2, linear)));
      expectNoAnswerAnywhere<S>(S(1), X1, S(0.7), withLinear(X2, linear));
      expectNoAnswerAnywhere<S>(S(0.7), withLinear(X2, linear), S(1), X1);
    }
  }
}

/// The orthonormal frame whose third column is the direction of R's (its
/// first column made orthogonal to it, in long double): the disk a rotation
/// within kRotationDefectTolerance stands for, written here apart from the
/// library's own rebuilding.
template <typename S>
Transform3<S> withNormalFrame(const Transform3<S>& X) {
  using Vec = Eigen::Matrix<long double, 3, 1>;
  const Eigen::Matrix<long double, 3, 3> R = X.linear().template cast<long double>();
  const Vec n = R.col(2) / R.col(2).norm();
  Vec u = R.col(0) - n.dot(R.col(0)) * n;
  u /= u.norm();
  Eigen::Matrix<long double, 3, 3> frame;
  frame << u, n.cross(u), n;
  return withLinear<S>(X, fcl::Matrix3<S>(frame.template cast<S>()));
}

// A disk is its centre, normal and radius: a rotation within the tolerance (a
// scale, a shear of the in-plane axes, a tilt of the third column alone) gives
// the distance and contact verdict of the disk with that normal, and the
// certificate closes as for an orthonormal rotation. In double the
// perturbation is a float rotation's size (1e-7, a rotation built in float and
// widened), in float a quarter of the tolerance.
TYPED_TEST(Robustness, RotationWithinToleranceIsTheDiskOfItsNormal) {
  using S = TypeParam;
  const S delta = std::is_same<S, float>::value ? fcl_disk::kRotationDefectTolerance<S> / 4
                                                : S(1e-7);
  // The answers for the disk of the normal, each in S: double to the solver's
  // 1e-12; float to a few ulps of the scene, the two poses (perturbed and
  // rebuilt) each rounded to float.
  const double relative = std::is_same<S, float>::value ? 32 * 1.2e-7 : 1e-12;
  for (const auto& [X1, X2] : basePairs<S>()) {
    const fcl::Matrix3<S> R = X2.linear();
    fcl::Matrix3<S> scaled = (1 + delta) * R, sheared = R, tilted = R;
    sheared.col(0) += delta * R.col(1);
    sheared.col(1) += delta * R.col(2);
    tilted.col(2) += delta * R.col(0);
    for (const fcl::Matrix3<S>& linear : {scaled, sheared, tilted}) {
      const Transform3<S> X2_off = withLinear<S>(X2, linear);
      ASSERT_TRUE(fcl_disk::isValidDiskPose(X2_off));
      const Transform3<S> X2_disk = withNormalFrame(X2_off);
      const double scale = 1 + 0.7 + double((X2.translation() - X1.translation()).norm());
      for (const bool swap : {false, true}) {
        const auto off = swap ? fcl_disk::exactDiskDistance<S>(S(0.7), X2_off, S(1), X1)
                              : fcl_disk::exactDiskDistance<S>(S(1), X1, S(0.7), X2_off);
        const auto disk = swap ? fcl_disk::exactDiskDistance<S>(S(0.7), X2_disk, S(1), X1)
                               : fcl_disk::exactDiskDistance<S>(S(1), X1, S(0.7), X2_disk);
        ASSERT_TRUE(std::isfinite(off.distance));
        EXPECT_NEAR(double(off.distance), double(disk.distance), relative * scale);
        EXPECT_LE(double(off.certifiedGap()), relative * scale);
        if (off.distance > relative * scale) {
          EXPECT_FALSE(fcl_disk::intersectDisks<S>(S(1), X1, S(0.7), X2_off));
        } else if (disk.distance == 0) {
          EXPECT_TRUE(fcl_disk::intersectDisks<S>(S(1), X1, S(0.7), X2_off));
        }
      }
    }
  }
}

// checkDiskPose and checkTwoPoses (both poses of a query in one pass), in
// SSE2's two lanes in double and in float, and the entry-by-entry rule give
// the same verdicts: on rotations perturbed entry by entry around both tolerances
// (defects from 1e-17 (double) or 1e-9 (float) to 1e-4 or 1e-3, either sign),
// on every non-finite entry and on translations around kMaxDiskLength;
// checkTwoPoses on each such pose paired with the one before, in both orders.
template <typename S>
void expectTwoLaneFormsMatchTheRule(std::uint64_t seed) {
  using fcl_disk::internal::checkDiskPose;
  using fcl_disk::internal::checkDiskPoseOneByOne;
  using fcl_disk::internal::checkTwoPoses;
  using Transform = fcl::Transform3<S>;
  constexpr bool kDouble = std::is_same_v<S, double>;
  fcl_disk_test::Random random(seed);
  // The solvers ask for 1e-13 (their as-given tolerance in double) and -1
  // (never, in float); one more threshold inside the draws' range.
  const S tolerances[] = {kDouble ? S(1e-13) : S(1e-6), kDouble ? S(1e-9) : S(1e-5), S(-1)};
  const double smallest_defect = kDouble ? 1e-17 : 1e-9, largest_defect = kDouble ? 1e-4 : 1e-3;
  int valid = 0, invalid = 0, orthonormal = 0, pairs_valid = 0, pairs_invalid = 0;
  Transform previous = Transform::Identity();
  const auto expect_same = [&](const Transform& X) {
    for (const S tolerance : tolerances) {
      const auto two_lanes = checkDiskPose(X, tolerance);
      const auto rule = checkDiskPoseOneByOne(X, tolerance);
      ASSERT_EQ(two_lanes.valid, rule.valid) << X.matrix();
      if (rule.valid) {
        ASSERT_EQ(two_lanes.orthonormal, rule.orthonormal) << X.matrix();
        orthonormal += rule.orthonormal;
      }
      (rule.valid ? valid : invalid) += 1;
      const auto rule_previous = checkDiskPoseOneByOne(previous, tolerance);
      const bool both_valid = rule.valid && rule_previous.valid;
      for (const bool x_first : {true, false}) {
        const auto both = x_first ? checkTwoPoses(X, previous, tolerance)
                                  : checkTwoPoses(previous, X, tolerance);
        ASSERT_EQ(both.valid, both_valid) << X.matrix() << "\n" << previous.matrix();
        if (both_valid) {
          ASSERT_EQ(x_first ? both.orthonormal_a : both.orthonormal_b, rule.orthonormal);
          ASSERT_EQ(x_first ? both.orthonormal_b : both.orthonormal_a, rule_previous.orthonormal);
        }
      }
      (both_valid ? pairs_valid : pairs_invalid) += 1;
    }
    previous = X;
  };
  for (int i = 0; i < 20000; ++i) {
    Transform X = Transform::Identity();
    X.linear() = random.rotation().template cast<S>();
    X.translation() = random.inBall(random.logUniform(1e-3, 1e3)).template cast<S>();
    const int entries = 1 + int(random.uniform01() * 3);
    for (int e = 0; e < entries; ++e) {
      const int row = int(random.uniform01() * 3), col = int(random.uniform01() * 3);
      const double sign = random.chance(0.5) ? 1.0 : -1.0;
      X.matrix()(row, col) += S(sign * random.logUniform(smallest_defect, largest_defect));
    }
    expect_same(X);
  }
  const Transform X = tiltedPose<S>({0.3, -0.2, 0.1}, {1, 2, 3});
  for (const auto& variant : nonFiniteVariants<S>(X)) expect_same(variant.second);
  const S length = fcl_disk::kMaxDiskLength<S>;
  for (int coordinate = 0; coordinate < 3; ++coordinate) {
    for (const S value : {length, std::nextafter(length, 2 * length), -length,
                          -std::nextafter(length, 2 * length)}) {
      Transform moved = X;
      moved.translation()(coordinate) = value;
      expect_same(moved);
    }
  }
  // Both verdicts occur: the draws straddle the tolerances.
  EXPECT_GT(valid, 1000);
  EXPECT_GT(invalid, 1000);
  EXPECT_GT(orthonormal, 1000);
  EXPECT_GT(pairs_valid, 1000);
  EXPECT_GT(pairs_invalid, 1000);
}

TEST(RobustnessPoseCheck, TwoLaneFormMatchesTheRule) {
  expectTwoLaneFormsMatchTheRule<double>(20241128);
}

TEST(RobustnessPoseCheck, TwoLaneFormMatchesTheRuleInFloat) {
  expectTwoLaneFormsMatchTheRule<float>(20261130);
}

// TransposedProduct (the frame change of every double query) gives Eigen's
// R.transpose() * x bit for bit, from a Mat3 (stride 3) and from a pose's 4x4
// matrix (stride 4), on perturbed rotations and vectors of every magnitude.
TEST(RobustnessPoseCheck, TransposedProductMatchesEigen) {
  fcl_disk_test::Random random(20261130);
  for (int i = 0; i < 20000; ++i) {
    fcl::Transform3d X = fcl::Transform3d::Identity();
    X.linear() = random.rotation();
    X.matrix()(int(random.uniform01() * 3), int(random.uniform01() * 3)) +=
        random.logUniform(1e-17, 1e-4);
    const Eigen::Matrix3d R = X.linear();
    const Eigen::Vector3d x = random.inBall(random.logUniform(1e-90, 1e90));
    const Eigen::Vector3d expected = R.transpose() * x;
    const Eigen::Vector3d from_mat3 = fcl_disk::internal::TransposedProduct<3>(R.data())(x);
    const Eigen::Vector3d from_pose =
        fcl_disk::internal::TransposedProduct<4>(X.matrix().data())(x);
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(from_mat3[k], expected[k]) << R << "\n" << x.transpose();
      ASSERT_EQ(from_pose[k], expected[k]) << R << "\n" << x.transpose();
    }
  }
}

// inverseSqrtNearOne (the normalisations that rebuild a float pose's rotation)
// agrees with 1 / sqrt to double's rounding on both sides of its Taylor range,
// and orthonormalFrameWithNormalOf turns float-rounded and perturbed rotations
// (normals near +-z included: its basis divides by 1 + |n_z|) into orthonormal
// right-handed frames with the rotation's own normal.
TEST(RobustnessPoseCheck, RebuiltFrameIsOrthonormalWithTheNormalKept) {
  using fcl_disk::internal::inverseSqrtNearOne;
  using fcl_disk::internal::kTaylorInverseSqrtRange;
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  fcl_disk_test::Random random(20261201);
  for (int i = 0; i < 20000; ++i) {
    const double offset = (random.chance(0.5) ? 1.0 : -1.0) *
                          random.logUniform(1e-17, 100 * kTaylorInverseSqrtRange);
    const double s = 1.0 + offset;
    const long double exact = 1.0L / std::sqrt(static_cast<long double>(s));
    ASSERT_LE(std::abs(static_cast<long double>(inverseSqrtNearOne(s)) - exact), 2 * kEps * exact)
        << "s = 1 + " << offset;
  }
  for (int i = 0; i < 20000; ++i) {
    Eigen::Matrix3d R = random.rotation();
    if (i % 4 < 2) {  // a normal within 1e-2 rad of +z or -z, or on it
      const double tilt = i % 8 == 0 ? 0.0 : random.logUniform(1e-17, 1e-2);
      const double spin = random.uniform(0.0, 2.0 * M_PI);
      const double heading = random.uniform(0.0, 2.0 * M_PI);
      const Eigen::Vector3d tilt_axis(std::cos(heading), std::sin(heading), 0.0);
      R = Eigen::AngleAxisd(spin, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
          Eigen::AngleAxisd(tilt, tilt_axis).toRotationMatrix();
      if (i % 4 == 1) R = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix() * R;
    }
    if (i % 2 == 0) {
      R = R.cast<float>().cast<double>();  // a float pose widened
    } else {
      R(int(random.uniform01() * 3), int(random.uniform01() * 3)) +=
          (random.chance(0.5) ? 1.0 : -1.0) * random.logUniform(1e-12, 1e-4);
    }
    const Eigen::Matrix3d F = fcl_disk::internal::orthonormalFrameWithNormalOf(R);
    const double defect = (F.transpose() * F - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    ASSERT_LE(defect, 4 * kEps) << R;
    ASSERT_LE((F.col(2).cross(F.col(0)) - F.col(1)).cwiseAbs().maxCoeff(), 4 * kEps) << R;
    // The normal is R's, pointing the same way.
    ASSERT_LE(F.col(2).cross(R.col(2).normalized()).norm(), 4 * kEps) << R;
    ASSERT_GT(F.col(2).dot(R.col(2)), 0.0) << R;
  }
}

// A reflection (det = -1) maps the local disk onto the same set as the rotation
// with the opposite third column, so the answers agree.
TYPED_TEST(Robustness, ReflectedFrameGivesTheSameDistance) {
  using S = TypeParam;
  const double tolerance = std::is_same<S, float>::value ? 1e-5 : 1e-12;
  for (const auto& [X1, X2] : basePairs<S>()) {
    for (int which = 0; which < 2; ++which) {
      Transform3<S> R1 = X1, R2 = X2;
      (which == 0 ? R1 : R2).linear().col(2) *= S(-1);
      ASSERT_TRUE(fcl_disk::isValidDiskPose(which == 0 ? R1 : R2));
      const auto proper = fcl_disk::exactDiskDistance<S>(S(1), X1, S(0.7), X2);
      const auto reflected = fcl_disk::exactDiskDistance<S>(S(1), R1, S(0.7), R2);
      EXPECT_NEAR(double(reflected.distance), double(proper.distance), tolerance);
      const auto proper_report = fcl_disk::almohamadSelimDiskDistance<S>(S(1), X1, S(0.7), X2);
      const auto reflected_report = fcl_disk::almohamadSelimDiskDistance<S>(S(1), R1, S(0.7), R2);
      EXPECT_NEAR(double(reflected_report.distance), double(proper_report.distance), tolerance);
      EXPECT_EQ(fcl_disk::intersectDisks<S>(S(1), R1, S(0.7), R2),
                fcl_disk::intersectDisks<S>(S(1), X1, S(0.7), X2));
    }
  }
}

// ---- the broadphase with a bad object -------------------------------------------

/// A row of unit disks 1.5 apart, the middle one with a NaN pose.
template <typename S>
struct SceneWithNaNDisk {
  std::vector<std::unique_ptr<fcl::CollisionObject<S>>> objects;
  fcl::DynamicAABBTreeCollisionManager<S> manager;

  explicit SceneWithNaNDisk(int count) {
    auto disk = std::make_shared<fcl_disk::Disk<S>>(S(1));
    for (int i = 0; i < count; ++i) {
      Transform3<S> X = tiltedPose<S>({S(1.5) * S(i), 0, 0}, {0, S(0.2) * S(i % 3), 1});
      if (i == count / 2) X.translation().y() = std::numeric_limits<S>::quiet_NaN();
      objects.push_back(std::make_unique<fcl::CollisionObject<S>>(disk, X));
      manager.registerObject(objects.back().get());
    }
    manager.setup();
  }
};

// The tree must not crash or hang; collide finds only pairs of valid disks, with
// finite contacts.
// distance: the scene's nearest distance is NaN if the NaN disk was queried
// (DistanceResult keeps NaN), else the minimum over the pairs that were: never a
// distance that some queried pair does not have.
TYPED_TEST(Robustness, BroadphaseWithNaNDiskTerminates) {
  using S = TypeParam;
  SceneWithNaNDisk<S> scene(9);
  fcl::DefaultCollisionData<S> collision;
  collision.request.num_max_contacts = 100;
  // Without enable_contact FCL's contacts carry no position (its Contact
  // constructor leaves pos and normal uninitialised, for every shape pair).
  collision.request.enable_contact = true;
  scene.manager.collide(&collision, fcl::DefaultCollisionFunction<S>);
  std::vector<fcl::Contact<S>> contacts;
  collision.result.getContacts(contacts);
  for (const auto& contact : contacts) EXPECT_TRUE(contact.pos.allFinite());
  fcl::DefaultDistanceData<S> distance;
  scene.manager.distance(&distance, fcl::DefaultDistanceFunction<S>);
  const S d = distance.result.min_distance;
  EXPECT_TRUE(std::isnan(d) || d >= S(0)) << d;
}

}  // namespace
