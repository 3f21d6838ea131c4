// Properties of diskShapeDistance() / diskShapeIntersect() and of fcl::distance /
// fcl::collide on a Disk against every FCL primitive, on 1e5 random poses per
// pair type in double and in float (half of them scaled by 10^x, x in
// [-6, 6]): the disk point on the disk and the shape point on the shape (long
// double distances of test/disk_shape_oracle.h), |p - q| == distance,
// lower_bound <= distance with the certified gap closed in double, the same
// answer with the arguments swapped through fcl::distance and after a common
// rigid motion of both poses, and collide agreeing with the distance outside
// the touching band, with its contact on both shapes and a normal whose
// translation by the depth separates them. The same in double on 10,000 poses
// per pair, half of them scaled by 10^x, x in [-98, 98]. And the same for
// Convex hulls of 66 to 130 vertices (ring hulls), whose closed form finds
// their nearest feature by the support search (src/pairs/point_to_hull.h), on
// 10,000 poses in double and in float and 2,000 at every length scale.
#include <fcl_disk/fcl_disk.h>

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <type_traits>

#include "disk_shape_fcl.h"
#include "disk_shape_oracle.h"
#include "hull_lists.h"
#include "test_random.h"

namespace {

using namespace fcl_disk_test::oracle;
using fcl_disk_test::Random;

constexpr int kPosesPerPair = 100000;
constexpr int kPosesAtEveryLengthScale = 10000;
/// Every 50th pose also goes through fcl::distance / fcl::collide both ways and
/// a rigid motion (the hook's answers equal diskShapeDistance bit for bit,
/// test_hook checks; this checks the symmetries of the answer).
constexpr int kSymmetryEvery = 50;

template <typename S>
struct Tolerance {
  static constexpr bool kFloat = std::is_same<S, float>::value;
  /// Points on their shapes, |p - q| vs distance: the header's 1e-12 of the scene
  /// in double; in float the answer is rounded to float (1/2 ulp per coordinate)
  /// and the poses are float: 16 ulps of the scene.
  static constexpr double kRelative = kFloat ? 16 * 1.1920928955078125e-07 : 1e-12;
  /// Swap and rigid motion: the moved pose is rounded to S (centres by ~ulp of
  /// the scene, rotations by ~eps), and the distance is 1-Lipschitz in such
  /// moves: 8 ulps of S of the scene, plus the solver's bound twice.
  static constexpr double kMotionRelative =
      8 * double(std::numeric_limits<S>::epsilon()) + 2 * kRelative;
  /// The certified gap the header promises on converged answers (double).
  static constexpr double kGapRelative = kFloat ? 1.0 : 1e-12;
};

/// A random shape of `kind`; for Kind::convex with `large_hull`, a ring hull
/// of 8 rings of 8 to 16 points (66 to 130 vertices) with random semi-axes.
Shape randomShape(Kind kind, Random& random, bool large_hull = false) {
  Shape s;
  s.kind = kind;
  auto length = [&] { return Real(random.uniform(0.05, 0.6)); };
  switch (kind) {
    case Kind::sphere: s.dims = V3(length(), 0, 0); break;
    case Kind::box: s.dims = V3(length(), length(), length()); break;
    case Kind::capsule:
    case Kind::cylinder:
    case Kind::cone: s.dims = V3(length(), length(), 0); break;
    case Kind::ellipsoid: s.dims = V3(length(), length(), length()); break;
    case Kind::convex: {
      if (large_hull) {
        const int around = 8 + int(random.uniform(0.0, 8.999));
        const fcl_disk_test::HullLists hull = fcl_disk_test::ringHull(
            8, around, Eigen::Vector3d(double(length()), double(length()), double(length())));
        for (const Eigen::Vector3d& v : hull.vertices) s.vertices.push_back(v.cast<Real>());
        s.faces = hull.faces;
        break;
      }
      // A random box-like frustum: a rectangle base and a smaller top.
      const Real a = length(), b = length(), h = length(), shrink = Real(random.uniform(0.2, 1.0));
      s.vertices = {V3(-a, -b, -h), V3(a, -b, -h), V3(a, b, -h), V3(-a, b, -h),
                    V3(-a * shrink, -b * shrink, h), V3(a * shrink, -b * shrink, h),
                    V3(a * shrink, b * shrink, h), V3(-a * shrink, b * shrink, h)};
      s.faces = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
      break;
    }
    case Kind::halfspace:
    case Kind::plane:
      s.n = random.unitVector().cast<Real>();
      s.d = Real(random.uniform(-0.3, 0.3));
      break;
    case Kind::triangle:
      for (int i = 0; i < 3; ++i) s.vertices.push_back(random.inBall(0.6).cast<Real>());
      break;
  }
  return s;
}

Shape scaledShape(Shape s, Real k) {
  s.dims *= k;
  for (V3& v : s.vertices) v *= k;
  s.d *= k;
  return s;
}

/// The shape as stored in S (an fcl::Halfspace / Plane normalises its normal).
template <typename S>
Shape asStored(Shape s, const fcl::ShapeBase<S>& stored) {
  for (int i = 0; i < 3; ++i) s.dims[i] = Real(S(s.dims[i]));
  for (V3& v : s.vertices) v = v.cast<S>().template cast<Real>();
  if (s.kind == Kind::halfspace) {
    const auto& h = static_cast<const fcl::Halfspace<S>&>(stored);
    s.n = h.n.template cast<Real>();
    s.d = Real(h.d);
  } else if (s.kind == Kind::plane) {
    const auto& p = static_cast<const fcl::Plane<S>&>(stored);
    s.n = p.n.template cast<Real>();
    s.d = Real(p.d);
  }
  return s;
}

template <typename S>
struct Answer {
  S distance, lower_bound;
  fcl::Vector3<S> p, q;
};

template <typename S>
Answer<S> direct(S r, const fcl::Transform3<S>& X_WD, const fcl::ShapeBase<S>& shape,
                 const fcl::Transform3<S>& X_WS) {
  const auto a = diskShapeDistanceAny(r, X_WD, shape, X_WS);
  return Answer<S>{a.distance, a.lower_bound, a.p_W_disk, a.p_W_shape};
}

template <typename S>
fcl::Transform3<S> randomPose(Random& random, double spread) {
  fcl::Transform3<double> X = fcl::Transform3<double>::Identity();
  X.linear() = random.rotation();
  X.translation() = random.inBall(spread);
  return X.template cast<S>();
}

/// The touching rule (closer than 1e-13 * scale counts as touching, scale = r +
/// the shape's bounding radius + the centres' distance) at the tolerance's
/// multiples: a separated pair's shape moved along q - p to distance `multiple`
/// * 1e-13 * scale (exactly, up to the rounding of the moved pose: the planes
/// normal to q - p through p and q keep separating the sets) intersects below 1
/// and not above, through diskShapeIntersect and fcl::collide's default request,
/// on either side of the early exit's margin (8 tolerances,
/// src/disk_shape_pair.h). The scale is that of the moved pose, taken low for
/// the touching multiple and high (the oracle's bounding radius, at least the
/// solver's) for the others.
template <typename S>
void checkTouchingBand(S r, const fcl::Transform3<S>& X_WD,
                       const std::shared_ptr<fcl::ShapeBase<S>>& shape,
                       const fcl::Transform3<S>& X_WS, const Answer<S>& a, double bounding_radius,
                       const std::string& what) {
  const fcl::Vector3<S> along = (a.q - a.p) / a.distance;
  const fcl::Vector3<S> touching_centre = X_WS.translation() - a.distance * along;
  const double low_scale = double(r) + double((X_WD.translation() - touching_centre).norm());
  if (!(double(a.distance) > 1e-9 * low_scale)) return;
  fcl::CollisionObject<S> disk_object(std::make_shared<fcl_disk::Disk<S>>(r), X_WD);
  for (const double multiple : {0.5, 1.5, 4.0, 10.0, 40.0}) {
    const bool touching = multiple < 1.0;
    const double scale = touching ? low_scale : low_scale + bounding_radius;
    fcl::Transform3<S> X_moved = X_WS;
    X_moved.translation() -= (a.distance - S(multiple * 1e-13 * scale)) * along;
    ASSERT_EQ(diskShapeIntersectAny(r, X_WD, *shape, X_moved), touching)
        << "moved to " << multiple << " touching tolerances, distance "
        << double(direct(r, X_WD, *shape, X_moved).distance) / (1e-13 * scale) << " of them\n"
        << what;
    fcl::CollisionObject<S> shape_object(shape, X_moved);
    fcl::CollisionResult<S> decision;
    fcl::collide(&disk_object, &shape_object, fcl::CollisionRequest<S>(), decision);
    ASSERT_EQ(decision.isCollision(), touching)
        << "fcl::collide, moved to " << multiple << " touching tolerances\n" << what;
  }
}

/// `poses` random poses of `kind`, half of them scaled by 10^x, x uniform in
/// [-max_exponent, max_exponent].
template <typename S>
void checkPair(Kind kind, int poses = kPosesPerPair, double max_exponent = 6.0,
               bool large_hulls = false) {
  using T = Tolerance<S>;
  Random random(7919 * (int(kind) + 1) + (std::is_same<S, float>::value ? 1 : 0) +
                int(max_exponent) + (large_hulls ? 104729 : 0));
  int separated = 0, intersecting = 0;
  for (int i = 0; i < poses; ++i) {
    const Real k = random.chance(0.5)
                       ? std::pow(Real(10), Real(random.uniform(-max_exponent, max_exponent)))
                       : Real(1);
    const Shape wanted = scaledShape(randomShape(kind, random, large_hulls), k);
    const auto fcl_shape = toFcl<S>(wanted);
    const Shape shape = asStored<S>(wanted, *fcl_shape);
    const S r = S(random.uniform(0.05, 0.8) * double(k));
    fcl::Transform3<S> X_WD = randomPose<S>(random, double(k)), X_WS = randomPose<S>(random, double(k));
    const Answer<S> a = direct(r, X_WD, *fcl_shape, X_WS);

    const Disk disk{X_WD.translation().template cast<Real>(), X_WD.linear().col(0).template cast<Real>(),
                    X_WD.linear().col(1).template cast<Real>(), Real(r)};
    Pose X;
    X.R = X_WS.linear().template cast<Real>();
    X.t = X_WS.translation().template cast<Real>();
    const bool boundary = kind == Kind::halfspace || kind == Kind::plane;
    const double scale = double(disk.r + shape.boundingRadius() +
                                (boundary ? std::abs((X.R * shape.n).dot(disk.c - X.t) - shape.d)
                                          : (disk.c - X.t).norm()));
    const double tolerance = T::kRelative * scale;
    std::ostringstream what;
    what.precision(17);
    what << kindName(kind) << " pose " << i << " r " << r << "\nX_WD\n" << X_WD.matrix() << "\nX_WS\n"
         << X_WS.matrix() << "\ndistance " << a.distance << " lower " << a.lower_bound
         << "\ndims " << double(shape.dims.x()) << " " << double(shape.dims.y()) << " " << double(shape.dims.z());
    for (const V3& v : shape.vertices) what << "\nvertex " << double(v.x()) << " " << double(v.y()) << " " << double(v.z());
    const V3 p = a.p.template cast<Real>(), q = a.q.template cast<Real>();
    ASSERT_TRUE(std::isfinite(double(a.distance))) << what.str();
    ASSERT_LE(double(pointToDisk(disk, p)), tolerance) << "disk point off the disk\n" << what.str();
    ASSERT_LE(double(pointDistanceWorld(shape, X, q)), tolerance) << "shape point off the shape\n" << what.str();
    ASSERT_LE(std::abs(double((p - q).norm()) - double(a.distance)), 2 * tolerance) << what.str();
    ASSERT_LE(double(a.lower_bound), double(a.distance)) << what.str();
    ASSERT_LE(double(a.distance - a.lower_bound), T::kGapRelative * scale) << what.str();
    (a.distance > 0 ? separated : intersecting)++;

    if (i % kSymmetryEvery != 0) continue;
    // Both argument orders through fcl::distance.
    fcl::CollisionObject<S> disk_object(std::make_shared<fcl_disk::Disk<S>>(r), X_WD);
    fcl::CollisionObject<S> shape_object(fcl_shape, X_WS);
    fcl::DistanceRequest<S> request;
    fcl::DistanceResult<S> disk_first, shape_first;
    fcl::distance(&disk_object, &shape_object, request, disk_first);
    fcl::distance(&shape_object, &disk_object, request, shape_first);
    ASSERT_EQ(disk_first.min_distance, a.distance) << what.str();
    ASSERT_EQ(shape_first.min_distance, a.distance) << what.str();
    ASSERT_EQ(shape_first.nearest_points[0], a.q) << what.str();
    ASSERT_EQ(shape_first.nearest_points[1], a.p) << what.str();
    // A common rigid motion of both poses.
    const fcl::Transform3<S> M = randomPose<S>(random, 3.0 * double(k));
    const Answer<S> moved = direct(r, fcl::Transform3<S>(M * X_WD), *fcl_shape, fcl::Transform3<S>(M * X_WS));
    ASSERT_LE(std::abs(double(moved.distance) - double(a.distance)), T::kMotionRelative * (scale + 3 * double(k)))
        << what.str();
    // Collision agrees with the distance outside the touching band; its contact
    // is on both shapes and the translation by the depth separates them.
    fcl::CollisionRequest<S> collision_request;
    collision_request.enable_contact = true;
    fcl::CollisionResult<S> collision;
    fcl::collide(&disk_object, &shape_object, collision_request, collision);
    if (double(a.distance) > 1e3 * tolerance) {
      ASSERT_FALSE(collision.isCollision()) << what.str();
    } else if (a.distance == 0) {
      ASSERT_TRUE(collision.isCollision()) << what.str();
      const auto& contact = collision.getContact(0);
      const V3 pos = contact.pos.template cast<Real>();
      ASSERT_LE(double(pointToDisk(disk, pos)), 1e3 * tolerance) << what.str();
      ASSERT_LE(double(pointDistanceWorld(shape, X, pos)), 1e3 * tolerance) << what.str();
      ASSERT_NEAR(double(contact.normal.norm()), 1.0, 1e-5) << what.str();
      if (!boundary) {  // a halfspace or plane moved stays unbounded; its depth is exact
        fcl::Transform3<S> X_moved = X_WS;
        X_moved.translation() += (contact.penetration_depth + S(1e-6 * scale)) * contact.normal;
        ASSERT_GT(double(direct(r, X_WD, *fcl_shape, X_moved).distance), 0.0) << what.str();
      }
    }
    // FCL's default request (no contact asked) decides as the one above.
    fcl::CollisionResult<S> decision;
    fcl::collide(&disk_object, &shape_object, fcl::CollisionRequest<S>(), decision);
    ASSERT_EQ(decision.isCollision(), collision.isCollision()) << what.str();
    // Not the ellipsoid: where its iteration stops next to a grazing contact it
    // decides to its distance's accuracy, 1e-12 * scale (the header says so).
    if (!T::kFloat && !boundary && kind != Kind::ellipsoid && a.distance > 0) {
      checkTouchingBand(r, X_WD, fcl_shape, X_WS, a, double(shape.boundingRadius()), what.str());
    }
  }
  EXPECT_GT(separated, poses / 10) << kindName(kind);
  std::cout << kindName(kind) << (large_hulls ? " (large hulls)" : "")
            << (std::is_same<S, float>::value ? " float" : " double") << ": "
            << separated << " separated, " << intersecting << " intersecting\n";
}

class DiskShapeProperties : public ::testing::TestWithParam<Kind> {};

TEST_P(DiskShapeProperties, Double) { checkPair<double>(GetParam()); }
TEST_P(DiskShapeProperties, Float) { checkPair<float>(GetParam()); }
// Lengths from 1e-98 to 1e98 (kMinDiskRadius and kMaxDiskLength are 1e-100 and
// 1e100, and the shapes reach to 20 times the scale): the solvers' squares
// and products of lengths must stay normal doubles at every scale.
TEST_P(DiskShapeProperties, DoubleAtEveryLengthScale) {
  checkPair<double>(GetParam(), kPosesAtEveryLengthScale, 98.0);
}

// Hulls of 66 to 130 vertices: the Convex closed form's support search.
constexpr int kLargeHullPoses = 10000;
constexpr int kLargeHullPosesAtEveryLengthScale = 2000;
TEST(DiskLargeHullProperties, Double) {
  checkPair<double>(Kind::convex, kLargeHullPoses, 6.0, /*large_hulls=*/true);
}
TEST(DiskLargeHullProperties, Float) {
  checkPair<float>(Kind::convex, kLargeHullPoses, 6.0, /*large_hulls=*/true);
}
TEST(DiskLargeHullProperties, DoubleAtEveryLengthScale) {
  checkPair<double>(Kind::convex, kLargeHullPosesAtEveryLengthScale, 98.0, /*large_hulls=*/true);
}

INSTANTIATE_TEST_SUITE_P(EveryPrimitive, DiskShapeProperties,
                         ::testing::Values(Kind::sphere, Kind::box, Kind::capsule, Kind::cylinder,
                                           Kind::cone, Kind::ellipsoid, Kind::convex,
                                           Kind::halfspace, Kind::plane, Kind::triangle),
                         [](const ::testing::TestParamInfo<Kind>& info) {
                           return std::string(kindName(info.param));
                         });

}  // namespace
