// Disk - fcl::TriangleP (the leaf of meshes): the generic solver with the
// triangle's projection (its face, else its nearest edge) and support (a vertex).
// docs/disk_shape_distance.md, section 4.
#include "../disk_shape_pair.h"
#include "polygon_projection.h"

namespace fcl_disk {
namespace internal {
namespace {

/// A triangle whose angle at a is below this sine is a sliver: its plane, and
/// so its face projection, is known only to about eps / sine (the cross product
/// of nearly parallel edges), 1e-13 at this sine; its edges stay exact.
constexpr double kSliverSine = 1e-3;
/// The region test's vectors are scaled by the triangle's largest edge entry
/// while x is within this many of them (fourth powers stay below 1e200).
constexpr double kFarRatio = 1e50;

/// The closed flat triangle a, b, c, in its frame (a zero-area triangle is the
/// union of its edges).
struct TriangleTarget {
  std::array<Vec3, 3> vertices;
  Vec3 normal;       ///< (b - a) x (c - a) / inverse_edge^2, not normalised; zero when degenerate.
  Vec3 unit_normal;  ///< normal / |normal| (stableNorm: no overflow); zero when degenerate.
  bool sliver;  ///< |normal| < kSliverSine |b - a| |c - a|: the face projection
                ///< is checked against the edges'.
  double inverse_edge;  ///< 1 / the largest entry of b - a and c - a (1 if 0).

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
      return projectOntoPolygon(x, 3, [this](int i) { return vertices[i]; }, unit_normal);
    }
    const double v = vb / area, w = vc / area;
    return Projection{a + v * ab_raw + w * ac_raw,
                      FactoredHessian::diagonalOf(Vec3::Zero()).add(1.0, unit_normal)};
  }

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

  /// The point from + t edge of an edge, 0 < t < 1: psi's Hessian I - e e^T.
  static Projection onEdge(const Vec3& from, const Vec3& edge, double t) {
    return Projection{from + t * edge,
                      FactoredHessian::identity().add(-1.0 / edge.squaredNorm(), edge)};
  }

  Vec3 support(const Vec3& w) const {
    int best = 0;  // ties take the first vertex
    for (int i = 1; i < 3; ++i) {
      if (w.dot(vertices[i]) > w.dot(vertices[best])) best = i;
    }
    return vertices[best];
  }

  /// The face, for the nearly-parallel candidates (none when degenerate).
  template <typename Visit>
  void forEachFace(Visit&& visit) const {
    if (!(unit_normal.squaredNorm() > 0.0)) return;
    visit(unit_normal, 3, [this](int i) { return vertices[i]; });
  }
};

template <typename S>
struct TriangleTraits {
  static bool valid(const fcl::TriangleP<S>& triangle) {
    bool valid = true;
    for (const auto* v : {&triangle.a, &triangle.b, &triangle.c}) {
      valid &= (v->array().abs() <= kMaxDiskLength<S>).all();
    }
    return valid;
  }
  static double boundingRadius(const fcl::TriangleP<S>& triangle) {
    return std::sqrt(std::max({triangle.a.template cast<double>().squaredNorm(),
                               triangle.b.template cast<double>().squaredNorm(),
                               triangle.c.template cast<double>().squaredNorm()}));
  }
  static double inflation(const fcl::TriangleP<S>&) { return 0.0; }
  static TriangleTarget target(const fcl::TriangleP<S>& triangle) {
    TriangleTarget target{{triangle.a.template cast<double>(), triangle.b.template cast<double>(),
                           triangle.c.template cast<double>()},
                          Vec3::Zero(), Vec3::Zero(), false, 1.0};
    const Vec3 ab_raw = target.vertices[1] - target.vertices[0];
    const Vec3 ac_raw = target.vertices[2] - target.vertices[0];
    const double edge_largest = std::max(ab_raw.cwiseAbs().maxCoeff(), ac_raw.cwiseAbs().maxCoeff());
    if (edge_largest > 0.0) target.inverse_edge = 1.0 / edge_largest;
    // In edges scaled to entries <= 1: the normal's norm and the sliver test's
    // products cannot overflow (raw, they are fourth powers of lengths).
    const Vec3 ab = target.inverse_edge * ab_raw, ac = target.inverse_edge * ac_raw;
    target.normal = ab.cross(ac);
    const double area = target.normal.norm();
    if (area > 0.0) target.unit_normal = target.normal / area;
    target.sliver = area * area < kSliverSine * kSliverSine * ab.squaredNorm() * ac.squaredNorm();
    return target;
  }
  /// The triangle's normal.
  static std::array<Vec3, 1> contactDirections(const TriangleTarget& triangle) {
    return {triangle.unit_normal};
  }
};

}  // namespace

template <typename S>
struct DiskShapePair<fcl::TriangleP<S>>
    : GenericDiskShapePair<S, fcl::TriangleP<S>, TriangleTraits<S>> {};

}  // namespace internal
}  // namespace fcl_disk

FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::TriangleP)
