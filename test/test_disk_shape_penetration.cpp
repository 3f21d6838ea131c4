// Signed distance of a Disk against the shapes with an exact penetration depth
// (every primitive but the Ellipsoid: kExactDiskShapePenetration), standalone and through
// fcl::distance / fcl::collide, float and double, against a long-double
// reference written here from the geometry (not from the solver's code):
//   sphere:    PD = rho - dist(s, disk), dist by projecting s on the disk's plane
//              and clamping to the rim;
//   halfspace: PD = r |P m| - h0 (the disk's lowest height below the boundary);
//   plane:     PD = min(h0 + r |P m|, r |P m| - h0);
//   capsule, cylinder, cone, box, triangle, convex: PD = min over unit w of
//              h_disk(w) + h_shape(-w), by a search over the sphere (below),
//              with the shape's support from its vertices, ends or axis.
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <fcl_disk/fcl_disk.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "test_random.h"

namespace {

using fcl_disk_test::Random;
using Vd = Eigen::Vector3d;
using Real = long double;
using VR = Eigen::Matrix<Real, 3, 1>;

/// Relative tolerances (of scale = r + shape size + centre distance). double:
/// the solvers' 1e-12 promise; float: the inputs and results are rounded to
/// float, 16 ulps of the scale.
template <typename S>
constexpr double kDepthRelative = std::is_same<S, float>::value ? 16 * 1.2e-7 : 1e-12;
/// The separation check's step: far above either rounding, far below any depth tested.
constexpr double kSeparationStepRelative = 1e-6;
/// The path of the continuity check moves the shape by this much per step (scale units).
constexpr double kPathStepRelative = 1e-3;
constexpr int kPosesPerShape = 30000;
/// The searched references take ~1 ms a pose: fewer poses.
constexpr int kSearchedPoses = 1500;

template <typename S>
fcl::Transform3<S> randomPose(Random& rng, double reach) {
  fcl::Transform3<S> X = fcl::Transform3<S>::Identity();
  X.linear() = rng.rotation().cast<S>();
  X.translation() = rng.inBall(reach).cast<S>();
  return X;
}

VR toReal(const Vd& v) { return v.cast<Real>(); }

/// Distance from a point to a disk (centre c, unit normal n, radius r).
Real pointDiskDistance(const VR& x, const VR& c, const VR& n, Real r) {
  const VR d = x - c;
  const Real height = d.dot(n);
  const VR in_plane = d - height * n;
  const Real radial = std::sqrt(in_plane.squaredNorm());
  const Real outside = std::max(radial - r, Real(0));
  return std::sqrt(height * height + outside * outside);
}

/// The disk's lowest height along unit m (relative to its centre): -r |P m|.
Real halfSpan(const VR& n, const VR& m, Real r) {
  const VR in_plane = m - m.dot(n) * n;
  return r * std::sqrt(in_plane.squaredNorm());
}

struct Pose {
  VR c, n;
  Real r;
};

template <typename S>
Pose diskOf(S r, const fcl::Transform3<S>& X) {
  return {toReal(X.translation().template cast<double>()),
          toReal(X.linear().col(2).template cast<double>()).normalized(), Real(r)};
}

/// Reference penetration depth (negative: minus the distance, for the plane
/// and halfspace; the sphere's is only used when they intersect).
template <typename S>
Real referenceDepth(S r, const fcl::Transform3<S>& X_WD, const fcl::Sphere<S>& sphere,
                    const fcl::Transform3<S>& X_WS) {
  const Pose disk = diskOf(r, X_WD);
  return Real(sphere.radius) -
         pointDiskDistance(toReal(X_WS.translation().template cast<double>()), disk.c, disk.n,
                           disk.r);
}

/// A boundary n.y = d in the shape frame, in the world: unit m and height of the disk centre.
template <typename S>
std::pair<VR, Real> boundaryInWorld(const fcl::Vector3<S>& n_S, S d, const fcl::Transform3<S>& X_WS,
                                    const VR& c) {
  const VR n = toReal(n_S.template cast<double>());
  const Real length = std::sqrt(n.squaredNorm());
  const Eigen::Matrix<Real, 3, 3> R = X_WS.linear().template cast<Real>();
  const VR m = R * (n / length);
  const VR point = X_WS.translation().template cast<Real>() + m * (Real(d) / length);
  return {m, m.dot(c - point)};
}

template <typename S>
Real referenceDepth(S r, const fcl::Transform3<S>& X_WD, const fcl::Halfspace<S>& halfspace,
                    const fcl::Transform3<S>& X_WS) {
  const Pose disk = diskOf(r, X_WD);
  const auto [m, h0] = boundaryInWorld(halfspace.n, halfspace.d, X_WS, disk.c);
  return halfSpan(disk.n, m, disk.r) - h0;
}

template <typename S>
Real referenceDepth(S r, const fcl::Transform3<S>& X_WD, const fcl::Plane<S>& plane,
                    const fcl::Transform3<S>& X_WS) {
  const Pose disk = diskOf(r, X_WD);
  const auto [m, h0] = boundaryInWorld(plane.n, plane.d, X_WS, disk.c);
  const Real span = halfSpan(disk.n, m, disk.r);
  return std::min(span + h0, span - h0);
}

/// The searched references: PD = min over unit w of F(w) = h_disk(w) +
/// h_shape(-w), found by a search of its own: given directions (the disk's
/// normals, the shape's face normals); the circles where F is kinked (normal
/// to an axis or edge, where the shape's support jumps between two vertices
/// or caps), each sampled at kCircleSamples angles and every local minimum
/// refined by golden sections; and a Fibonacci sphere of kSphereSamples
/// directions, the best kSphereStarts refined by a shrinking compass search.
constexpr int kCircleSamples = 720;
constexpr int kSphereSamples = 6000;
constexpr int kSphereStarts = 12;
constexpr Real kSearchFinalStep = 1e-13L;

/// The circle {unit w : w . axis = height} (|axis| = 1).
struct Circle {
  VR axis;
  Real height = 0;
};

/// Great circles normal to each axis.
std::vector<Circle> greatCircles(const std::vector<VR>& axes) {
  std::vector<Circle> circles;
  for (const VR& axis : axes) circles.push_back({axis, 0});
  return circles;
}

/// min over unit w of F, searched: the given directions, the circles (sampled,
/// each local minimum refined by golden sections), and a Fibonacci sphere whose
/// best samples a shrinking compass search refines.
template <typename Function>
Real searchMinimum(const Function& F, const std::vector<VR>& directions,
                   const std::vector<Circle>& circles) {
  Real best = std::numeric_limits<Real>::infinity();
  for (const VR& w : directions) best = std::min(best, F(w));
  for (const Circle& circle : circles) {
    const VR& axis = circle.axis;
    VR e1 = axis.cross(VR::UnitX());
    if (e1.squaredNorm() < 0.25L) e1 = axis.cross(VR::UnitY());
    e1 /= std::sqrt(e1.squaredNorm());
    const VR e2 = axis.cross(e1);
    const Real ring = std::sqrt(1 - circle.height * circle.height);
    const auto on_circle = [&](Real angle) {
      return F(ring * (std::cos(angle) * e1 + std::sin(angle) * e2) + circle.height * axis);
    };
    const Real step = 2 * Real(M_PI) / kCircleSamples;
    std::vector<Real> values(kCircleSamples);
    for (int k = 0; k < kCircleSamples; ++k) values[k] = on_circle(k * step);
    for (int k = 0; k < kCircleSamples; ++k) {
      const Real value = values[k];
      if (!(value <= values[(k + kCircleSamples - 1) % kCircleSamples] &&
            value <= values[(k + 1) % kCircleSamples])) {
        continue;
      }
      Real lo = (k - 1) * step, hi = (k + 1) * step;  // golden sections on a local minimum
      for (int i = 0; i < 200 && hi - lo > 1e-18L; ++i) {
        const Real m1 = lo + (hi - lo) * 0.381966L, m2 = lo + (hi - lo) * 0.618034L;
        if (on_circle(m1) < on_circle(m2)) hi = m2; else lo = m1;
      }
      best = std::min(best, on_circle((lo + hi) / 2));
    }
  }
  std::vector<std::pair<Real, VR>> samples;
  for (int k = 0; k < kSphereSamples; ++k) {
    const Real z = 1 - (2 * k + 1) / Real(kSphereSamples), ring = std::sqrt(1 - z * z);
    const Real angle = k * 2.399963229728653L;
    const VR w(ring * std::cos(angle), ring * std::sin(angle), z);
    samples.emplace_back(F(w), w);
  }
  std::partial_sort(samples.begin(), samples.begin() + kSphereStarts, samples.end(),
                    [](const auto& a, const auto& b) { return a.first < b.first; });
  for (int k = 0; k < kSphereStarts; ++k) {
    VR w = samples[k].second;
    Real value = samples[k].first;
    VR t1 = w.cross(VR::UnitX());
    if (t1.squaredNorm() < 0.25L) t1 = w.cross(VR::UnitY());
    t1 /= std::sqrt(t1.squaredNorm());
    for (Real move = 0.05L; move > kSearchFinalStep;) {
      const VR t2 = w.cross(t1);
      bool improved = false;
      for (int d = 0; d < 8 && !improved; ++d) {
        const Real a = d * Real(M_PI) / 4;
        VR trial = w + move * (std::cos(a) * t1 + std::sin(a) * t2);
        trial /= std::sqrt(trial.squaredNorm());
        const Real trial_value = F(trial);
        if (trial_value < value) value = trial_value, w = trial, improved = true;
      }
      if (!improved) move /= 2;
      t1 = t1 - t1.dot(w) * w;
      t1 /= std::sqrt(t1.squaredNorm());
    }
    best = std::min(best, value);
  }
  return best;
}

/// The disk's support h_disk(w) = c.w + r |P w|.
Real diskSupport(const Pose& disk, const VR& w) {
  const VR in_plane = w - w.dot(disk.n) * disk.n;
  return disk.c.dot(w) + disk.r * std::sqrt(in_plane.squaredNorm());
}

template <typename S>
Real referenceDepth(S r, const fcl::Transform3<S>& X_WD, const fcl::Capsule<S>& capsule,
                    const fcl::Transform3<S>& X_WS) {
  const Pose disk = diskOf(r, X_WD);
  const Eigen::Matrix<Real, 3, 3> R_WS = X_WS.linear().template cast<Real>();
  const VR axis = R_WS.col(2), centre = X_WS.translation().template cast<Real>();
  const Real h = Real(capsule.lz) / 2;
  const VR end_a = centre + h * axis, end_b = centre - h * axis;
  const auto F = [&](const VR& w_raw) {
    const VR w = w_raw / std::sqrt(w_raw.squaredNorm());
    return diskSupport(disk, w) - std::min(end_a.dot(w), end_b.dot(w));
  };
  return Real(capsule.radius) + searchMinimum(F, {disk.n, VR(-disk.n)}, greatCircles({axis}));
}

/// Cylinder (axis z of its frame, half length h, radius rho): its support at
/// -w is -centre.w + rho |P_axis w| + h |axis.w|, kinked at +-axis and on the
/// circle normal to it.
template <typename S>
Real referenceDepth(S r, const fcl::Transform3<S>& X_WD, const fcl::Cylinder<S>& cylinder,
                    const fcl::Transform3<S>& X_WS) {
  const Pose disk = diskOf(r, X_WD);
  const Eigen::Matrix<Real, 3, 3> R_WS = X_WS.linear().template cast<Real>();
  const VR axis = R_WS.col(2), centre = X_WS.translation().template cast<Real>();
  const Real h = Real(cylinder.lz) / 2, rho = Real(cylinder.radius);
  const auto F = [&](const VR& w_raw) {
    const VR w = w_raw / std::sqrt(w_raw.squaredNorm());
    const Real along = w.dot(axis);
    const VR across = w - along * axis;
    return diskSupport(disk, w) - centre.dot(w) + rho * std::sqrt(across.squaredNorm()) +
           h * std::abs(along);
  };
  return searchMinimum(F, {disk.n, VR(-disk.n), axis, VR(-axis)}, greatCircles({axis}));
}

/// Cone (axis z of its frame, apex at +h, base radius rho at -h): its support at
/// -w is the apex or the base's, whichever is larger; they tie where -w is a side
/// normal, (2h cos, 2h sin, rho) / L: on the circle w . axis = -rho / L.
template <typename S>
Real referenceDepth(S r, const fcl::Transform3<S>& X_WD, const fcl::Cone<S>& cone,
                    const fcl::Transform3<S>& X_WS) {
  const Pose disk = diskOf(r, X_WD);
  const Eigen::Matrix<Real, 3, 3> R_WS = X_WS.linear().template cast<Real>();
  const VR axis = R_WS.col(2), centre = X_WS.translation().template cast<Real>();
  const Real h = Real(cone.lz) / 2, rho = Real(cone.radius);
  const VR apex = centre + h * axis, base = centre - h * axis;
  const auto F = [&](const VR& w_raw) {
    const VR w = w_raw / std::sqrt(w_raw.squaredNorm());
    const VR across = w - w.dot(axis) * axis;
    const Real base_support = -base.dot(w) + rho * std::sqrt(across.squaredNorm());
    return diskSupport(disk, w) + std::max(-apex.dot(w), base_support);
  };
  const Real slant = std::sqrt(4 * h * h + rho * rho);
  return searchMinimum(F, {disk.n, VR(-disk.n), axis, VR(-axis)},
                       {Circle{axis, -rho / slant}, Circle{axis, 0}});
}

/// A polytope in the world: vertices (its support is the largest vertex),
/// edge directions (F is kinked on the circles normal to them) and face
/// normals (where those circles cross).
struct PolytopeInWorld {
  std::vector<VR> vertices, edges, normals;
};

template <typename S>
VR toWorld(const fcl::Transform3<S>& X_WS, const fcl::Vector3<S>& x_S) {
  return X_WS.translation().template cast<Real>() + X_WS.linear().template cast<Real>() * x_S.template cast<Real>();
}

template <typename S>
Real polytopeDepth(S r, const fcl::Transform3<S>& X_WD, const PolytopeInWorld& polytope) {
  const Pose disk = diskOf(r, X_WD);
  const auto F = [&](const VR& w_raw) {
    const VR w = w_raw / std::sqrt(w_raw.squaredNorm());
    Real lowest = std::numeric_limits<Real>::infinity();
    for (const VR& x : polytope.vertices) lowest = std::min(lowest, x.dot(w));
    return diskSupport(disk, w) - lowest;
  };
  std::vector<VR> directions = {disk.n, VR(-disk.n)};
  for (const VR& m : polytope.normals) directions.insert(directions.end(), {m, VR(-m)});
  return searchMinimum(F, directions, greatCircles(polytope.edges));
}

template <typename S>
Real referenceDepth(S r, const fcl::Transform3<S>& X_WD, const fcl::Box<S>& box,
                    const fcl::Transform3<S>& X_WS) {
  PolytopeInWorld polytope;
  const fcl::Vector3<S> half = box.side / S(2);
  for (const int sx : {-1, 1}) {
    for (const int sy : {-1, 1}) {
      for (const int sz : {-1, 1}) {
        polytope.vertices.push_back(
            toWorld(X_WS, fcl::Vector3<S>(S(sx) * half.x(), S(sy) * half.y(), S(sz) * half.z())));
      }
    }
  }
  for (int i = 0; i < 3; ++i) polytope.edges.push_back(X_WS.linear().col(i).template cast<Real>());
  polytope.normals = polytope.edges;
  return polytopeDepth(r, X_WD, polytope);
}

template <typename S>
Real referenceDepth(S r, const fcl::Transform3<S>& X_WD, const fcl::TriangleP<S>& triangle,
                    const fcl::Transform3<S>& X_WS) {
  PolytopeInWorld polytope;
  for (const auto* x : {&triangle.a, &triangle.b, &triangle.c}) {
    polytope.vertices.push_back(toWorld(X_WS, *x));
  }
  for (int i = 0; i < 3; ++i) {
    const VR edge = polytope.vertices[(i + 1) % 3] - polytope.vertices[i];
    if (edge.squaredNorm() > 0) polytope.edges.push_back(edge / std::sqrt(edge.squaredNorm()));
  }
  const VR normal = polytope.edges.size() == 3 ? VR(polytope.edges[0].cross(polytope.edges[1])) : VR::Zero();
  if (normal.squaredNorm() > 0) polytope.normals.push_back(normal / std::sqrt(normal.squaredNorm()));
  return polytopeDepth(r, X_WD, polytope);
}

template <typename S>
Real referenceDepth(S r, const fcl::Transform3<S>& X_WD, const fcl::Convex<S>& convex,
                    const fcl::Transform3<S>& X_WS) {
  PolytopeInWorld polytope;
  const auto& vertices = convex.getVertices();
  for (const auto& x : vertices) polytope.vertices.push_back(toWorld(X_WS, x));
  const std::vector<int>& list = convex.getFaces();
  for (std::size_t at = 0; at < list.size(); at += list[at] + 1) {
    const int count = list[at];
    for (int i = 0; i < count; ++i) {
      const VR edge = polytope.vertices[list[at + 1 + (i + 1) % count]] - polytope.vertices[list[at + 1 + i]];
      polytope.edges.push_back(edge / std::sqrt(edge.squaredNorm()));
    }
    const VR a = polytope.vertices[list[at + 1]], b = polytope.vertices[list[at + 2]],
             c = polytope.vertices[list[at + 3]];
    const VR normal = (b - a).cross(c - a);
    polytope.normals.push_back(normal / std::sqrt(normal.squaredNorm()));
  }
  return polytopeDepth(r, X_WD, polytope);
}

/// Random shapes of size ~0.5 at centres in the unit ball, a disk of radius
/// 0.2..1, so that a good share of poses intersect.
template <typename S>
fcl::Sphere<S> randomShape(Random& rng, fcl::Sphere<S>*) {
  return fcl::Sphere<S>(S(rng.uniform(0.05, 1.0)));
}
template <typename S>
fcl::Halfspace<S> randomShape(Random& rng, fcl::Halfspace<S>*) {
  return fcl::Halfspace<S>(rng.unitVector().cast<S>(), S(rng.uniform(-0.5, 0.5)));
}
template <typename S>
fcl::Capsule<S> randomShape(Random& rng, fcl::Capsule<S>*) {
  return fcl::Capsule<S>(S(rng.uniform(0.0, 0.5)), S(rng.uniform(0.0, 2.0)));
}
template <typename S>
fcl::Cylinder<S> randomShape(Random& rng, fcl::Cylinder<S>*) {
  return fcl::Cylinder<S>(S(rng.uniform(0.05, 1.0)), S(rng.uniform(0.0, 2.0)));
}
template <typename S>
fcl::Cone<S> randomShape(Random& rng, fcl::Cone<S>*) {
  return fcl::Cone<S>(S(rng.uniform(0.0, 1.0)), S(rng.uniform(0.0, 2.0)));
}
template <typename S>
fcl::Plane<S> randomShape(Random& rng, fcl::Plane<S>*) {
  return fcl::Plane<S>(rng.unitVector().cast<S>(), S(rng.uniform(-0.5, 0.5)));
}
template <typename S>
fcl::Box<S> randomShape(Random& rng, fcl::Box<S>*) {
  return fcl::Box<S>(S(rng.uniform(0.0, 1.2)), S(rng.uniform(0.0, 1.2)), S(rng.uniform(0.0, 1.2)));
}
template <typename S>
fcl::TriangleP<S> randomShape(Random& rng, fcl::TriangleP<S>*) {
  return fcl::TriangleP<S>(rng.inBall(0.8).cast<S>(), rng.inBall(0.8).cast<S>(),
                           rng.inBall(0.8).cast<S>());
}
/// A tetrahedron, or a prism over a triangle with its top shifted (planar
/// parallelogram sides), in the ball of radius 1; faces counter-clockwise seen
/// from outside. Coordinates are multiples of kConvexGrid, so that every vertex,
/// and so every side's planarity, is exact in float too (the solvers take a
/// face to be the plane of its Newell normal).
constexpr double kConvexGrid = 1.0 / 1024;
template <typename S>
fcl::Convex<S> randomShape(Random& rng, fcl::Convex<S>*) {
  const auto on_grid = [&](double reach) {
    Vd x = rng.inBall(reach);
    for (int i = 0; i < 3; ++i) x[i] = std::round(x[i] / kConvexGrid) * kConvexGrid;
    return x;
  };
  auto vertices = std::make_shared<std::vector<fcl::Vector3<S>>>();
  std::vector<std::vector<int>> faces;
  Vd base[3];
  for (;;) {
    for (Vd& x : base) x = on_grid(0.5);
    if ((base[1] - base[0]).cross(base[2] - base[0]).norm() > 0.05) break;
  }
  const Vd base_normal = (base[1] - base[0]).cross(base[2] - base[0]).normalized();
  Vd lift;
  do lift = on_grid(0.5);
  while (std::abs(lift.dot(base_normal)) < 0.1);
  if (rng.uniform(0.0, 1.0) < 0.5) {
    for (const Vd& x : base) vertices->push_back(x.cast<S>());
    vertices->push_back((base[0] + lift).cast<S>());
    faces = {{0, 1, 2}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  } else {
    for (const Vd& x : base) vertices->push_back(x.cast<S>());
    for (const Vd& x : base) vertices->push_back((x + lift).cast<S>());
    faces = {{0, 1, 2}, {3, 4, 5}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}};
  }
  Vd centroid = Vd::Zero();
  for (const auto& x : *vertices) centroid += x.template cast<double>();
  centroid /= double(vertices->size());
  auto list = std::make_shared<std::vector<int>>();
  for (auto& face : faces) {
    const Vd a = (*vertices)[face[0]].template cast<double>();
    const Vd normal = ((*vertices)[face[1]].template cast<double>() - a)
                          .cross((*vertices)[face[2]].template cast<double>() - a);
    if (normal.dot(a - centroid) < 0) std::reverse(face.begin(), face.end());
    list->push_back(int(face.size()));
    list->insert(list->end(), face.begin(), face.end());
  }
  return fcl::Convex<S>(vertices, int(faces.size()), list);
}

template <typename S, typename Shape>
void checkShape(const char* name, std::uint64_t seed, int poses = kPosesPerShape) {
  SCOPED_TRACE(name);
  Random rng(seed);
  int intersecting = 0;
  double worst = 0;
  for (int i = 0; i < poses; ++i) {
    const S r = S(rng.uniform(0.2, 1.0));
    const fcl::Transform3<S> X_WD = randomPose<S>(rng, 1.0);
    const fcl::Transform3<S> X_WS = randomPose<S>(rng, 1.0);
    const Shape shape = randomShape<S>(rng, static_cast<Shape*>(nullptr));
    const double scale = double(r) + 1.0 + 2.0;  // r + shape size + centre distance bound
    const double tolerance = kDepthRelative<S> * scale;
    const auto answer = fcl_disk::signedDiskShapeDistance(r, X_WD, shape, X_WS);
    const auto trace = [&] { return std::string(name) + " pose " + std::to_string(i); };
    ASSERT_TRUE(std::isfinite(double(answer.signed_distance))) << trace();
    EXPECT_NEAR(answer.direction.template cast<double>().norm(), 1.0, 1e-6) << trace();
    if (answer.signed_distance > 0) {
      // Apart: the plain distance, direction from the disk's point to the shape's.
      const auto distance = fcl_disk::diskShapeDistance(r, X_WD, shape, X_WS);
      EXPECT_EQ(answer.signed_distance, distance.distance) << trace();
      continue;
    }
    ++intersecting;
    const double depth = -double(answer.signed_distance);
    const double reference = double(referenceDepth(r, X_WD, shape, X_WS));
    EXPECT_NEAR(depth, reference, tolerance) << trace();
    worst = std::max(worst, std::abs(depth - reference) / scale);
    // Witnesses: p1 - p2 = depth * direction, p1 on the disk.
    const Vd p1 = answer.p_W1.template cast<double>(), p2 = answer.p_W2.template cast<double>();
    const Vd w = answer.direction.template cast<double>();
    EXPECT_LE((p1 - p2 - depth * w).norm(), tolerance) << trace();
    const Pose disk = diskOf(r, X_WD);
    EXPECT_LE(double(pointDiskDistance(toReal(p1), disk.c, disk.n, disk.r)), tolerance) << trace();
    // Moving the shape by depth + step along the direction separates; by
    // depth - step it does not.
    const double step = kSeparationStepRelative * scale;
    fcl::Transform3<S> moved = X_WS;
    moved.translation() = (X_WS.translation().template cast<double>() + (depth + step) * w).template cast<S>();
    EXPECT_GT(fcl_disk::diskShapeDistance(r, X_WD, shape, moved).distance, S(0)) << trace();
    if (depth > 2 * step) {
      moved.translation() =
          (X_WS.translation().template cast<double>() + (depth - step) * w).template cast<S>();
      EXPECT_TRUE(fcl_disk::diskShapeIntersect(r, X_WD, shape, moved)) << trace();
    }
    // Through FCL, both orders and solvers: -depth; libccd with the deepest
    // points (FCL's EPA convention), indep with collide()'s contact point.
    auto disk_geometry = std::make_shared<fcl_disk::Disk<S>>(r);
    auto shape_geometry = std::make_shared<Shape>(shape);
    fcl::CollisionObject<S> disk_object(disk_geometry, X_WD), shape_object(shape_geometry, X_WS);
    for (const auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
      for (const bool disk_first : {true, false}) {
        fcl::DistanceRequest<S> request(true);
        request.enable_signed_distance = true;
        request.gjk_solver_type = solver;
        fcl::DistanceResult<S> result;
        if (disk_first) {
          fcl::distance(&disk_object, &shape_object, request, result);
        } else {
          fcl::distance(&shape_object, &disk_object, request, result);
        }
        EXPECT_NEAR(double(result.min_distance), -depth, tolerance) << trace();
        if (solver == fcl::GST_LIBCCD && depth > 0) {
          const Vd o1_point = (disk_first ? p1 : p2), o2_point = (disk_first ? p2 : p1);
          EXPECT_LE((result.nearest_points[0].template cast<double>() - o1_point).norm(), tolerance)
              << trace();
          EXPECT_LE((result.nearest_points[1].template cast<double>() - o2_point).norm(), tolerance)
              << trace();
        }
      }
    }
    // fcl::collide: one contact, depth and normal of the penetration.
    fcl::CollisionRequest<S> request(1, true);
    fcl::CollisionResult<S> result;
    ASSERT_EQ(fcl::collide(&disk_object, &shape_object, request, result), 1u) << trace();
    EXPECT_NEAR(double(result.getContact(0).penetration_depth), depth, tolerance) << trace();
    if (depth > tolerance) {
      EXPECT_LE((result.getContact(0).normal.template cast<double>() - w).norm(), 1e-6) << trace();
    }
  }
  std::cout << "  " << name << ": " << intersecting << " intersecting poses of " << poses
            << ", largest |PD - PD_ref| / scale " << worst << "\n";
  EXPECT_GT(intersecting, poses / 10);
}

template <typename S>
class DiskShapePenetration : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(DiskShapePenetration, Scalars);

TYPED_TEST(DiskShapePenetration, SphereMatchesReference) {
  checkShape<TypeParam, fcl::Sphere<TypeParam>>("sphere", 11);
}
TYPED_TEST(DiskShapePenetration, HalfspaceMatchesReference) {
  checkShape<TypeParam, fcl::Halfspace<TypeParam>>("halfspace", 12);
}
TYPED_TEST(DiskShapePenetration, PlaneMatchesReference) {
  checkShape<TypeParam, fcl::Plane<TypeParam>>("plane", 13);
}
TYPED_TEST(DiskShapePenetration, CapsuleMatchesReference) {
  checkShape<TypeParam, fcl::Capsule<TypeParam>>("capsule", 14, kSearchedPoses);
}
TYPED_TEST(DiskShapePenetration, CylinderMatchesReference) {
  checkShape<TypeParam, fcl::Cylinder<TypeParam>>("cylinder", 15, kSearchedPoses);
}
TYPED_TEST(DiskShapePenetration, ConeMatchesReference) {
  checkShape<TypeParam, fcl::Cone<TypeParam>>("cone", 19, kSearchedPoses);
}
TYPED_TEST(DiskShapePenetration, BoxMatchesReference) {
  checkShape<TypeParam, fcl::Box<TypeParam>>("box", 16, kSearchedPoses);
}
TYPED_TEST(DiskShapePenetration, TriangleMatchesReference) {
  checkShape<TypeParam, fcl::TriangleP<TypeParam>>("triangle", 17, kSearchedPoses);
}
TYPED_TEST(DiskShapePenetration, ConvexMatchesReference) {
  checkShape<TypeParam, fcl::Convex<TypeParam>>("convex", 18, kSearchedPoses);
}

/// A cone whose base rim grazes through the disk by 4e-6 of the scene: the
/// generic solver stalls 5e-13 from the cone without proving either answer,
/// and the cone's penetration candidates decide the overlap.
TEST(DiskShapePenetration, GrazingOverlapTheSolverLeavesOpen) {
  const auto pose = [](std::initializer_list<double> rows) {
    fcl::Transform3d X = fcl::Transform3d::Identity();
    const std::vector<double> m(rows);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) X.linear()(i, j) = m[4 * i + j];
      X.translation()[i] = m[4 * i + 3];
    }
    // The rows are a float rotation's: orthonormal to double precision again.
    X.linear() = Eigen::Quaterniond(X.linear()).normalized().toRotationMatrix();
    return X;
  };
  const double r = 0.84621530771255493;
  const fcl::Transform3d X_WD = pose({0.21576054394245148, -0.94261282682418823, 0.25481066107749939,
                                      -0.16098333895206451, -0.96560460329055786, -0.2447512149810791,
                                      -0.087776049971580505, 0.50574624538421631, 0.1451040506362915,
                                      -0.22710773348808289, -0.96299892663955688, -0.44478151202201843});
  const fcl::Transform3d X_WS = pose({0.69901025295257568, 0.61131948232650757, -0.37104335427284241,
                                      -0.34618356823921204, 0.49454975128173828, -0.78802913427352905,
                                      -0.36664777994155884, 0.68888574838638306, -0.51653188467025757,
                                      0.072791144251823425, -0.85316836833953857, -0.38350799679756165});
  const fcl::Coned cone(0.30189511179924011, 0.19546227157115936);
  const double reference = double(referenceDepth(r, X_WD, cone, X_WS));
  ASSERT_GT(reference, 1e-6);
  const double scale = r + 1.0 + 2.0;
  EXPECT_EQ(fcl_disk::diskShapeDistance(r, X_WD, cone, X_WS).distance, 0.0);
  fcl_disk::DiskContact<double> contact;
  ASSERT_TRUE(fcl_disk::diskShapeIntersect(r, X_WD, cone, X_WS, &contact));
  EXPECT_NEAR(contact.penetration_depth, reference, kDepthRelative<double> * scale);
  EXPECT_NEAR(fcl_disk::signedDiskShapeDistance(r, X_WD, cone, X_WS).signed_distance, -reference,
              kDepthRelative<double> * scale);
}

TEST(DiskShapePenetration, HandMadeCases) {
  using X = fcl::Transform3d;
  X disk = X::Identity();  // radius 1 in the XY plane at the origin
  // A sphere of radius 0.5 centred 0.2 above the disk's face: out along +z by 0.3.
  X sphere_pose = X::Identity();
  sphere_pose.translation() = Vd(0.3, 0, 0.2);
  auto s = fcl_disk::signedDiskShapeDistance(1.0, disk, fcl::Sphered(0.5), sphere_pose);
  EXPECT_NEAR(s.signed_distance, -0.3, 1e-15);
  EXPECT_NEAR((s.direction - Vd::UnitZ()).norm(), 0.0, 1e-15);
  // Centre on the disk: out along the normal by the radius (tie between +-n).
  sphere_pose.translation() = Vd(0.3, 0, 0);
  s = fcl_disk::signedDiskShapeDistance(1.0, disk, fcl::Sphered(0.5), sphere_pose);
  EXPECT_NEAR(s.signed_distance, -0.5, 1e-15);
  EXPECT_NEAR(std::abs(s.direction.z()), 1.0, 1e-15);
  // Centre beyond the rim: out radially, by 0.5 - 0.1.
  sphere_pose.translation() = Vd(1.1, 0, 0);
  s = fcl_disk::signedDiskShapeDistance(1.0, disk, fcl::Sphered(0.5), sphere_pose);
  EXPECT_NEAR(s.signed_distance, -0.4, 1e-15);
  EXPECT_NEAR((s.direction - Vd::UnitX()).norm(), 0.0, 1e-15);
  // The ground z <= 0 under a disk standing on its rim, sunk 0.25 into it.
  X standing = X::Identity();
  standing.linear() = Eigen::AngleAxisd(M_PI / 2, Vd::UnitX()).toRotationMatrix();
  standing.translation() = Vd(0, 0, 0.75);
  s = fcl_disk::signedDiskShapeDistance(1.0, standing, fcl::Halfspaced(Vd::UnitZ(), 0.0),
                                        X::Identity());
  EXPECT_NEAR(s.signed_distance, -0.25, 1e-15);
  EXPECT_NEAR((s.direction + Vd::UnitZ()).norm(), 0.0, 1e-15);
  EXPECT_NEAR((s.p_W1 - Vd(0, 0, -0.25)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((s.p_W2 - Vd(0, 0, 0)).norm(), 0.0, 1e-15);
  // The plane z = 0 through the same disk: out by the shorter side, 0.25 (down).
  s = fcl_disk::signedDiskShapeDistance(1.0, standing, fcl::Planed(Vd::UnitZ(), 0.0), X::Identity());
  EXPECT_NEAR(s.signed_distance, -0.25, 1e-15);
  // NaN in, NaN out.
  X nan_pose = X::Identity();
  nan_pose.translation().x() = std::nan("");
  s = fcl_disk::signedDiskShapeDistance(1.0, nan_pose, fcl::Sphered(0.5), X::Identity());
  EXPECT_TRUE(std::isnan(s.signed_distance));
}

/// The signed distance is continuous through contact and 1-Lipschitz in the
/// shape's translation.
TEST(DiskShapePenetration, ContinuousThroughContact) {
  using X = fcl::Transform3d;
  Random rng(21);
  for (int path = 0; path < 50; ++path) {
    const X disk = randomPose<double>(rng, 0.5);
    X sphere_pose = X::Identity();
    const Vd start = rng.inBall(0.2), direction = rng.unitVector();
    double last = NAN;
    for (int k = 0; k <= 2000; ++k) {
      sphere_pose.translation() = start + (k * kPathStepRelative) * direction;
      const double sd =
          fcl_disk::signedDiskShapeDistance(0.7, disk, fcl::Sphered(0.3), sphere_pose).signed_distance;
      if (k > 0) {
        EXPECT_LE(std::abs(sd - last), kPathStepRelative * (1 + 1e-9) + 1e-12)
            << "path " << path << " step " << k;
      }
      last = sd;
    }
  }
}

}  // namespace
