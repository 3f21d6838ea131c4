// Internal: projection onto a segment, a convex polygon and a triangle in 3-D,
// with psi's Hessian (I - D proj), shared by the triangle and convex-polytope pairs.
#pragma once

#include "../disk_shape_solver.h"

#include <algorithm>
#include <array>

namespace fcl_disk {
namespace internal {

/// Nearest point of the segment a-b to x: on the open segment psi's Hessian is
/// I - e e^T (e the unit direction), at an end (or a zero-length segment) I.
inline Projection projectOntoSegment(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 edge = b - a;
  const double length_squared = edge.squaredNorm();
  const double t = length_squared > 0.0 ? edge.dot(x - a) / length_squared : 0.0;
  if (t > 0.0 && t < 1.0) {
    return Projection{a + t * edge,
                      FactoredHessian::identity().add(-1.0 / length_squared, edge)};
  }
  return Projection{t <= 0.0 ? a : b, FactoredHessian::identity()};
}

/// Nearest point of the closed convex polygon with vertices `vertex(0..count-1)`
/// (in order around it) and normal `normal` (any length; zero for a degenerate
/// polygon) to x: the foot of x on the plane if it lies inside every edge (then
/// psi's Hessian is n n^T), else the nearest point of the boundary.
template <typename VertexAt>
Projection projectOntoPolygon(const Vec3& x, int count, VertexAt vertex, const Vec3& normal) {
  const double normal_squared = normal.squaredNorm();
  if (normal_squared > 0.0) {
    bool inside = true;
    for (int i = 0; i < count && inside; ++i) {
      const Vec3 from = vertex(i), to = vertex((i + 1) % count);
      inside = normal.dot((to - from).cross(x - from)) >= 0.0;
    }
    if (inside) {
      const Vec3 on_plane = x - (normal.dot(x - vertex(0)) / normal_squared) * normal;
      return Projection{on_plane, FactoredHessian().add(1.0 / normal_squared, normal)};
    }
  }
  Projection best{vertex(0), FactoredHessian::identity()};
  double best_squared = (x - best.q).squaredNorm();
  for (int i = 0; i < count; ++i) {
    const Projection on_edge = projectOntoSegment(x, vertex(i), vertex((i + 1) % count));
    const double squared = (x - on_edge.q).squaredNorm();
    if (squared < best_squared) best = on_edge, best_squared = squared;
  }
  return best;
}

/// A triangle whose angle at a is below this sine is a sliver: its plane, and
/// so its face projection, is known only to about eps / sine (the cross product
/// of nearly parallel edges), 1e-13 at this sine; its edges stay exact.
constexpr double kSliverSine = 1e-3;
/// The region test's vectors are scaled by the triangle's largest edge entry
/// while x is within this many of them (fourth powers stay below 1e200).
constexpr double kFarRatio = 1e50;

/// Projection onto the closed flat triangle a, b, c (a zero-area triangle is
/// the union of its edges), with what it needs computed once per triangle.
struct TriangleProjection {
  std::array<Vec3, 3> vertices;
  Vec3 unit_normal = Vec3::Zero();  ///< (b - a) x (c - a) normalised; zero when degenerate.
  bool sliver = false;  ///< |normal| < kSliverSine |b - a| |c - a|: the face projection
                        ///< is checked against the edges'.
  double inverse_edge = 1.0;  ///< 1 / the largest entry of b - a and c - a (1 if 0).

  TriangleProjection() = default;
  TriangleProjection(const Vec3& a, const Vec3& b, const Vec3& c) : vertices{a, b, c} {
    const Vec3 ab_raw = b - a, ac_raw = c - a;
    const double edge_largest = std::max(ab_raw.cwiseAbs().maxCoeff(), ac_raw.cwiseAbs().maxCoeff());
    if (edge_largest > 0.0) inverse_edge = 1.0 / edge_largest;
    // In edges scaled to entries <= 1: the normal's norm and the sliver test's
    // products cannot overflow (raw, they are fourth powers of lengths).
    const Vec3 ab = inverse_edge * ab_raw, ac = inverse_edge * ac_raw;
    const Vec3 normal = ab.cross(ac);
    const double area = normal.norm();
    if (area > 0.0) unit_normal = normal / area;
    sliver = area * area < kSliverSine * kSliverSine * ab.squaredNorm() * ac.squaredNorm();
  }

  /// The nearest point of the triangle to x, with psi's Hessian.
  Projection project(const Vec3& x) const {
    const Projection by_region = projectByRegion(x);
    if (!sliver) return by_region;
    // A sliver: the region test and the face point carry the plane's error; the
    // nearest edge point (the polygon projection without a plane), when nearer,
    // is the better answer (exact where x lies on an edge).
    const Projection on_edges =
        projectOntoPolygon(x, 3, [this](int i) { return vertices[i]; }, Vec3::Zero());
    return (x - on_edges.q).squaredNorm() < (x - by_region.q).squaredNorm() ? on_edges : by_region;
  }

  /// Ericson's region test (Real-Time Collision Detection, 5.1.5): the Voronoi
  /// region of x among the vertices, edges and face decides the nearest point
  /// from six dot products. A degenerate triangle, whose face region has no
  /// area, goes to the general polygon projection (its nearest edge). The
  /// tests multiply pairs of dot products (fourth powers of lengths): they run
  /// on the vectors scaled by their largest entry (the tests and the ratios are
  /// homogeneous), so lengths up to kMaxDiskLength do not overflow.
  Projection projectByRegion(const Vec3& x) const {
    const Vec3& a = vertices[0];
    const Vec3& b = vertices[1];
    const Vec3& c = vertices[2];
    const Vec3 ab_raw = b - a, ac_raw = c - a, ap_raw = x - a;
    // The triangle's own scale, unless x is so far that (|ap| / edge)^4 could
    // overflow: then |ap|'s.
    const double ap_largest = ap_raw.cwiseAbs().maxCoeff();
    const double inverse = ap_largest * inverse_edge <= kFarRatio ? inverse_edge : 1.0 / ap_largest;
    const Vec3 ab = inverse * ab_raw, ac = inverse * ac_raw, ap = inverse * ap_raw;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0.0 && d2 <= 0.0) return Projection{a, FactoredHessian::identity()};
    const Vec3 bp = inverse * (x - b);
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0.0 && d4 <= d3) return Projection{b, FactoredHessian::identity()};
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0) {
      return onEdge(a, ab_raw, d1 / (d1 - d3));
    }
    const Vec3 cp = inverse * (x - c);
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0.0 && d5 <= d6) return Projection{c, FactoredHessian::identity()};
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0) {
      return onEdge(a, ac_raw, d2 / (d2 - d6));
    }
    const double va = d3 * d6 - d5 * d4;
    const double towards_c = d4 - d3, towards_b = d5 - d6;
    if (va <= 0.0 && towards_c >= 0.0 && towards_b >= 0.0 && towards_c + towards_b > 0.0) {
      return onEdge(b, c - b, towards_c / (towards_c + towards_b));
    }
    const double area = va + vb + vc;  // |normal|^2, scaled
    if (!(area > 0.0)) {
      // No area to rounding: the union of the edges (a sliver's unit normal,
      // known only to eps / sine, would put a face foot off the triangle).
      return projectOntoPolygon(x, 3, [this](int i) { return vertices[i]; }, Vec3::Zero());
    }
    const double v = vb / area, w = vc / area;
    // A sliver's barycentric coordinates carry its plane's error (1 / sine):
    // out of range, their point lies off the triangle; its edges decide.
    if (sliver && !(v >= 0.0 && w >= 0.0 && v + w <= 1.0)) {
      return projectOntoPolygon(x, 3, [this](int i) { return vertices[i]; }, Vec3::Zero());
    }
    return Projection{a + v * ab_raw + w * ac_raw,
                      FactoredHessian::diagonalOf(Vec3::Zero()).add(1.0, unit_normal)};
  }

  /// The point from + t edge of an edge, 0 < t < 1: psi's Hessian I - e e^T.
  static Projection onEdge(const Vec3& from, const Vec3& edge, double t) {
    return Projection{from + t * edge,
                      FactoredHessian::identity().add(-1.0 / edge.squaredNorm(), edge)};
  }
};

}  // namespace internal
}  // namespace fcl_disk
