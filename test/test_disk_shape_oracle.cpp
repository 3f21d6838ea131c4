// diskShapeDistance() against distances known without any solver
// (test/disk_shape_oracle.h), for every FCL primitive, in double and float:
//
// * Aligned families: the shape placed so that its support point along -w is
//   `gap` from the disk's support point along w, hence d == gap exactly. w random,
//   along the disk's normal (a vertex or a face over the disk's face), along a
//   face normal of the shape with the disk parallel to that face, perpendicular to
//   a box edge (rim against an edge); gaps 0 (touching) and 1e-12..1e6 of the
//   scene; shapes far from the origin; every length scaled by 1e-6..1e6.
// * Searched families: random poses, overlapping poses and a disk inside the
//   shape, against the nested golden-section reference (long double).
//
// Each answer is also checked for its points: the disk point on the disk, the
// shape point on the shape (long double distances written here), |p - q| ==
// distance, and lower_bound <= the true distance.
#include <fcl_disk/disk_shape_distance.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <type_traits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "disk_shape_fcl.h"
#include "disk_shape_oracle.h"
#include "test_random.h"

namespace {

using namespace fcl_disk_test::oracle;
using fcl_disk_test::Random;

/// |d - d_true| and the points' offsets from their shapes, relative to the
/// scene (r + R_S + |c_D - c_S|): the bound the header promises (double).
constexpr double kDoubleRelative = 1e-12;
/// Float: the solver rounds its double answer to float (1/2 ulp), and the pose
/// rounded to float moves the true distance by a few float ulps of the scene
/// (the distance is 1-Lipschitz in the points; a float rotation is orthonormal
/// to ~1 ulp); 32 float ulps leave a margin over the ~4 measured.
constexpr double kFloatRelative = 32 * 1.1920928955078125e-07;

/// The shapes under test, of size ~0.5 (scaled by the families).
Shape makeShape(Kind kind) {
  Shape s;
  s.kind = kind;
  switch (kind) {
    case Kind::sphere: s.dims = V3(0.4, 0, 0); break;
    case Kind::box: s.dims = V3(0.4, 0.25, 0.15); break;
    case Kind::capsule: s.dims = V3(0.2, 0.4, 0); break;
    case Kind::cylinder: s.dims = V3(0.3, 0.4, 0); break;
    case Kind::cone: s.dims = V3(0.3, 0.4, 0); break;
    case Kind::ellipsoid: s.dims = V3(0.5, 0.3, 0.2); break;
    case Kind::convex:
      // A frustum: a 0.8 x 0.5 base, a 0.6 x 0.4 top, 0.3 high.
      s.vertices = {V3(-0.4, -0.25, -0.15), V3(0.4, -0.25, -0.15), V3(0.4, 0.25, -0.15),
                    V3(-0.4, 0.25, -0.15),  V3(-0.3, -0.2, 0.15),  V3(0.3, -0.2, 0.15),
                    V3(0.3, 0.2, 0.15),     V3(-0.3, 0.2, 0.15)};
      s.faces = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
      break;
    case Kind::halfspace:
    case Kind::plane:
      s.n = V3(0, 0, 1);
      s.d = 0.1;
      break;
    case Kind::triangle: s.vertices = {V3(-0.3, -0.2, 0), V3(0.5, -0.1, 0.05), V3(0.1, 0.4, -0.05)}; break;
  }
  return s;
}

Shape scaled(Shape s, Real k) {
  s.dims *= k;
  for (V3& v : s.vertices) v *= k;
  s.d *= k;
  return s;
}

/// A disk and a shape pose in long double, and their poses in S exactly as the
/// solver sees them (the long double values are rounded to S first, so the
/// oracle and the solver describe the same sets up to that rounding).
struct Case {
  std::string family;
  Shape shape;
  Disk disk;
  Pose X;
  Real truth;  ///< the true distance, or -1: ask the reference
};

M3 rotationOf(Random& random) { return random.rotation().cast<Real>(); }
V3 unitOf(Random& random) { return random.unitVector().cast<Real>(); }

Disk makeDisk(const V3& c, const M3& R, Real r) { return Disk{c, R.col(0), R.col(1), r}; }

/// A rotation whose third column is n.
M3 withNormal(const V3& n, Random& random) {
  const V3 a = unitOf(random);
  V3 u = a - a.dot(n) * n;
  u.normalize();
  M3 R;
  R.col(0) = u;
  R.col(1) = n.cross(u);
  R.col(2) = n;
  return R;
}

std::vector<Case> alignedCases(Kind kind, Random& random) {
  std::vector<Case> cases;
  const Real gaps[] = {0, 1e-12, 1e-9, 1e-6, 1e-3, 1, 1e3, 1e6};
  for (int i = 0; i < 240; ++i) {
    const Real k = std::pow(Real(10), Real(random.uniform(-6, 6)));  // every length
    const bool far = random.chance(0.25);
    const V3 offset = far ? V3(unitOf(random) * Real(random.uniform(1e5, 1e6)) * k) : V3::Zero();
    Shape shape = scaled(makeShape(kind), k);
    const Real r = Real(random.uniform(0.1, 1.0)) * k;
    const Real gap = gaps[i % 8] * (r + shape.boundingRadius());
    M3 R_disk = rotationOf(random), R_shape = rotationOf(random);
    V3 w = unitOf(random);
    std::string family = "random w";
    const int variant = (i / 8) % 4;
    if (kind == Kind::halfspace || kind == Kind::plane) {
      w = -(R_shape * shape.n);  // the only directions with a support point
      family = "normal";
    } else if (variant == 1) {
      w = R_disk.col(2) * (random.chance(0.5) ? 1 : -1);
      family = "along the disk normal (vertex or face over the disk's face)";
    } else if (variant == 2 && (kind == Kind::box || kind == Kind::convex || kind == Kind::triangle ||
                                kind == Kind::cylinder || kind == Kind::cone)) {
      // The disk parallel to a face: w = minus the face normal, disk normal = w.
      V3 face_normal_S(0, 0, -1);  // the cap / base / bottom face
      if (kind == Kind::triangle) {
        face_normal_S = (shape.vertices[1] - shape.vertices[0])
                            .cross(shape.vertices[2] - shape.vertices[0])
                            .normalized();
      }
      w = -(R_shape * face_normal_S);
      R_disk = withNormal(w, random);
      family = "disk parallel to a face";
    } else if (variant == 3 && kind == Kind::box) {
      // w perpendicular to the box's z edges: the lowest feature is an edge.
      const Real angle = Real(random.uniform(0, 6.283185307179586));
      w = R_shape * V3(std::cos(angle), std::sin(angle), 0);
      family = "rim against an edge";
    }
    const Disk disk = makeDisk(offset, R_disk, r);
    Pose X = alignedPair(disk, shape, R_shape, w, gap);
    cases.push_back({family + (far ? ", far from the origin" : ""), shape, disk, X, gap});
  }
  return cases;
}

std::vector<Case> searchedCases(Kind kind, Random& random) {
  std::vector<Case> cases;
  for (int i = 0; i < 36; ++i) {
    Shape shape = makeShape(kind);
    Real r = Real(random.uniform(0.1, 1.0));
    Pose X;
    X.R = rotationOf(random);
    X.t = unitOf(random) * Real(random.uniform(0, 1.2));
    std::string family = i % 3 == 0 ? "random" : "overlapping";
    if (i % 3 == 1) X.t *= Real(0.3);  // mostly overlapping
    V3 c = V3::Zero();
    if (i % 3 == 2 && kind != Kind::triangle && kind != Kind::plane) {
      r = Real(0.05);  // a small disk at the shape's centre: inside it
      c = X.t + (kind == Kind::halfspace ? V3(X.R * V3(0, 0, -1)) : V3::Zero());
      family = "disk inside the shape";
    }
    const Disk disk = makeDisk(c, rotationOf(random), r);
    cases.push_back({family, shape, disk, X, -1});
  }
  return cases;
}

template <typename S>
void check(const Case& c, double tolerance_relative, int index) {
  // The poses in S, and the oracle's sets rebuilt from exactly those values.
  fcl::Transform3<S> X_WD = fcl::Transform3<S>::Identity(), X_WS = fcl::Transform3<S>::Identity();
  M3 R_disk;
  R_disk.col(0) = c.disk.u;
  R_disk.col(1) = c.disk.v;
  R_disk.col(2) = c.disk.normal();
  X_WD.linear() = R_disk.cast<S>();
  X_WD.translation() = c.disk.c.cast<S>();
  X_WS.linear() = c.X.R.cast<S>();
  X_WS.translation() = c.X.t.cast<S>();
  const S r = S(c.disk.r);
  const Disk disk{X_WD.translation().template cast<Real>(),
                  X_WD.linear().col(0).template cast<Real>(),
                  X_WD.linear().col(1).template cast<Real>(), Real(r)};
  Pose X;
  X.R = X_WS.linear().template cast<Real>();
  X.t = X_WS.translation().template cast<Real>();
  const auto fcl_shape = toFcl<S>(c.shape);
  const Shape shape = [&] {  // the dimensions as stored in S
    Shape s = c.shape;
    for (int i = 0; i < 3; ++i) s.dims[i] = Real(S(s.dims[i]));
    for (V3& v : s.vertices) v = v.cast<S>().template cast<Real>();
    s.d = Real(S(s.d));
    return s;
  }();

  const auto answer = diskShapeDistanceAny(r, X_WD, *fcl_shape, X_WS);
  // The library's scale: r + R_S + |c_D - c_S| (for a halfspace or plane, the
  // disk centre's height over the boundary instead of the centre distance).
  const bool boundary = shape.kind == Kind::halfspace || shape.kind == Kind::plane;
  const Real scale = disk.r + shape.boundingRadius() +
                     (boundary ? std::abs((X.R * shape.n).dot(disk.c - X.t) - shape.d)
                               : (disk.c - X.t).norm());
  // World coordinates round to an ulp of their magnitude: the points carry that,
  // and in float the poses themselves (the aligned truth is for the unrounded
  // long double poses, which differ from the float ones by that much).
  const Real far = std::max(disk.c.norm(), X.t.norm());
  const Real world_rounding = 4 * Real(std::numeric_limits<S>::epsilon()) * far;
  const bool is_float = std::is_same<S, float>::value;
  // The aligned truth is for the long double poses; where rounding them to S
  // could move it by a hundredth of the tolerance, the reference is asked about
  // the rounded ones instead.
  const bool truth_survives_rounding =
      world_rounding <= Real(0.01) * Real(tolerance_relative) * scale;
  const Real truth =
      c.truth >= 0 && truth_survives_rounding ? c.truth : referenceDistance(disk, shape, X);
  const Real tolerance = Real(tolerance_relative) * scale + (is_float ? world_rounding : 0);
  std::ostringstream what;
  what.precision(21);
  what << kindName(c.shape.kind) << " / " << c.family << " #" << index << ": r " << disk.r
       << "\nX_WD\n" << X_WD.matrix() << "\nX_WS\n" << X_WS.matrix() << "\nd " << answer.distance
       << " truth " << truth << " scale " << scale;
  const V3 p = answer.p_W_disk.template cast<Real>(), q = answer.p_W_shape.template cast<Real>();
  EXPECT_LE(std::abs(Real(answer.distance) - truth), tolerance) << what.str();
  const Real point_tolerance = tolerance + world_rounding;
  EXPECT_LE(pointToDisk(disk, p), point_tolerance) << "disk point off the disk\n" << what.str();
  EXPECT_LE(pointDistanceWorld(shape, X, q), point_tolerance) << "shape point off the shape\n"
                                                               << what.str();
  EXPECT_LE(std::abs((p - q).norm() - Real(answer.distance)), 2 * point_tolerance) << what.str();
  EXPECT_LE(Real(answer.lower_bound), truth + tolerance) << what.str();
}

class DiskShapeOracle : public ::testing::TestWithParam<Kind> {};

TEST_P(DiskShapeOracle, AlignedFamiliesDouble) {
  Random random(1000 + int(GetParam()));
  int index = 0;
  for (const Case& c : alignedCases(GetParam(), random)) check<double>(c, kDoubleRelative, index++);
}

TEST_P(DiskShapeOracle, AlignedFamiliesFloat) {
  Random random(2000 + int(GetParam()));
  int index = 0;
  for (const Case& c : alignedCases(GetParam(), random)) {
    // Float holds lengths in 1e-37..1e37 and the rounding of a pose far from the
    // origin is an ulp of its translation; the scale families stay in range.
    check<float>(c, kFloatRelative, index++);
  }
}

TEST_P(DiskShapeOracle, SearchedFamiliesDouble) {
  Random random(3000 + int(GetParam()));
  int index = 0;
  for (const Case& c : searchedCases(GetParam(), random)) check<double>(c, kDoubleRelative, index++);
}

TEST_P(DiskShapeOracle, SearchedFamiliesFloat) {
  Random random(4000 + int(GetParam()));
  int index = 0;
  for (const Case& c : searchedCases(GetParam(), random)) check<float>(c, kFloatRelative, index++);
}

INSTANTIATE_TEST_SUITE_P(EveryPrimitive, DiskShapeOracle,
                         ::testing::Values(Kind::sphere, Kind::box, Kind::capsule, Kind::cylinder,
                                           Kind::cone, Kind::ellipsoid, Kind::convex,
                                           Kind::halfspace, Kind::plane, Kind::triangle),
                         [](const ::testing::TestParamInfo<Kind>& info) {
                           return std::string(kindName(info.param));
                         });

}  // namespace
