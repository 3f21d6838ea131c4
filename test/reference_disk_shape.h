// An independent, high-precision reference for the distance between a disk and an
// FCL primitive, for tests. Header-only; depends on Eigen and the standard library
// only (no fcl, no fcl_disk header), so a bug in the production solver cannot leak
// into the values it is judged against.
//
// Notation: the disk has centre c, orthonormal frame (u, v, n) (n the unit normal)
// and radius r; it is the closed set {c + a u + b v : a^2 + b^2 <= r^2}. A shape X
// is given in its own frame S (FCL's conventions, listed at each struct below) and
// posed by a rotation R and a translation t: X_W = R X_S + t.
//
// METHOD (primal and brute-force-flavoured on purpose; the production solver runs
// Newton on a projection, this does not):
//   (i)   Nested golden-section search in Cartesian disk coordinates. With
//         f(a, b) = dist(c + a u + b v, X), f is jointly convex (the distance to
//         a convex set is convex, composed with an affine map), so its partial
//         minimum g(a) = min_b f(a, b) over the chord
//         b in [-sqrt(r^2 - a^2), +sqrt(r^2 - a^2)] is convex on [-r, r]. An
//         outer golden-section search over a, each step an inner golden-section
//         search over b, both run kGoldenSteps steps (the bracket shrinks by
//         0.618^kGoldenSteps = 1e-19, long double resolution) and keep the best
//         evaluated point, chord ends included. The point-to-shape distance
//         dist(x, X) is evaluated in the shape's frame, in long double:
//           sphere, box, capsule, cylinder, halfspace, plane: closed forms;
//           triangle: the projection onto its plane if it falls inside (edge
//             tests), else the nearest of the three edges (Ericson's regions);
//           cone: a solid of revolution, so the nearest point lies in the
//             meridian half-plane of x: the 2-D distance from (rho, z) to the
//             triangle (0, -h), (R, -h), (0, h);
//           ellipsoid: Eberly's method: the nearest point of an outside x is
//             y_i = a_i^2 x_i / (t + a_i^2) with t >= 0 the root of
//             F(t) = sum (a_i x_i / (t + a_i^2))^2 - 1, convex and decreasing;
//             Newton from a lower bound of the root (monotone, never
//             overshoots), bisection whenever a step leaves the bracket; x - y
//             is formed as x_i t / (t + a_i^2), so nothing cancels near the
//             surface;
//           convex: 0 if x is inside every face plane, else the minimum, over
//             the faces whose plane x lies outside of, of the point-to-polygon
//             distance (the nearest boundary point lies on such a face).
//   (ii)  Candidates: every candidate is a real pair (p on the disk, q on X), so
//         each is an upper bound and the smallest wins: the disk's closest point
//         to every vertex (polytopes, triangle, cone apex); golden section along
//         every edge of the point-to-disk distance (convex along a segment);
//         closed forms for the sphere (disk to centre minus rho), the capsule
//         (golden section along its axis, minus rho), the halfspace and the plane
//         (the disk's extreme points along the normal).
//   Why this is the distance: f is convex and continuous on the compact disk, so
//   (i) converges to min f; (ii) makes exact answers exact where f is flat or
//   kinked.
//
// SELF-CERTIFICATE: both sets are convex, so for ANY unit w (pointing disk ->
//   shape) d >= min_{y in X} w.y - (w.c + r sqrt((u.w)^2 + (v.w)^2)), with each
//   shape's support function written out independently below. It is evaluated
//   at w0 = (q - p)/|q - p|; at w0 with the components along the disk's rim
//   tangent at p and along the shape's edge directions removed, and at
//   edge x rim tangent (the optimal direction of rim-vertex and rim-edge
//   contacts, where a polytope's support is kinked and w0, located only to
//   sqrt(eps) along the rim, would lose first-order accuracy); at +-n; at +- each
//   face normal of the shape. For the halfspace and the plane the only finite
//   bound (w along the normal) is closed form. The best bound (or 0) is
//   lower_bound. It only CHECKS the primal answer: the search does not use it.
//
// ACCURACY: all arithmetic in long double (x87 80-bit, eps = 1.08e-19) in the
// shape's frame, so far-from-origin poses cost nothing beyond the exactness of
// c - t. The rotation of the shape is projected onto the rotations (polar
// factor) and the disk's frame re-orthonormalised (n first), so "the" shape of a
// float pose is defined to ~1e-7 of its size, of a double pose to ~1e-16.
// Validated on every family of disk_shape_families.h (seeds 12345 and the
// test's, 40-200 cases per family and shape) against the distances fixed by
// construction, an independent membership test of both points (implicit
// inequalities, not the distance functions), and brute force (the point-to-shape
// distance on a 120-ring polar grid of the disk, ~29000 points):
//   - constructions: error within the rounding of the poses to double
//     (<= 4e-14 * scale, where the frame origin is far from the contact, and
//     <= 6e-15 * scale otherwise); closed forms (test_disk_shape_accuracy,
//     ReferenceSelfCheck) to <= 1e-18 * scale;
//   - both points on their sets and | |p - q| - distance | to <= 1e-18 * scale
//     (a few ulps of the world coordinates far from the origin);
//   - never above brute force;
//   - certificate gap (distance - lower_bound) <= 1e-16 * scale, except where
//     the distance itself is at rounding level (then gap <= distance) and for
//     curved contacts (ellipsoid, cylinder and cone rims) at distances below
//     ~1e-6 * scale, where w0 is known only to sqrt(eps) * scale / d: there it
//     stays below ~1e-10 * scale, an error bar, not an error of the distance.
// So the distance is good to ~1e-17 * scale, five orders below the 1e-12 the
// production solver is held to.
//
// scale = r + R_S + |c - c_S|, with R_S the shape's bounding radius about its
// frame origin c_S (halfspace, plane: R_S = 0 and c_S the foot of c on the plane).
//
// Cost: ~8.5e3 point-to-shape distances per query: 0.5 ms for the closed-form
// shapes, 1.5 ms for the triangle, 2-4 ms for the convex and the ellipsoid (x87).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace fcl_disk_test {
namespace ref {

using Real = long double;
using V3 = Eigen::Matrix<Real, 3, 1>;
using M3 = Eigen::Matrix<Real, 3, 3>;

/// Golden-section steps of every search: 0.618^kGoldenSteps = 1.0e-19, the
/// relative resolution of long double, so a kinked minimum (a chord end, a
/// polytope edge) is located to the last bits and a smooth one to sqrt(eps).
constexpr int kGoldenSteps = 91;

// ---------------------------------------------------------------- the shapes

/// A disk: centre c, orthonormal frame (u, v in-plane, n normal), radius r.
struct Disk {
  V3 c{V3::Zero()};
  V3 u{V3::UnitX()};
  V3 v{V3::UnitY()};
  V3 n{V3::UnitZ()};
  Real r{1};
};

/// The disk of radius r whose frame is R (columns u, v, n) at t (fcl_disk's
/// convention: centred at its frame origin, in the XY plane). R is
/// re-orthonormalised: n first, then u, v = n x u.
inline Disk makeDisk(Real r, const M3& R, const V3& t) {
  Disk d;
  d.c = t;
  d.n = R.col(2).normalized();
  d.u = (R.col(0) - d.n.dot(R.col(0)) * d.n).normalized();
  d.v = d.n.cross(d.u);
  d.r = r;
  return d;
}

// Every shape holds its pose (R, t): the shape in the world is R X_S + t.

/// Ball of radius `radius` centred at the frame origin.
struct Sphere {
  M3 R{M3::Identity()};
  V3 t{V3::Zero()};
  Real radius{1};
};
/// Solid box centred at the origin, |x_i| <= side_i / 2.
struct Box {
  M3 R{M3::Identity()};
  V3 t{V3::Zero()};
  V3 side{V3::Ones()};
};
/// Segment (0, 0, -lz/2)-(0, 0, lz/2) inflated by `radius`.
struct Capsule {
  M3 R{M3::Identity()};
  V3 t{V3::Zero()};
  Real radius{1};
  Real lz{1};
};
/// Solid cylinder x^2 + y^2 <= radius^2, |z| <= lz/2.
struct Cylinder {
  M3 R{M3::Identity()};
  V3 t{V3::Zero()};
  Real radius{1};
  Real lz{1};
};
/// Solid cone: base disk of `radius` at z = -lz/2, apex at (0, 0, +lz/2).
struct Cone {
  M3 R{M3::Identity()};
  V3 t{V3::Zero()};
  Real radius{1};
  Real lz{1};
};
/// x^2/a^2 + y^2/b^2 + z^2/c^2 <= 1, radii = (a, b, c).
struct Ellipsoid {
  M3 R{M3::Identity()};
  V3 t{V3::Zero()};
  V3 radii{V3::Ones()};
};
/// Solid convex hull of `vertices`; `faces` lists each face's vertex indices,
/// counter-clockwise seen from outside (FCL's convention; the reference orients
/// the face planes itself, away from the vertex centroid).
struct Convex {
  M3 R{M3::Identity()};
  V3 t{V3::Zero()};
  std::vector<V3> vertices;
  std::vector<std::vector<int>> faces;
};
/// {x : n.x <= d} (n is normalised here, as FCL does).
struct Halfspace {
  M3 R{M3::Identity()};
  V3 t{V3::Zero()};
  V3 n{V3::UnitZ()};
  Real d{0};
};
/// {x : n.x = d}, a two-sided surface.
struct Plane {
  M3 R{M3::Identity()};
  V3 t{V3::Zero()};
  V3 n{V3::UnitZ()};
  Real d{0};
};
/// The closed flat triangle a, b, c.
struct TriangleP {
  M3 R{M3::Identity()};
  V3 t{V3::Zero()};
  V3 a{V3::Zero()};
  V3 b{V3::UnitX()};
  V3 c{V3::UnitY()};
};

/// The reference answer; points in the world frame.
struct Result {
  Real distance{0};        ///< the distance (an upper bound up to rounding).
  V3 p_disk{V3::Zero()};   ///< nearest point on the disk.
  V3 p_shape{V3::Zero()};  ///< nearest point on the shape.
  Real lower_bound{0};     ///< certificate: lower_bound <= true distance (up to rounding).
  Real scale{1};           ///< r + R_S + |c - c_S|.
  std::string method;      ///< which candidate won (informational).

  Real certifiedGap() const { return distance - lower_bound; }
};

namespace detail {

inline Real norm2(Real a, Real b) { return std::sqrt(a * a + b * b); }
constexpr Real kInf = std::numeric_limits<Real>::infinity();
constexpr Real kInvPhi = 0.6180339887498948482045868343656381177L;

/// The nearest orthonormal matrix (polar factor) by Newton's iteration
/// R <- (R + R^-T) / 2, quadratically convergent from a rotation that is
/// orthonormal to rounding (a float rotation's 1e-7 takes three steps).
inline M3 orthonormalise(M3 R) {
  for (int i = 0; i < 8; ++i) {
    const M3 next = (R + R.inverse().transpose()) / 2;
    if ((next - R).cwiseAbs().maxCoeff() == 0) break;
    R = next;
  }
  return R;
}

/// Minimum of a function on [lo, hi] that is convex up to rounding: golden
/// section for kGoldenSteps steps; returns the best value met (ends included)
/// and its argument.
template <typename F>
Real goldenMinimum(Real lo, Real hi, const F& f, Real* argmin) {
  Real best_x = lo, best = f(lo);
  {
    const Real f_hi = f(hi);
    if (f_hi < best) {
      best = f_hi;
      best_x = hi;
    }
  }
  if (!(hi > lo)) {
    *argmin = best_x;
    return best;
  }
  Real x1 = hi - kInvPhi * (hi - lo), x2 = lo + kInvPhi * (hi - lo);
  Real f1 = f(x1), f2 = f(x2);
  for (int step = 0; step < kGoldenSteps; ++step) {
    if (f1 <= f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - kInvPhi * (hi - lo);
      f1 = f(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + kInvPhi * (hi - lo);
      f2 = f(x2);
    }
    if (f1 < best) {
      best = f1;
      best_x = x1;
    }
    if (f2 < best) {
      best = f2;
      best_x = x2;
    }
  }
  *argmin = best_x;
  return best;
}

/// Distance from x to the segment [a, b] and the nearest point.
inline Real pointSegment(const V3& x, const V3& a, const V3& b, V3* nearest) {
  const V3 ab = b - a;
  const Real len2 = ab.squaredNorm();
  Real s = len2 > 0 ? (x - a).dot(ab) / len2 : 0;
  s = std::min<Real>(1, std::max<Real>(0, s));
  *nearest = a + s * ab;
  return (x - *nearest).norm();
}

/// The disk in the shape's frame.
struct LocalDisk {
  V3 c, u, v, n;
  Real r;
  V3 at(Real a, Real b) const { return c + a * u + b * v; }
  /// Closest point of the disk to y (closed form) and its distance.
  Real closest(const V3& y, V3* p) const {
    const V3 rel = y - c;
    const Real a = u.dot(rel), b = v.dot(rel), h = n.dot(rel);
    const Real rho = norm2(a, b);
    if (rho <= r) {
      *p = c + a * u + b * v;
      return std::fabs(h);
    }
    const Real k = r / rho;
    *p = c + (k * a) * u + (k * b) * v;
    return norm2(h, rho - r);
  }
  /// max over the disk of w.x.
  Real support(const V3& w) const { return w.dot(c) + r * norm2(u.dot(w), v.dot(w)); }
};

// --------------------------------------------------- per-shape local models
// Each model works in the shape's frame: distance(x, &y) = dist(x, X_S) with y
// the nearest point; support(w) = max_{y in X_S} w.y (+inf if unbounded);
// vertices(), edges(), normals(), edgeDirections(q) feed the candidates and the
// certificate; closedForm() may add an exact candidate; extraLowerBound() a
// closed-form bound.

struct ModelBase {
  std::vector<V3> vertices() const { return {}; }
  std::vector<std::pair<V3, V3>> edges() const { return {}; }
  std::vector<V3> normals() const { return {}; }
  std::vector<V3> edgeDirections(const V3&) const { return {}; }
  bool closedForm(const LocalDisk&, V3*, V3*, Real*) const { return false; }
  Real extraLowerBound(const LocalDisk&) const { return -kInf; }
};

/// Unit directions of a list of edges (for the certificate).
inline std::vector<V3> directionsOf(const std::vector<std::pair<V3, V3>>& edges) {
  std::vector<V3> out;
  for (const auto& e : edges) {
    const V3 d = e.second - e.first;
    if (d.norm() > 0) out.push_back(d / d.norm());
  }
  return out;
}

/// The tangent of the circle about the z axis through q (a rim's edge
/// direction), if q is off the axis.
inline std::vector<V3> circleTangent(const V3& q) {
  const Real rho = norm2(q.x(), q.y());
  if (!(rho > 0)) return {};
  return {V3(-q.y() / rho, q.x() / rho, 0)};
}

struct SphereModel : ModelBase {
  Real rho;
  explicit SphereModel(const Sphere& s) : rho(s.radius) {}
  Real boundingRadius() const { return rho; }
  Real distance(const V3& x, V3* y) const {
    const Real len = x.norm();
    if (len <= rho) {
      *y = x;
      return 0;
    }
    *y = x * (rho / len);
    return len - rho;
  }
  Real support(const V3& w) const { return rho * w.norm(); }
  bool closedForm(const LocalDisk& disk, V3* p, V3* q, Real* d) const {
    const Real to_centre = disk.closest(V3::Zero(), p);
    if (to_centre <= rho) {
      *q = *p;
      *d = 0;
      return true;
    }
    *q = *p * (rho / p->norm());
    *d = to_centre - rho;
    return true;
  }
};

struct BoxModel : ModelBase {
  V3 h;
  explicit BoxModel(const Box& b) : h(b.side / 2) {}
  Real boundingRadius() const { return h.norm(); }
  Real distance(const V3& x, V3* y) const {
    Real s = 0;
    for (int i = 0; i < 3; ++i) {
      const Real yi = std::min(h[i], std::max(-h[i], x[i]));
      (*y)[i] = yi;
      s += (x[i] - yi) * (x[i] - yi);
    }
    return std::sqrt(s);
  }
  Real support(const V3& w) const { return w.cwiseAbs().dot(h); }
  std::vector<V3> vertices() const {
    std::vector<V3> out;
    for (int k = 0; k < 8; ++k)
      out.push_back(V3((k & 1) ? h[0] : -h[0], (k & 2) ? h[1] : -h[1], (k & 4) ? h[2] : -h[2]));
    return out;
  }
  std::vector<std::pair<V3, V3>> edges() const {
    const std::vector<V3> v = vertices();
    std::vector<std::pair<V3, V3>> out;
    for (int k = 0; k < 8; ++k)
      for (int bit = 1; bit < 8; bit <<= 1)
        if (!(k & bit)) out.push_back({v[k], v[k | bit]});
    return out;
  }
  std::vector<V3> normals() const { return {V3::UnitX(), V3::UnitY(), V3::UnitZ()}; }
  std::vector<V3> edgeDirections(const V3&) const { return normals(); }
};

struct CapsuleModel : ModelBase {
  Real rho, h;
  explicit CapsuleModel(const Capsule& c) : rho(c.radius), h(c.lz / 2) {}
  Real boundingRadius() const { return rho + h; }
  Real distance(const V3& x, V3* y) const {
    const V3 axis(0, 0, std::min(h, std::max(-h, x.z())));
    const V3 rel = x - axis;
    const Real len = rel.norm();
    if (len <= rho) {
      *y = x;
      return 0;
    }
    *y = axis + rel * (rho / len);
    return len - rho;
  }
  Real support(const V3& w) const { return h * std::fabs(w.z()) + rho * w.norm(); }
  std::vector<V3> normals() const { return {V3::UnitZ()}; }
  std::vector<V3> edgeDirections(const V3&) const { return {V3::UnitZ()}; }
  /// dist(axis segment, disk) - rho, by golden section of the point-to-disk
  /// distance along the axis (convex).
  bool closedForm(const LocalDisk& disk, V3* p, V3* q, Real* d) const {
    V3 scratch;
    Real s;
    goldenMinimum(-h, h, [&](Real z) { return disk.closest(V3(0, 0, z), &scratch); }, &s);
    const V3 axis(0, 0, s);
    const Real to_axis = disk.closest(axis, p);
    if (to_axis <= rho) {
      *q = *p;
      *d = 0;
      return true;
    }
    *q = axis + (*p - axis) * (rho / (*p - axis).norm());
    *d = to_axis - rho;
    return true;
  }
};

struct CylinderModel : ModelBase {
  Real R, h;
  explicit CylinderModel(const Cylinder& c) : R(c.radius), h(c.lz / 2) {}
  Real boundingRadius() const { return norm2(R, h); }
  Real distance(const V3& x, V3* y) const {
    const Real rho = norm2(x.x(), x.y());
    const Real dr = rho - R, dz = std::fabs(x.z()) - h;
    const Real k = rho > R ? R / rho : 1;
    *y = V3(k * x.x(), k * x.y(), std::min(h, std::max(-h, x.z())));
    return norm2(std::max<Real>(dr, 0), std::max<Real>(dz, 0));
  }
  Real support(const V3& w) const { return R * norm2(w.x(), w.y()) + h * std::fabs(w.z()); }
  std::vector<V3> normals() const { return {V3::UnitZ()}; }
  std::vector<V3> edgeDirections(const V3& q) const {
    std::vector<V3> out = circleTangent(q);
    out.push_back(V3::UnitZ());
    return out;
  }
};

struct ConeModel : ModelBase {
  Real R, h;
  explicit ConeModel(const Cone& c) : R(c.radius), h(c.lz / 2) {}
  Real boundingRadius() const { return norm2(R, h); }
  /// 2-D distance from (rho, z) to the segment (r0, z0)-(r1, z1).
  static Real seg2(Real rho, Real z, Real r0, Real z0, Real r1, Real z1, Real* rn, Real* zn) {
    const Real dr = r1 - r0, dz = z1 - z0;
    const Real len2 = dr * dr + dz * dz;
    Real s = len2 > 0 ? ((rho - r0) * dr + (z - z0) * dz) / len2 : 0;
    s = std::min<Real>(1, std::max<Real>(0, s));
    *rn = r0 + s * dr;
    *zn = z0 + s * dz;
    return norm2(rho - *rn, z - *zn);
  }
  Real distance(const V3& x, V3* y) const {
    const Real rho = norm2(x.x(), x.y()), z = x.z();
    // Inside: above the base, below the lateral line 2 h rho + R z <= R h.
    if (z >= -h && 2 * h * rho + R * z <= R * h) {
      *y = x;
      return 0;
    }
    Real rb, zb, rl, zl;
    const Real d_base = seg2(rho, z, 0, -h, R, -h, &rb, &zb);
    const Real d_lat = seg2(rho, z, R, -h, 0, h, &rl, &zl);
    const bool base = d_base <= d_lat;
    const Real rn = base ? rb : rl, zn = base ? zb : zl;
    if (rho > 0) {
      *y = V3(x.x() * (rn / rho), x.y() * (rn / rho), zn);
    } else {
      *y = V3(rn, 0, zn);
    }
    return base ? d_base : d_lat;
  }
  Real support(const V3& w) const {
    return std::max(h * w.z(), -h * w.z() + R * norm2(w.x(), w.y()));
  }
  std::vector<V3> vertices() const { return {V3(0, 0, h)}; }
  std::vector<V3> normals() const { return {V3::UnitZ()}; }
  std::vector<V3> edgeDirections(const V3& q) const { return circleTangent(q); }
};

struct EllipsoidModel : ModelBase {
  V3 a;
  explicit EllipsoidModel(const Ellipsoid& e) : a(e.radii) {}
  Real boundingRadius() const { return a.maxCoeff(); }
  Real distance(const V3& x, V3* y) const {
    Real level = 0;
    for (int i = 0; i < 3; ++i) level += (x[i] / a[i]) * (x[i] / a[i]);
    if (level <= 1) {
      *y = x;
      return 0;
    }
    // F(t) = sum (a_i x_i / (t + a_i^2))^2 - 1 is convex and decreasing on t >= 0
    // with F(0) > 0. Each single term bounds the root from below,
    // t* >= a_i |x_i| - a_i^2, and F(|A x|) <= 0 bounds it from above.
    Real lo = 0, hi = 0;
    for (int i = 0; i < 3; ++i) {
      lo = std::max(lo, a[i] * std::fabs(x[i]) - a[i] * a[i]);
      hi += (a[i] * x[i]) * (a[i] * x[i]);
    }
    hi = std::max(std::sqrt(hi), lo);
    Real t = lo;
    for (int it = 0; it < 400; ++it) {
      Real f = -1, df = 0;
      for (int i = 0; i < 3; ++i) {
        const Real q = a[i] * x[i] / (t + a[i] * a[i]);
        f += q * q;
        df -= 2 * q * q / (t + a[i] * a[i]);
      }
      if (f == 0) break;
      if (f > 0) {
        lo = t;
      } else {
        hi = t;
      }
      Real next = (f > 0 && df < 0) ? t - f / df : (lo + hi) / 2;
      if (!(next > lo && next < hi)) next = lo + (hi - lo) / 2;
      if (!(next > lo && next < hi)) break;  // the bracket is down to adjacent numbers
      t = next;
    }
    Real s = 0;
    for (int i = 0; i < 3; ++i) {
      const Real diff = x[i] * t / (t + a[i] * a[i]);
      (*y)[i] = x[i] - diff;
      s += diff * diff;
    }
    return std::sqrt(s);
  }
  Real support(const V3& w) const { return w.cwiseProduct(a).norm(); }
  std::vector<V3> normals() const { return {V3::UnitX(), V3::UnitY(), V3::UnitZ()}; }
};

/// A planar convex polygon: vertices in counter-clockwise order about the unit
/// normal m; m.x = off on its plane.
struct Polygon {
  std::vector<V3> v;
  V3 m;
  Real off;
  /// Distance from x to the polygon, given x's signed plane distance: the plane
  /// distance if the projection falls inside, else the nearest edge.
  Real distance(const V3& x, Real plane_distance, V3* y) const {
    const V3 proj = x - plane_distance * m;
    bool inside = v.size() >= 3;
    const size_t k = v.size();
    for (size_t i = 0; i < k && inside; ++i) {
      const V3& a = v[i];
      const V3& b = v[(i + 1) % k];
      if (m.dot((b - a).cross(proj - a)) < 0) inside = false;
    }
    if (inside) {
      *y = proj;
      return std::fabs(plane_distance);
    }
    Real best = kInf;
    for (size_t i = 0; i < k; ++i) {
      V3 near = V3::Zero();
      const Real d = pointSegment(x, v[i], v[(i + 1) % k], &near);
      if (d < best) {
        best = d;
        *y = near;
      }
    }
    return best;
  }
};

/// Newell's normal of a polygon (robust for any planar face); zero if degenerate.
inline V3 newellNormal(const std::vector<V3>& v) {
  V3 m = V3::Zero();
  for (size_t i = 0; i < v.size(); ++i) {
    const V3& a = v[i];
    const V3& b = v[(i + 1) % v.size()];
    m.x() += (a.y() - b.y()) * (a.z() + b.z());
    m.y() += (a.z() - b.z()) * (a.x() + b.x());
    m.z() += (a.x() - b.x()) * (a.y() + b.y());
  }
  return m;
}

struct ConvexModel : ModelBase {
  std::vector<V3> verts;
  std::vector<Polygon> faces;
  std::vector<std::pair<V3, V3>> edge_list;
  std::vector<V3> edge_dirs;
  explicit ConvexModel(const Convex& cv) : verts(cv.vertices) {
    V3 centroid = V3::Zero();
    for (const V3& x : verts) centroid += x;
    centroid /= Real(verts.size());
    std::set<std::pair<int, int>> seen;
    for (const auto& f : cv.faces) {
      for (size_t i = 0; i < f.size(); ++i) {
        const int a = f[i], b = f[(i + 1) % f.size()];
        if (seen.insert({std::min(a, b), std::max(a, b)}).second)
          edge_list.push_back({verts[a], verts[b]});
      }
      Polygon p;
      for (int i : f) p.v.push_back(verts[i]);
      V3 m = newellNormal(p.v);
      if (!(m.norm() > 0)) continue;
      m.normalize();
      V3 mean = V3::Zero();
      for (const V3& x : p.v) mean += x;
      mean /= Real(p.v.size());
      if (m.dot(mean - centroid) < 0) {
        m = -m;
        std::reverse(p.v.begin(), p.v.end());
      }
      p.m = m;
      p.off = m.dot(mean);
      faces.push_back(p);
    }
    edge_dirs = directionsOf(edge_list);
  }
  Real boundingRadius() const {
    Real r = 0;
    for (const V3& x : verts) r = std::max(r, x.norm());
    return r;
  }
  Real distance(const V3& x, V3* y) const {
    Real best = kInf;
    if (faces.empty()) {  // a hull without area: its edges
      for (const auto& e : edge_list) {
        V3 near = V3::Zero();
        const Real d = pointSegment(x, e.first, e.second, &near);
        if (d < best) {
          best = d;
          *y = near;
        }
      }
      return best;
    }
    // The nearest boundary point of an outside x lies on a face whose plane x is
    // outside of, and a polygon distance is at least its plane distance.
    bool inside = true;
    for (const Polygon& f : faces) {
      const Real s = f.m.dot(x) - f.off;
      if (s <= 0) continue;
      inside = false;
      if (s >= best) continue;
      V3 near = V3::Zero();
      const Real d = f.distance(x, s, &near);
      if (d < best) {
        best = d;
        *y = near;
      }
    }
    if (inside) {
      *y = x;
      return 0;
    }
    return best;
  }
  Real support(const V3& w) const {
    Real s = -kInf;
    for (const V3& x : verts) s = std::max(s, w.dot(x));
    return s;
  }
  std::vector<V3> vertices() const { return verts; }
  std::vector<std::pair<V3, V3>> edges() const { return edge_list; }
  std::vector<V3> normals() const {
    std::vector<V3> out;
    for (const Polygon& f : faces) out.push_back(f.m);
    return out;
  }
  std::vector<V3> edgeDirections(const V3&) const { return edge_dirs; }
};

struct TriangleModel : ModelBase {
  Polygon tri;
  bool has_area;
  explicit TriangleModel(const TriangleP& t) {
    tri.v = {t.a, t.b, t.c};
    const V3 m = (t.b - t.a).cross(t.c - t.a);
    has_area = m.norm() > 0;
    tri.m = has_area ? V3(m.normalized()) : V3(V3::UnitZ());
    tri.off = tri.m.dot(t.a);
  }
  Real boundingRadius() const {
    return std::max({tri.v[0].norm(), tri.v[1].norm(), tri.v[2].norm()});
  }
  Real distance(const V3& x, V3* y) const {
    if (has_area) return tri.distance(x, tri.m.dot(x) - tri.off, y);
    Real best = kInf;
    for (int i = 0; i < 3; ++i) {
      V3 near = V3::Zero();
      const Real d = pointSegment(x, tri.v[i], tri.v[(i + 1) % 3], &near);
      if (d < best) {
        best = d;
        *y = near;
      }
    }
    return best;
  }
  Real support(const V3& w) const {
    return std::max({w.dot(tri.v[0]), w.dot(tri.v[1]), w.dot(tri.v[2])});
  }
  std::vector<V3> vertices() const { return tri.v; }
  std::vector<std::pair<V3, V3>> edges() const {
    return {{tri.v[0], tri.v[1]}, {tri.v[1], tri.v[2]}, {tri.v[2], tri.v[0]}};
  }
  std::vector<V3> normals() const { return {tri.m}; }
  std::vector<V3> edgeDirections(const V3&) const { return directionsOf(edges()); }
};

/// Halfspace {m.x <= off} (kTwoSided false) and Plane {m.x = off}, with m
/// normalised in long double.
template <bool kTwoSided>
struct FlatModel : ModelBase {
  V3 m;
  Real off;
  FlatModel(const V3& n, Real d) : m(n / n.norm()), off(d / n.norm()) {}
  Real boundingRadius() const { return 0; }
  Real distance(const V3& x, V3* y) const {
    const Real s = m.dot(x) - off;
    if (kTwoSided ? s == 0 : s <= 0) {
      *y = x;
      return 0;
    }
    *y = x - s * m;
    return std::fabs(s);
  }
  Real support(const V3&) const { return kInf; }
  std::vector<V3> normals() const { return {m}; }
  /// Signed heights over the plane of the disk's lowest and highest points.
  void extent(const LocalDisk& disk, Real* lo, Real* hi) const {
    const Real mid = m.dot(disk.c) - off;
    const Real half = disk.r * norm2(disk.u.dot(m), disk.v.dot(m));
    *lo = mid - half;
    *hi = mid + half;
  }
  bool closedForm(const LocalDisk& disk, V3* p, V3* q, Real* d) const {
    Real lo, hi;
    extent(disk, &lo, &hi);
    const Real a = disk.u.dot(m), b = disk.v.dot(m), len = norm2(a, b);
    // The disk's lowest and highest points along m (the centre if parallel).
    const V3 low = len > 0 ? disk.at(-disk.r * a / len, -disk.r * b / len) : disk.c;
    const V3 high = len > 0 ? disk.at(disk.r * a / len, disk.r * b / len) : disk.c;
    if (lo > 0) {
      *p = low;
      *d = lo;
      *q = *p - lo * m;
    } else if (kTwoSided && hi < 0) {
      *p = high;
      *d = -hi;
      *q = *p - hi * m;
    } else {
      // A common point: the lowest point (halfspace), or where the segment
      // low-high crosses the plane (plane).
      *p = (kTwoSided && hi > lo) ? V3(low + (-lo / (hi - lo)) * (high - low)) : low;
      *q = *p;
      *d = 0;
    }
    return true;
  }
  Real extraLowerBound(const LocalDisk& disk) const {
    Real lo, hi;
    extent(disk, &lo, &hi);
    return kTwoSided ? std::max(lo, -hi) : lo;
  }
};

inline SphereModel model(const Sphere& s) { return SphereModel(s); }
inline BoxModel model(const Box& s) { return BoxModel(s); }
inline CapsuleModel model(const Capsule& s) { return CapsuleModel(s); }
inline CylinderModel model(const Cylinder& s) { return CylinderModel(s); }
inline ConeModel model(const Cone& s) { return ConeModel(s); }
inline EllipsoidModel model(const Ellipsoid& s) { return EllipsoidModel(s); }
inline ConvexModel model(const Convex& s) { return ConvexModel(s); }
inline TriangleModel model(const TriangleP& s) { return TriangleModel(s); }
inline FlatModel<false> model(const Halfspace& s) { return FlatModel<false>(s.n, s.d); }
inline FlatModel<true> model(const Plane& s) { return FlatModel<true>(s.n, s.d); }

/// The shape's frame in long double, its rotation projected onto the rotations.
struct Frame {
  M3 R;
  V3 t;
};
template <typename Shape>
Frame shapeFrame(const Shape& s) {
  return {orthonormalise(s.R), s.t};
}

inline LocalDisk localDisk(const Disk& disk, const Frame& f) {
  LocalDisk d;
  const M3 RT = f.R.transpose();
  d.c = RT * (disk.c - f.t);
  d.u = RT * disk.u;
  d.v = RT * disk.v;
  d.n = RT * disk.n;
  d.r = disk.r;
  return d;
}

/// The certificate (see the top of the file), in the shape's frame: the best of
/// min_X w.y - max_D w.x over the candidate directions, and 0.
template <typename Model>
Real certificate(const Model& m, const LocalDisk& disk, const V3& p, const V3& q) {
  std::vector<V3> dirs = {disk.n, -disk.n};
  for (const V3& f : m.normals()) {
    dirs.push_back(f);
    dirs.push_back(-f);
  }
  const V3 w0 = q - p;
  if (w0.norm() > 0) {
    const auto add = [&](const V3& w) {
      if (w.norm() > 0) dirs.push_back(w / w.norm());
    };
    add(w0);
    // The rim tangent at p, if p is on the rim.
    const V3 rel = p - disk.c;
    const Real a = disk.u.dot(rel), b = disk.v.dot(rel), rho = norm2(a, b);
    const bool on_rim = rho > 0 && rho >= disk.r * (1 - 1e-9L);
    const V3 tangent = on_rim ? V3((-b * disk.u + a * disk.v) / rho) : V3(V3::Zero());
    if (on_rim) add(w0 - w0.dot(tangent) * tangent);
    for (const V3& e : m.edgeDirections(q)) {
      add(w0 - w0.dot(e) * e);
      if (on_rim) {
        const V3 x = e.cross(tangent);
        add(x.dot(w0) >= 0 ? x : V3(-x));
      }
    }
  }
  Real best = std::max<Real>(0, m.extraLowerBound(disk));
  for (const V3& w : dirs) {
    const Real s = m.support(-w);
    if (!(s < kInf)) continue;
    best = std::max(best, -s - disk.support(w));
  }
  return best;
}

}  // namespace detail

/// Bounding radius R_S of the shape about its frame origin (0 for the halfspace
/// and the plane).
template <typename Shape>
Real boundingRadius(const Shape& s) {
  return detail::model(s).boundingRadius();
}

/// scale = r + R_S + |c - c_S| (c_S: the shape's frame origin; for the halfspace
/// and the plane the foot of c on the boundary plane, with R_S = 0).
template <typename Shape>
Real scaleOf(const Disk& disk, const Shape& s) {
  return disk.r + boundingRadius(s) + (disk.c - s.t).norm();
}
inline Real flatScale(const Disk& disk, const M3& R, const V3& t, const V3& n, Real d) {
  const V3 nw = detail::orthonormalise(R) * n / n.norm();
  const Real dw = d / n.norm() + nw.dot(t);
  return disk.r + std::fabs(nw.dot(disk.c) - dw);
}
inline Real scaleOf(const Disk& disk, const Halfspace& s) { return flatScale(disk, s.R, s.t, s.n, s.d); }
inline Real scaleOf(const Disk& disk, const Plane& s) { return flatScale(disk, s.R, s.t, s.n, s.d); }

/// Distance from a world point to the shape (long double), for checking that
/// reported points lie on their shapes.
template <typename Shape>
Real distanceToShape(const V3& x, const Shape& s) {
  const detail::Frame f = detail::shapeFrame(s);
  V3 y;
  return detail::model(s).distance(f.R.transpose() * (x - f.t), &y);
}

/// Distance from a world point to the disk (closed form).
inline Real distanceToDisk(const V3& x, const Disk& disk) {
  const detail::LocalDisk d{disk.c, disk.u, disk.v, disk.n, disk.r};
  V3 p;
  return d.closest(x, &p);
}

/// The reference distance between `disk` and `shape` (method: top of the file).
template <typename Shape>
Result referenceDistance(const Disk& disk, const Shape& shape) {
  using namespace detail;
  const auto m = model(shape);
  const Frame frame = shapeFrame(shape);
  const LocalDisk d = localDisk(disk, frame);

  Real best = kInf;
  V3 best_p = d.c, best_q = d.c;
  std::string method;
  const auto consider = [&](Real dist, const V3& p, const V3& q, const char* name) {
    if (dist < best) {
      best = dist;
      best_p = p;
      best_q = q;
      method = name;
    }
  };

  // (i) nested golden section over the disk.
  {
    V3 y;
    const auto inner = [&](Real a, Real* b_arg) {
      const Real half = std::sqrt(std::max<Real>(0, d.r * d.r - a * a));
      return goldenMinimum(-half, half, [&](Real b) { return m.distance(d.at(a, b), &y); }, b_arg);
    };
    Real a_arg, b_arg, b_scratch;
    goldenMinimum(-d.r, d.r, [&](Real a) { return inner(a, &b_scratch); }, &a_arg);
    inner(a_arg, &b_arg);
    const V3 p = d.at(a_arg, b_arg);
    V3 q = V3::Zero();
    const Real dist = m.distance(p, &q);
    consider(dist, p, q, "golden");
  }
  // (ii) candidates.
  for (const V3& vertex : m.vertices()) {
    V3 p;
    const Real dist = d.closest(vertex, &p);
    consider(dist, p, vertex, "vertex");
  }
  for (const auto& e : m.edges()) {
    V3 p;
    Real s;
    goldenMinimum(0, 1, [&](Real s_) { return d.closest(e.first + s_ * (e.second - e.first), &p); }, &s);
    const V3 q = e.first + s * (e.second - e.first);
    const Real dist = d.closest(q, &p);
    consider(dist, p, q, "edge");
  }
  {
    V3 p, q;
    Real dist;
    if (m.closedForm(d, &p, &q, &dist)) consider(dist, p, q, "closed_form");
  }

  Result r;
  r.distance = best;
  r.lower_bound = certificate(m, d, best_p, best_q);
  r.p_disk = frame.R * best_p + frame.t;
  r.p_shape = frame.R * best_q + frame.t;
  r.scale = scaleOf(disk, shape);
  r.method = method;
  return r;
}

}  // namespace ref
}  // namespace fcl_disk_test
