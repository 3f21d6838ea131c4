// Tight world boxes for disks (include/fcl_disk/disk_aabb.h), in float and double:
//
// 1. diskWorldAABB contains every sampled disk point (rim at many angles, the rim
//    points extreme along each axis, interior points), evaluated in long double
//    from the stored pose, i.e. the exact disk the narrowphase sees;
// 2. it is tight: on every face some rim point comes within the header's stated
//    slack; and it never exceeds FCL's own box;
// 3. DiskCollisionObject / updateDiskAABB store that box where FCL's managers read
//    it, and the base computeAABB() restores FCL's cube (documented behaviour);
// 4. a DynamicAABBTreeCollisionManager over DiskCollisionObjects finds exactly the
//    colliding pairs and nearest distances of brute force over all pairs, before
//    and after moving objects and calling update(): tight boxes never lose a pair.
//
// Poses include normals exactly on and barely off the world axes, where the tight
// box is thinnest (zero thickness when exactly on an axis) and a box that is too
// small would show.
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>

#include <fcl_disk/fcl_disk.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <set>
#include <type_traits>
#include <utility>
#include <vector>

#include "test_random.h"
#include "test_tolerances.h"

namespace {

using fcl_disk::DiskCollisionObject;
using fcl_disk::diskWorldAABB;
using fcl_disk_test::Eps;
using fcl_disk_test::Random;
using LongVector3 = Eigen::Matrix<long double, 3, 1>;

// ---------------------------------------------------------------- tolerances
/// Sample points are computed in long double from the stored (S) pose; their own
/// rounding is a few long-double ulps of |c| + r. 16 of them is still ~1e4 times
/// below the box's padding in double, so "inside" is tested essentially exactly.
constexpr long double kSamplePointRounding = 16 * std::numeric_limits<long double>::epsilon();

/// How far a face may lie beyond the farthest sampled rim point, in units of
/// eps(S) * (|c_i| + r): disk_aabb.h states at most 2 * kDiskAabbExtentPadUlps eps
/// of the extent plus 2 ulps of |c_i| + extent (an ulp of x is at most eps * x).
/// The rim is also sampled at the exact extreme angle, so no sampling error enters.
constexpr double kTightnessUlps = 2 * fcl_disk::kDiskAabbExtentPadUlps + 2;

/// FCL's cube and our box are each rounded: FCL's faces c_i +- aabb_radius to
/// nearest (aabb_radius itself a few eps of r off), ours outward by up to 1.5 ulps.
/// Where sqrt(2) r - r is below that (a radius of a few ulps of |c_i|) ours may
/// poke out of FCL's by it: 4 eps * (|c_i| + r) covers both.
constexpr double kFclBoxRoundingUlps = 4;

/// Rim samples per disk (plus the six axis-extreme points) and interior samples.
constexpr int kRimSamples = 64;
constexpr int kInteriorSamples = 16;
constexpr int kRandomPoses = 20000;

constexpr std::uint64_t kSeed = 20240604;

// ---------------------------------------------------------------- poses
/// A random pose: a third generic, a third with the normal exactly on a world axis
/// (rotation entries exactly 0 and 1, so the box is flat), a third tilted off an
/// axis by 1e-9 .. 1e-2 rad (nearly flat boxes, where sqrt(1 - n_i^2) would
/// cancel). Any spin about the normal; centre in a ball of centre_range.
Eigen::Isometry3d randomPose(Random& random, double centre_range) {
  Eigen::Matrix3d R;
  const double kind = random.uniform01();
  if (kind < 1.0 / 3) {
    R = random.rotation();
  } else {
    // Rotations taking local +Z to world +X, +Y or +Z, with 0/1 entries.
    const int axis = int(random.uniform(0, 3)) % 3;
    Eigen::Matrix3d to_axis = Eigen::Matrix3d::Identity();  // axis 2
    if (axis == 0) to_axis << 0, 0, 1, 1, 0, 0, 0, 1, 0;
    if (axis == 1) to_axis << 0, 1, 0, 0, 0, 1, 1, 0, 0;
    const double spin = kind < 2.0 / 3 ? 0.5 * M_PI * int(random.uniform(0, 4))
                                       : random.uniform(0, 2 * M_PI);
    R = to_axis * Eigen::AngleAxisd(spin, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    if (kind >= 2.0 / 3) {
      const double tilt = random.logUniform(1e-9, 1e-2);
      R = Eigen::AngleAxisd(tilt, random.unitVector()).toRotationMatrix() * R;
    }
  }
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  X.translation() = random.inBall(centre_range);
  return X;
}

template <typename S>
fcl::Transform3<S> toScalar(const Eigen::Isometry3d& X) {
  return X.cast<S>();
}

/// The disk point at polar (rho, angle) for the stored pose, in long double.
template <typename S>
LongVector3 diskPoint(const fcl::Transform3<S>& X_WD, S radius, long double rho_fraction,
                      long double angle) {
  const LongVector3 u = X_WD.linear().col(0).template cast<long double>();
  const LongVector3 v = X_WD.linear().col(1).template cast<long double>();
  const LongVector3 c = X_WD.translation().template cast<long double>();
  const long double rho = rho_fraction * static_cast<long double>(radius);
  return c + rho * (std::cos(angle) * u + std::sin(angle) * v);
}

// Named after the file so that `ctest -R disk_aabb` selects these tests. The test
// names have no underscore, so gtest's caveat about underscores (names that can
// collide when both parts have one) does not apply.
template <typename S>
class disk_aabb : public ::testing::Test {};
using ScalarTypes = ::testing::Types<float, double>;
TYPED_TEST_SUITE(disk_aabb, ScalarTypes);

// ---------------------------------------------------------------- the box itself

TYPED_TEST(disk_aabb, ContainsTheDiskIsTightAndNeverExceedsFclsBox) {
  using S = TypeParam;
  Random random(kSeed);
  const long double eps = std::numeric_limits<S>::epsilon();
  for (int k = 0; k < kRandomPoses; ++k) {
    const S radius = S(random.logUniform(1e-3, 1e3));
    const fcl::Transform3<S> X_WD = toScalar<S>(randomPose(random, random.logUniform(1e-3, 1e3)));
    const fcl::AABB<S> box = diskWorldAABB(radius, X_WD);
    const LongVector3 c = X_WD.translation().template cast<long double>();
    const LongVector3 lo = box.min_.template cast<long double>();
    const LongVector3 hi = box.max_.template cast<long double>();

    std::vector<LongVector3> rim;
    for (int j = 0; j < kRimSamples; ++j) {
      rim.push_back(diskPoint(X_WD, radius, 1.0L, 2 * M_PI * j / kRimSamples));
    }
    for (int i = 0; i < 3; ++i) {  // the rim points extreme along each axis
      const long double angle = std::atan2(static_cast<long double>(X_WD.linear()(i, 1)),
                                           static_cast<long double>(X_WD.linear()(i, 0)));
      rim.push_back(diskPoint(X_WD, radius, 1.0L, angle));
      rim.push_back(diskPoint(X_WD, radius, 1.0L, angle + M_PI));
    }
    std::vector<LongVector3> points = rim;
    for (int j = 0; j < kInteriorSamples; ++j) {
      points.push_back(diskPoint(X_WD, radius, std::sqrt(random.uniform01()),
                                 random.uniform(0, 2 * M_PI)));
    }

    for (int i = 0; i < 3; ++i) {
      const long double scale = std::abs(c[i]) + radius;
      const long double rounding = kSamplePointRounding * scale;
      long double rim_lo = std::numeric_limits<long double>::infinity();
      long double rim_hi = -rim_lo;
      for (const LongVector3& p : points) {
        ASSERT_GE(p[i], lo[i] - rounding) << "pose " << k << " axis " << i;
        ASSERT_LE(p[i], hi[i] + rounding) << "pose " << k << " axis " << i;
      }
      for (const LongVector3& p : rim) {
        rim_lo = std::min(rim_lo, p[i]);
        rim_hi = std::max(rim_hi, p[i]);
      }
      const long double slack = kTightnessUlps * eps * scale + rounding;
      ASSERT_LE(rim_lo - lo[i], slack) << "pose " << k << " axis " << i;
      ASSERT_LE(hi[i] - rim_hi, slack) << "pose " << k << " axis " << i;
    }

    // FCL's box for a rotated object is the cube of half-width aabb_radius
    // (sqrt(2) r), which contains ours up to rounding. A rotation that Eigen's
    // isIdentity() accepts (entries within 1e-12 in double, 1e-5 in float) FCL
    // treats as the identity and translates its local box [-r, r]^2 x {0}, ignoring
    // the small tilt, so there ours may exceed FCL's by that tilt (r times twice the
    // largest entry of R - I bounds it): FCL's box then misses disk points. For an
    // exact identity FCL's box is the tight one, unpadded: ours exceeds it by our
    // padding (kTightnessUlps).
    const fcl::CollisionObject<S> fcl_object(std::make_shared<fcl_disk::Disk<S>>(radius), X_WD);
    const fcl::AABB<S>& fcl_box = fcl_object.getAABB();
    const bool fcl_takes_identity = X_WD.linear().isIdentity();
    const S ignored_tilt =
        fcl_takes_identity ? (X_WD.linear() - fcl::Matrix3<S>::Identity()).cwiseAbs().maxCoeff()
                           : S(0);
    const S rounding_ulps = S(fcl_takes_identity ? kTightnessUlps : kFclBoxRoundingUlps);
    for (int i = 0; i < 3; ++i) {
      const S allowance = rounding_ulps * std::numeric_limits<S>::epsilon() *
                              (std::abs(X_WD.translation()[i]) + radius) +
                          2 * radius * ignored_tilt;
      ASSERT_LE(box.max_[i], fcl_box.max_[i] + allowance) << "pose " << k << " axis " << i;
      ASSERT_GE(box.min_[i], fcl_box.min_[i] - allowance) << "pose " << k << " axis " << i;
    }
  }
}

TYPED_TEST(disk_aabb, ExtentsMatchClosedFormsOnSimplePoses) {
  using S = TypeParam;
  const S r = S(0.5);
  const S eps = std::numeric_limits<S>::epsilon();
  // Normal along +Z, centred at the origin: the square [-r, r]^2, zero height.
  fcl::AABB<S> box = diskWorldAABB(r, fcl::Transform3<S>::Identity());
  EXPECT_NEAR(box.max_[0], r, S(kTightnessUlps) * eps * r);
  EXPECT_NEAR(box.min_[1], -r, S(kTightnessUlps) * eps * r);
  EXPECT_EQ(box.max_[2], std::numeric_limits<S>::denorm_min());  // 0, rounded outward
  // Normal tilted by theta about X: the y half-extent is r cos(theta).
  const S theta = S(0.3);
  fcl::Transform3<S> X = fcl::Transform3<S>::Identity();
  X.linear() = Eigen::AngleAxis<S>(theta, fcl::Vector3<S>::UnitX()).toRotationMatrix();
  box = diskWorldAABB(r, X);
  EXPECT_NEAR(box.max_[0], r, S(kTightnessUlps) * eps * r);
  EXPECT_NEAR(box.max_[1], r * std::cos(theta), S(kTightnessUlps) * eps * r);
  EXPECT_NEAR(box.max_[2], r * std::sin(theta), S(kTightnessUlps) * eps * r);
}

TYPED_TEST(disk_aabb, CoversTiltsThatFclTakesForTheIdentity) {
  using S = TypeParam;
  // Below Eigen's isIdentity() precision p (1e-5 float, 1e-12 double), FCL's
  // computeAABB() translates the Disk's local box as if untilted: the local box
  // is padded so that it still holds the rim. The largest such tilt: about a
  // diagonal axis of the plane, with both z entries of the rotation just under p.
  const S p = Eigen::NumTraits<S>::dummy_precision();
  for (const S tilt : {S(0.1) * p, S(0.99) * std::sqrt(S(2)) * p}) {
    for (const S r : {S(1), S(1e6), S(1e-6)}) {
      fcl::Transform3<S> X = fcl::Transform3<S>::Identity();
      X.linear() =
          Eigen::AngleAxis<S>(tilt, fcl::Vector3<S>(1, 1, 0).normalized()).toRotationMatrix();
      X.translation() = fcl::Vector3<S>(S(0.25) * r, S(-0.5) * r, S(2) * r);
      ASSERT_TRUE(X.linear().isIdentity());
      const fcl::CollisionObject<S> fcl_object(std::make_shared<fcl_disk::Disk<S>>(r), X);
      const fcl::AABB<S>& box = fcl_object.getAABB();
      for (int k = 0; k < 64; ++k) {  // rim points
        const S angle = S(2 * M_PI * k / 64);
        const fcl::Vector3<S> rim =
            X * fcl::Vector3<S>(r * std::cos(angle), r * std::sin(angle), S(0));
        EXPECT_TRUE(box.contain(rim)) << "tilt " << tilt << " r " << r << " rim point " << k;
      }
      EXPECT_GE(diskWorldAABB(r, X).max_[2] - X.translation().z(), r * std::sin(tilt) * S(0.99));
    }
  }
}

TYPED_TEST(disk_aabb, CollisionObjectsStoreTheTightBoxWhereManagersReadIt) {
  using S = TypeParam;
  Random random(kSeed + 1);
  const S r = S(0.7);
  auto disk = std::make_shared<fcl_disk::Disk<S>>(r);
  const fcl::Transform3<S> X1 = toScalar<S>(randomPose(random, 5));
  fcl::Transform3<S> X2 = X1;
  X2.linear() = random.rotation().cast<S>();  // generic
  const auto equal = [](const fcl::AABB<S>& a, const fcl::AABB<S>& b) {
    return a.min_ == b.min_ && a.max_ == b.max_;
  };

  DiskCollisionObject<S> object(disk, X1);
  EXPECT_TRUE(equal(object.getAABB(), diskWorldAABB(r, X1)));
  object.setPoseAndUpdateAABB(X2);
  EXPECT_TRUE(equal(object.getAABB(), diskWorldAABB(r, X2)));
  object.setTransform(X1);
  object.computeAABB();  // the derived (hiding) function: tight
  EXPECT_TRUE(equal(object.getAABB(), diskWorldAABB(r, X1)));
  object.setTransform(X2);
  static_cast<fcl::CollisionObject<S>&>(object).computeAABB();  // FCL's own: the cube
  const fcl::CollisionObject<S> plain_reference(disk, X2);
  EXPECT_TRUE(equal(object.getAABB(), plain_reference.getAABB()));
  object.computeTightAABB();
  EXPECT_TRUE(equal(object.getAABB(), diskWorldAABB(r, X2)));

  // updateDiskAABB on a plain CollisionObject holding a Disk, and on a sphere.
  fcl::CollisionObject<S> plain(disk, X2);
  EXPECT_TRUE(fcl_disk::updateDiskAABB(plain));
  EXPECT_TRUE(equal(plain.getAABB(), diskWorldAABB(r, X2)));
  fcl::CollisionObject<S> sphere(std::make_shared<fcl::Sphere<S>>(r), X2);
  const fcl::AABB<S> sphere_box = sphere.getAABB();
  EXPECT_FALSE(fcl_disk::updateDiskAABB(sphere));
  EXPECT_TRUE(equal(sphere.getAABB(), sphere_box));

  EXPECT_THROW(DiskCollisionObject<S>(nullptr), std::invalid_argument);
}

// ---------------------------------------------------------------- broadphase

using Pair = std::pair<int, int>;

template <typename S>
int indexOf(const fcl::CollisionObject<S>* object) {
  return int(reinterpret_cast<std::intptr_t>(object->getUserData()));
}

/// Collects every colliding pair (never stops early, unlike
/// fcl::DefaultCollisionFunction with its default num_max_contacts = 1) and counts
/// the candidate pairs the manager hands over.
template <typename S>
struct AllPairsData {
  std::set<Pair> colliding;
  long candidates = 0;
};

template <typename S>
bool collectCollidingPair(fcl::CollisionObject<S>* o1, fcl::CollisionObject<S>* o2, void* data) {
  auto* all = static_cast<AllPairsData<S>*>(data);
  ++all->candidates;
  fcl::CollisionRequest<S> request;
  fcl::CollisionResult<S> result;
  if (fcl::collide(o1, o2, request, result) > 0) {
    const int i = indexOf(o1), j = indexOf(o2);
    all->colliding.insert({std::min(i, j), std::max(i, j)});
  }
  return false;  // never done: all pairs
}

/// Nearest OTHER object: the manager's per-object query also visits the object
/// itself when it is registered (fcl::DefaultDistanceFunction would return 0).
template <typename S>
struct NearestData {
  S nearest = std::numeric_limits<S>::max();
};

template <typename S>
bool nearestOther(fcl::CollisionObject<S>* o1, fcl::CollisionObject<S>* o2, void* data, S& dist) {
  auto* nearest = static_cast<NearestData<S>*>(data);
  if (o1 == o2) return false;
  fcl::DistanceRequest<S> request;
  fcl::DistanceResult<S> result;
  fcl::distance(o1, o2, request, result);
  nearest->nearest = std::min(nearest->nearest, std::max(result.min_distance, S(0)));
  dist = nearest->nearest;
  return nearest->nearest <= 0;  // nothing is nearer than touching
}

template <typename S>
struct Scene {
  std::vector<std::unique_ptr<DiskCollisionObject<S>>> objects;
  std::vector<fcl::CollisionObject<S>*> pointers;
  double size = 0;  ///< for relative tolerances: the scene's extent plus 2 r_max
};

constexpr int kSceneDisks = 300;
constexpr double kRadiusMin = 0.2, kRadiusMax = 1.0;

template <typename S>
Scene<S> makeScene(Random& random, double centre_range) {
  Scene<S> scene;
  for (int i = 0; i < kSceneDisks; ++i) {
    auto disk = std::make_shared<fcl_disk::Disk<S>>(S(random.uniform(kRadiusMin, kRadiusMax)));
    scene.objects.push_back(std::make_unique<DiskCollisionObject<S>>(
        disk, toScalar<S>(randomPose(random, centre_range))));
    scene.objects.back()->setUserData(reinterpret_cast<void*>(std::intptr_t(i)));
    scene.pointers.push_back(scene.objects.back().get());
  }
  scene.size = 2 * centre_range + 2 * kRadiusMax;
  return scene;
}

template <typename S>
void expectManagerMatchesBruteForce(const Scene<S>& scene,
                                    const fcl::DynamicAABBTreeCollisionManager<S>& manager,
                                    const char* stage) {
  SCOPED_TRACE(stage);
  const int n = int(scene.pointers.size());
  std::set<Pair> brute_colliding;
  long overlapping_boxes = 0;
  std::vector<S> brute_nearest(n, std::numeric_limits<S>::max());
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      fcl::CollisionObject<S>* a = scene.pointers[i];
      fcl::CollisionObject<S>* b = scene.pointers[j];
      overlapping_boxes += a->getAABB().overlap(b->getAABB());
      fcl::CollisionRequest<S> request;
      fcl::CollisionResult<S> result;
      if (fcl::collide(a, b, request, result) > 0) brute_colliding.insert({i, j});
      fcl::DistanceRequest<S> distance_request;
      fcl::DistanceResult<S> distance_result;
      fcl::distance(a, b, distance_request, distance_result);
      const S d = std::max(distance_result.min_distance, S(0));
      brute_nearest[i] = std::min(brute_nearest[i], d);
      brute_nearest[j] = std::min(brute_nearest[j], d);
    }
  }

  AllPairsData<S> all;
  manager.collide(&all, collectCollidingPair<S>);
  EXPECT_EQ(all.colliding, brute_colliding);
  // The manager hands over exactly the pairs whose boxes overlap.
  EXPECT_EQ(all.candidates, overlapping_boxes);

  // fcl::distance(a, b) and (b, a) may differ by rounding: the exact solver's bound.
  const double tolerance = Eps<S>::kExactDistanceRelative * scene.size;
  for (int i = 0; i < n; ++i) {
    NearestData<S> nearest;
    manager.distance(scene.pointers[i], &nearest, nearestOther<S>);
    ASSERT_NEAR(nearest.nearest, brute_nearest[i], tolerance) << "object " << i;
  }

  // Why nearestOther skips o1 == o2: the per-object query of a registered object
  // reaches the object itself, and FCL's default callback then reports 0.
  fcl::DefaultDistanceData<S> self_paired;
  manager.distance(scene.pointers[0], &self_paired, fcl::DefaultDistanceFunction<S>);
  EXPECT_EQ(self_paired.result.min_distance, S(0));

  // The whole-scene minimum with FCL's own default callback (no self pairs there).
  fcl::DefaultDistanceData<S> global;
  manager.distance(&global, fcl::DefaultDistanceFunction<S>);
  const S brute_min = *std::min_element(brute_nearest.begin(), brute_nearest.end());
  EXPECT_NEAR(std::max(global.result.min_distance, S(0)), brute_min, tolerance);
}

TYPED_TEST(disk_aabb, ManagerWithTightBoxesFindsWhatBruteForceFinds) {
  using S = TypeParam;
  Random random(kSeed + 2);
  // Dense (many collisions) and sparse (few, so the global minimum is positive).
  for (const double centre_range : {4.0, 25.0}) {
    SCOPED_TRACE(centre_range);
    Scene<S> scene = makeScene<S>(random, centre_range);
    fcl::DynamicAABBTreeCollisionManager<S> manager;
    manager.registerObjects(scene.pointers);
    manager.setup();
    expectManagerMatchesBruteForce(scene, manager, "as built");

    // Move two thirds of the disks (small steps and large jumps, new orientations).
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
      if (i % 3 == 0) continue;
      Eigen::Isometry3d X = randomPose(random, centre_range);
      if (i % 3 == 1) {  // a small step from where it was
        X.translation() =
            scene.objects[i]->getTransform().translation().template cast<double>() +
            random.inBall(0.1);
      }
      scene.objects[i]->setPoseAndUpdateAABB(toScalar<S>(X));
    }
    manager.update();
    expectManagerMatchesBruteForce(scene, manager, "after moves and update()");
  }
}

}  // namespace
