// An independent, long-double reference for the penetration depth of a disk
// against the FCL primitives with an exact PD in fcl_disk (Sphere, Halfspace,
// Plane, Capsule, Cylinder, Cone, Box, TriangleP, Convex), for
// test_disk_shape_penetration and fcl_disk_report. Header-only; FCL's shape
// classes for their dimensions, Eigen and the standard library (no fcl_disk
// code): written from the geometry, not from the solver, so a bug in the
// solver cannot leak into the values it is judged against.
//
// The disk: centre c, unit normal n (column 2 of its rotation), radius r.
//   sphere:    PD = rho - dist(s, disk), dist by projecting s on the disk's plane
//              and clamping to the rim;
//   halfspace: PD = r |P m| - h0 (the disk's lowest height below the boundary);
//   plane:     PD = min(h0 + r |P m|, r |P m| - h0);
//   capsule, cylinder, cone, box, triangle, convex: PD = min over unit w of
//              h_disk(w) + h_shape(-w), by a search over the sphere
//              (searchMinimum), with the shape's support from its vertices,
//              ends or axis.
// The searched references cost ~1 ms a call.
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

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace fcl_disk_shape_penetration_reference {

using Real = long double;
using VR = Eigen::Matrix<Real, 3, 1>;

inline VR toReal(const Eigen::Vector3d& v) { return v.cast<Real>(); }

/// Distance from a point to a disk (centre c, unit normal n, radius r).
inline Real pointDiskDistance(const VR& x, const VR& c, const VR& n, Real r) {
  const VR d = x - c;
  const Real height = d.dot(n);
  const VR in_plane = d - height * n;
  const Real radial = std::sqrt(in_plane.squaredNorm());
  const Real outside = std::max(radial - r, Real(0));
  return std::sqrt(height * height + outside * outside);
}

/// The disk's lowest height along unit m (relative to its centre): -r |P m|.
inline Real halfSpan(const VR& n, const VR& m, Real r) {
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
inline std::vector<Circle> greatCircles(const std::vector<VR>& axes) {
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
inline Real diskSupport(const Pose& disk, const VR& w) {
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

}  // namespace fcl_disk_shape_penetration_reference
