// Intersecting disk-shape pairs for fcl_disk_report's penetration section: a
// Disk against each shape with an exact penetration depth in fcl_disk
// (fcl_disk::kExactDiskShapePenetration: Sphere, Box, Capsule, Cylinder, Cone,
// Convex, Halfspace, Plane, TriangleP), drawn as test/test_disk_shape_penetration.cpp
// draws them and kept only if fcl_disk::diskShapeIntersect() says the two share
// a point.
//
// A pair: disk radius uniform in [0.2, 1]; the disk's and the shape's poses a
// uniformly random rotation and a centre uniform in the unit ball; the shape
// from randomShape() (test/disk_shape_penetration_draws.h, the test's: sizes
// ~0.5, so that a good share of the draws intersect). Scale of a pair (the error is
// |PD - PD_ref| / scale): r + 1 + 2, the test's bound on r + the shape's size +
// the centres' distance.
//
// Random numbers: fcl_disk_test::Random (test/test_random.h), one stream per
// shape, so a (shape, count, seed) triple gives the same pairs with every
// standard library.
#pragma once

#include <fcl/common/types.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/plane.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>
#include <fcl_disk/disk_shape_distance.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "disk_shape_penetration_draws.h"
#include "test_random.h"

namespace fcl_disk_shape_penetration_cases {

/// One stored pair: Disk(r) at X_WD against `shape` at X_WS.
template <typename Shape>
struct ShapePenCase {
  std::string name;  ///< "<shape>/<index>"
  double r = 1;
  fcl::Transform3d X_WD = fcl::Transform3d::Identity();
  fcl::Transform3d X_WS = fcl::Transform3d::Identity();
  Shape shape;
  double scale = 1;  ///< r + 1 + 2
};

inline const char* shapePenName(const fcl::Sphered*) { return "sphere"; }
inline const char* shapePenName(const fcl::Boxd*) { return "box"; }
inline const char* shapePenName(const fcl::Capsuled*) { return "capsule"; }
inline const char* shapePenName(const fcl::Cylinderd*) { return "cylinder"; }
inline const char* shapePenName(const fcl::Coned*) { return "cone"; }
inline const char* shapePenName(const fcl::Convexd*) { return "convex"; }
inline const char* shapePenName(const fcl::Halfspaced*) { return "halfspace"; }
inline const char* shapePenName(const fcl::Planed*) { return "plane"; }
inline const char* shapePenName(const fcl::TrianglePd*) { return "triangle"; }

/// Calls visit(static_cast<Shape*>(nullptr)) for every shape with an exact
/// penetration depth, in the report's order.
template <typename Visit>
void forEachExactPenetrationShape(Visit&& visit) {
  visit(static_cast<fcl::Sphered*>(nullptr));
  visit(static_cast<fcl::Boxd*>(nullptr));
  visit(static_cast<fcl::Capsuled*>(nullptr));
  visit(static_cast<fcl::Cylinderd*>(nullptr));
  visit(static_cast<fcl::Coned*>(nullptr));
  visit(static_cast<fcl::Convexd*>(nullptr));
  visit(static_cast<fcl::Halfspaced*>(nullptr));
  visit(static_cast<fcl::Planed*>(nullptr));
  visit(static_cast<fcl::TrianglePd*>(nullptr));
}

namespace detail {

using Random = fcl_disk_test::Random;
using Vd = Eigen::Vector3d;

/// Disk radius range, and the reach of both centres.
constexpr double kMinDiskRadius = 0.2, kMaxDiskRadius = 1.0;
constexpr double kCentreReach = 1.0;
/// The test's scale bound on the shape's size and on the centres' distance.
constexpr double kShapeSizeBound = 1.0, kCentreDistanceBound = 2.0;
/// Draws per requested pair before a shape gives up (the rarest, the triangle,
/// intersects in about one draw in eight).
constexpr int kAttemptsPerPair = 50;

using fcl_disk_shape_penetration_draws::randomPose;
using fcl_disk_shape_penetration_draws::randomShape;

/// A per-shape stream (FNV-1a of the name), so that adding a shape does not
/// change the others.
inline std::uint64_t shapeSeed(std::uint64_t seed, const char* name) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (const char* c = name; *c; ++c) hash = (hash ^ std::uint64_t(*c)) * 0x100000001b3ULL;
  constexpr std::uint64_t kGolden = 0x9E3779B97F4A7C15ULL;  // splitmix64's increment
  return (seed + 0x5350ULL /* "SP" */) * kGolden + hash;
}

}  // namespace detail

/// `count` intersecting pairs of a Disk and `Shape` (fewer only if
/// kAttemptsPerPair * count draws did not yield them; the caller reports the
/// number it got).
template <typename Shape>
std::vector<ShapePenCase<Shape>> makeShapePenCases(std::size_t count, std::uint64_t seed) {
  static_assert(fcl_disk::kExactDiskShapePenetration<Shape>,
                "only the shapes with an exact disk penetration depth");
  using namespace detail;
  const char* name = shapePenName(static_cast<const Shape*>(nullptr));
  Random rng(shapeSeed(seed, name));
  std::vector<ShapePenCase<Shape>> cases;
  cases.reserve(count);
  const std::size_t max_attempts = kAttemptsPerPair * count + 100;
  for (std::size_t attempt = 0; attempt < max_attempts && cases.size() < count; ++attempt) {
    // The test's order of draws: radius, disk pose, shape pose, shape.
    const double r = rng.uniform(kMinDiskRadius, kMaxDiskRadius);
    const fcl::Transform3d X_WD = randomPose<double>(rng, kCentreReach);
    const fcl::Transform3d X_WS = randomPose<double>(rng, kCentreReach);
    Shape shape = randomShape<double>(rng, static_cast<Shape*>(nullptr));
    if (!fcl_disk::diskShapeIntersect(r, X_WD, shape, X_WS)) continue;
    cases.push_back({std::string(name) + "/" + std::to_string(cases.size()), r, X_WD, X_WS,
                     std::move(shape), r + kShapeSizeBound + kCentreDistanceBound});
  }
  return cases;
}

}  // namespace fcl_disk_shape_penetration_cases
