// Test-side knowledge of FCL's primitives, in long double, written independently
// of fcl_disk's solvers (no fcl_disk header): each shape's distance from a point,
// its support point, and two ways to know the true disk-shape distance.
//
// 1. By construction (alignedPair): for a unit direction w, put the shape so
//    that its support point along -w sits at gap * w from the disk's support
//    point along w. The plane between them, normal to w, separates the two sets
//    by `gap`, so d >= gap; and those two points are `gap` apart, so d <= gap.
//    Hence d == gap exactly, for any shape and any w, with no solver involved.
//    Ties in the supports (a face parallel to the disk, an edge) give the
//    parallel-face, rim-edge and vertex-over-face configurations.
// 2. By search (referenceDistance): d = min over the disk of f(a, b) =
//    dist(c + a u + b v, X), f jointly convex, so g(a) = min_b f(a, b) is convex
//    and nested golden-section searches over a in [-r, r] and b in
//    [-sqrt(r^2 - a^2), +sqrt(r^2 - a^2)] find the minimum value; each search
//    shrinks its bracket to long double resolution (kGoldenSteps steps of
//    0.618), so the value is good to a few long double ulps of the scene plus
//    the point distance's own rounding.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/QR>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace fcl_disk_test {
namespace oracle {

using Real = long double;
using V3 = Eigen::Matrix<Real, 3, 1>;
using M3 = Eigen::Matrix<Real, 3, 3>;

enum class Kind { sphere, box, capsule, cylinder, cone, ellipsoid, convex, halfspace, plane, triangle };

inline const char* kindName(Kind kind) {
  switch (kind) {
    case Kind::sphere: return "sphere";
    case Kind::box: return "box";
    case Kind::capsule: return "capsule";
    case Kind::cylinder: return "cylinder";
    case Kind::cone: return "cone";
    case Kind::ellipsoid: return "ellipsoid";
    case Kind::convex: return "convex";
    case Kind::halfspace: return "halfspace";
    case Kind::plane: return "plane";
    case Kind::triangle: return "triangle";
  }
  return "?";
}

/// A shape in its own frame (FCL's conventions): dims holds radius / half
/// extents / semi-axes as the kind needs; vertices and faces for convex and
/// triangle; n, d for halfspace and plane.
struct Shape {
  Kind kind;
  V3 dims{V3::Zero()};  // sphere: (rho); box: half sides; capsule, cylinder, cone: (radius, half length)
  std::vector<V3> vertices;
  std::vector<std::vector<int>> faces;  // convex: counter-clockwise seen from outside
  V3 n{V3::UnitZ()};
  Real d{0};

  /// Radius of a ball about the frame origin containing the shape (0 for the
  /// halfspace and the plane, as the library defines scale).
  Real boundingRadius() const {
    switch (kind) {
      case Kind::sphere: return dims.x();
      case Kind::box: return dims.norm();
      case Kind::capsule: return dims.x() + dims.y();
      case Kind::cylinder:
      case Kind::cone: return std::hypot(dims.x(), dims.y());
      case Kind::ellipsoid: return dims.maxCoeff();
      case Kind::convex:
      case Kind::triangle: {
        Real largest = 0;
        for (const V3& v : vertices) largest = std::max(largest, v.norm());
        return largest;
      }
      case Kind::halfspace:
      case Kind::plane: return 0;
    }
    return 0;
  }
};

inline Real pointToSegment(const V3& p, const V3& a, const V3& b) {
  const V3 ab = b - a;
  const Real length_squared = ab.squaredNorm();
  Real t = length_squared > 0 ? ab.dot(p - a) / length_squared : 0;
  t = std::clamp<Real>(t, 0, 1);
  return (p - (a + t * ab)).norm();
}

/// Distance from p to the closed convex polygon (vertices in order, planar). A
/// triangle by least squares on its edges (QR, backward stable): inside (both
/// barycentric coordinates >= 0, sum <= 1) the residual is the distance, else
/// its nearest edge; a plane test would need the normal, known only to eps /
/// sine for a sliver of sine 1e-13 (1e-6 of its size in long double).
inline Real pointToPolygon(const V3& p, const std::vector<V3>& polygon) {
  if (polygon.size() == 3) {
    Eigen::Matrix<Real, 3, 2> edges;
    edges.col(0) = polygon[1] - polygon[0];
    edges.col(1) = polygon[2] - polygon[0];
    const Eigen::Matrix<Real, 2, 1> vw = edges.colPivHouseholderQr().solve(p - polygon[0]);
    if (vw.allFinite() && vw[0] >= 0 && vw[1] >= 0 && vw[0] + vw[1] <= 1) {
      return (edges * vw - (p - polygon[0])).norm();
    }
    return std::min({pointToSegment(p, polygon[0], polygon[1]), pointToSegment(p, polygon[1], polygon[2]),
                     pointToSegment(p, polygon[2], polygon[0])});
  }
  V3 normal = V3::Zero();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    normal += polygon[i].cross(polygon[(i + 1) % polygon.size()]);
  }
  Real best = std::numeric_limits<Real>::infinity();
  if (normal.squaredNorm() > 0) {
    const V3 unit = normal.normalized();
    const V3 foot = p - unit.dot(p - polygon[0]) * unit;
    bool inside = true;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      const V3& a = polygon[i];
      const V3& b = polygon[(i + 1) % polygon.size()];
      if (unit.dot((b - a).cross(foot - a)) < 0) inside = false;
    }
    if (inside) return std::abs(unit.dot(p - polygon[0]));
  }
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    best = std::min(best, pointToSegment(p, polygon[i], polygon[(i + 1) % polygon.size()]));
  }
  return best;
}

/// Distance from p (shape frame) to the solid 2-D triangle in the (rho, z)
/// half-plane of a cone, rho >= 0.
inline Real pointToMeridianTriangle(Real rho, Real z, Real radius, Real h) {
  using V2 = Eigen::Matrix<Real, 2, 1>;
  const V2 p(rho, z), apex(0, h), rim(radius, -h), centre(0, -h);
  auto cross = [](const V2& a, const V2& b) { return a.x() * b.y() - a.y() * b.x(); };
  // Inside: to the right of apex->centre? The triangle apex, centre, rim is
  // counter-clockwise when radius > 0 (centre below apex, rim to the right).
  const bool inside = cross(centre - apex, p - apex) >= 0 && cross(rim - centre, p - centre) >= 0 &&
                      cross(apex - rim, p - rim) >= 0;
  if (inside && radius > 0 && rho <= radius) return 0;
  auto to_segment = [](const V2& q, const V2& a, const V2& b) {
    const V2 ab = b - a;
    const Real length_squared = ab.squaredNorm();
    Real t = length_squared > 0 ? ab.dot(q - a) / length_squared : 0;
    t = std::clamp<Real>(t, 0, 1);
    return (q - (a + t * ab)).norm();
  };
  return std::min({to_segment(p, apex, rim), to_segment(p, rim, centre), to_segment(p, centre, apex)});
}

/// Distance from p to the solid ellipsoid with semi-axes e (>= 0; a zero
/// semi-axis flattens it: an ellipse, a segment, a point), by bisection on the
/// root t of sum over nonzero e_i of (e_i y_i / (t + e_i^2))^2 = 1 (Eberly),
/// 200 halvings.
inline Real pointToEllipsoid(const V3& p, const V3& e) {
  Real level = 0;
  for (int i = 0; i < 3; ++i) {
    if (e[i] > 0) {
      level += (p[i] / e[i]) * (p[i] / e[i]);
    } else if (p[i] != 0) {
      level = std::numeric_limits<Real>::infinity();
    }
  }
  if (level <= 1) return 0;
  auto ratio = [&](int i, Real t) { return e[i] > 0 ? e[i] * p[i] / (t + e[i] * e[i]) : Real(0); };
  Real lo = 0, hi = 0;
  for (int i = 0; i < 3; ++i) hi = std::max(hi, std::abs(e[i] * p[i]));
  hi *= 2;
  auto F = [&](Real t) {
    Real sum = 0;
    for (int i = 0; i < 3; ++i) sum += ratio(i, t) * ratio(i, t);
    return sum - 1;
  };
  if (hi > 0) {
    while (F(hi) > 0) hi *= 2;
    for (int k = 0; k < 200; ++k) {
      const Real mid = (lo + hi) / 2;
      (F(mid) > 0 ? lo : hi) = mid;
    }
  }
  const Real t = (lo + hi) / 2;
  V3 q = V3::Zero();
  for (int i = 0; i < 3; ++i) q[i] = e[i] * ratio(i, t);
  return (p - q).norm();
}

/// Distance from p (shape frame) to the shape (0 inside).
inline Real pointDistance(const Shape& s, const V3& p) {
  switch (s.kind) {
    case Kind::sphere: return std::max<Real>(0, p.norm() - s.dims.x());
    case Kind::box: {
      V3 excess;
      for (int i = 0; i < 3; ++i) excess[i] = std::max<Real>(0, std::abs(p[i]) - s.dims[i]);
      return excess.norm();
    }
    case Kind::capsule: {
      const Real z = std::clamp(p.z(), -s.dims.y(), s.dims.y());
      return std::max<Real>(0, (p - V3(0, 0, z)).norm() - s.dims.x());
    }
    case Kind::cylinder: {
      const Real radial = std::max<Real>(0, std::hypot(p.x(), p.y()) - s.dims.x());
      const Real axial = std::max<Real>(0, std::abs(p.z()) - s.dims.y());
      return std::hypot(radial, axial);
    }
    case Kind::cone:
      return pointToMeridianTriangle(std::hypot(p.x(), p.y()), p.z(), s.dims.x(), s.dims.y());
    case Kind::ellipsoid: return pointToEllipsoid(p, s.dims);
    case Kind::convex: {
      // Outside iff outside some face plane; then the nearest face polygon (only
      // faces whose plane is nearer than the best so far can be nearer).
      thread_local std::vector<V3> polygon;
      Real best = std::numeric_limits<Real>::infinity();
      bool inside = true;
      for (const auto& face : s.faces) {
        const V3& a = s.vertices[face[0]];
        const V3 normal = (s.vertices[face[1]] - a).cross(s.vertices[face[2]] - a);
        if (normal.dot(p - a) > 0) inside = false;
      }
      if (inside) return 0;
      for (const auto& face : s.faces) {
        const V3& a = s.vertices[face[0]];
        const V3 normal = (s.vertices[face[1]] - a).cross(s.vertices[face[2]] - a).normalized();
        if (!(std::abs(normal.dot(p - a)) < best)) continue;
        polygon.clear();
        for (int index : face) polygon.push_back(s.vertices[index]);
        best = std::min(best, pointToPolygon(p, polygon));
      }
      return best;
    }
    case Kind::halfspace: return std::max<Real>(0, s.n.dot(p) - s.d);
    case Kind::plane: return std::abs(s.n.dot(p) - s.d);
    case Kind::triangle: return pointToPolygon(p, s.vertices);
  }
  return 0;
}

/// A point of the shape maximising w.y (shape frame), or, for the halfspace,
/// the point of its boundary plane under `near` when w points out of it (the
/// support is unbounded otherwise; callers only ask for w = -n... see
/// alignedPair).
inline V3 supportPoint(const Shape& s, const V3& w) {
  switch (s.kind) {
    case Kind::sphere: return s.dims.x() * w.normalized();
    case Kind::box:
      return V3(w.x() >= 0 ? s.dims.x() : -s.dims.x(), w.y() >= 0 ? s.dims.y() : -s.dims.y(),
                w.z() >= 0 ? s.dims.z() : -s.dims.z());
    case Kind::capsule:
      return V3(0, 0, w.z() >= 0 ? s.dims.y() : -s.dims.y()) + s.dims.x() * w.normalized();
    case Kind::cylinder: {
      const Real planar = std::hypot(w.x(), w.y());
      const V3 rim = planar > 0 ? V3(s.dims.x() * w.x() / planar, s.dims.x() * w.y() / planar, 0)
                                : V3(s.dims.x(), 0, 0);
      return rim + V3(0, 0, w.z() >= 0 ? s.dims.y() : -s.dims.y());
    }
    case Kind::cone: {
      const Real planar = std::hypot(w.x(), w.y());
      const V3 rim = planar > 0 ? V3(s.dims.x() * w.x() / planar, s.dims.x() * w.y() / planar,
                                     -s.dims.y())
                                : V3(s.dims.x(), 0, -s.dims.y());
      const V3 apex(0, 0, s.dims.y());
      return w.dot(rim) > w.dot(apex) ? rim : apex;
    }
    case Kind::ellipsoid: {
      const V3 scaled = s.dims.cwiseProduct(w);
      return s.dims.cwiseProduct(scaled) / scaled.norm();
    }
    case Kind::convex:
    case Kind::triangle: {
      V3 best = s.vertices[0];
      for (const V3& v : s.vertices) {
        if (w.dot(v) > w.dot(best)) best = v;
      }
      return best;
    }
    case Kind::halfspace:
    case Kind::plane: return s.d * s.n;  // a point of the boundary (callers: w = +-n)
  }
  return V3::Zero();
}

/// A disk: centre c, orthonormal in-plane axes u, v, radius r (world frame).
struct Disk {
  V3 c, u, v;
  Real r;
  V3 normal() const { return u.cross(v); }
  V3 point(Real a, Real b) const { return c + a * u + b * v; }
  /// A point of the disk maximising w.k.
  V3 supportPoint(const V3& w) const {
    const Real a = u.dot(w), b = v.dot(w);
    const Real length = std::hypot(a, b);
    if (!(length > 0)) return c;
    return c + (r / length) * (a * u + b * v);
  }
};

/// A shape's pose: rotation R, translation t (world = R y + t).
struct Pose {
  M3 R{M3::Identity()};
  V3 t{V3::Zero()};
  V3 toWorld(const V3& y) const { return R * y + t; }
  V3 toShape(const V3& x) const { return R.transpose() * (x - t); }
};

inline Real pointDistanceWorld(const Shape& s, const Pose& X, const V3& p) {
  return pointDistance(s, X.toShape(p));
}

/// The distance from a world point to the disk (closed form).
inline Real pointToDisk(const Disk& disk, const V3& p) {
  const V3 rel = p - disk.c;
  const Real a = disk.u.dot(rel), b = disk.v.dot(rel);
  const Real in_plane = std::hypot(a, b);
  const Real height = disk.normal().dot(rel);
  return std::hypot(std::max<Real>(0, in_plane - disk.r), height);
}

/// Translation making the pair's distance exactly `gap` (>= 0) along the unit
/// direction w (from the disk to the shape): the shape's support point along
/// -w lands at the disk's support point along w plus gap * w. For the
/// halfspace and the plane, w must be -n_world (resp. +-n_world).
inline Pose alignedPair(const Disk& disk, const Shape& s, const M3& R_shape, const V3& w, Real gap) {
  Pose X;
  X.R = R_shape;
  const V3 w_S = R_shape.transpose() * w;
  const V3 low_S = supportPoint(s, -w_S);  // the shape's point lowest along w
  X.t = disk.supportPoint(w) + gap * w - R_shape * low_S;
  return X;
}

constexpr int kGoldenSteps = 100;

/// Golden-section minimum of a convex f over [lo, hi]: the smallest value seen.
template <typename F>
Real goldenMinimum(F f, Real lo, Real hi, Real* argmin = nullptr) {
  const Real ratio = (std::sqrt(Real(5)) - 1) / 2;
  Real x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
  Real f1 = f(x1), f2 = f(x2);
  Real best = std::min(f1, f2), best_x = f1 < f2 ? x1 : x2;
  for (int k = 0; k < kGoldenSteps && hi - lo > 0; ++k) {
    if (f1 <= f2) {
      hi = x2, x2 = x1, f2 = f1;
      x1 = hi - ratio * (hi - lo);
      f1 = f(x1);
      if (f1 < best) best = f1, best_x = x1;
    } else {
      lo = x1, x1 = x2, f1 = f2;
      x2 = lo + ratio * (hi - lo);
      f2 = f(x2);
      if (f2 < best) best = f2, best_x = x2;
    }
  }
  if (argmin) *argmin = best_x;
  return best;
}

/// The disk-shape distance by nested golden-section search (see the top).
inline Real referenceDistance(const Disk& disk, const Shape& s, const Pose& X) {
  auto inner = [&](Real a) {
    const Real half = std::sqrt(std::max<Real>(0, disk.r * disk.r - a * a));
    return goldenMinimum(
        [&](Real b) { return pointDistanceWorld(s, X, disk.point(a, b)); }, -half, half);
  };
  return goldenMinimum(inner, -disk.r, disk.r);
}

}  // namespace oracle
}  // namespace fcl_disk_test
