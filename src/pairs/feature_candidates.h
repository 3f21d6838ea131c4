// Internal: candidate directions of the penetration depth of a disk against a
// shape's vertices and edge lines (docs/penetration_depth.md, section 7). Where
// a vertex or an edge is the shape's support, F(w) = h_disk(w) + h_shape(-w) is
// the disk's support against that point or line, and these are the directions
// at which it is stationary. Capsule and cylinder use them for their segment
// ends and axis, the polytopes (box, triangle, convex) for all their features,
// cylinder and cone their flat ends.
#pragma once

#include <cmath>
#include <functional>

#include "../disk_penetration_candidates.h"
#include "../disk_shape_solver.h"
#include "../trig_roots.h"

namespace fcl_disk {
namespace internal {

/// Whether a candidate w at which F would be `value` (rho included) if its
/// feature were the shape's support there is no stationary point of F: for a
/// pair the search knows to share a point (it prunes, to within the touching
/// tolerance, under its slack) every F(w) >= -slack, so a lower value would
/// separate the sets, and the feature is not the support at w.
template <typename Search>
bool wouldSeparate(const Search& directions, double value) {
  return directions.prunes() && value < -directions.pruneSlack();
}

/// Appends the direction where F can have a local minimum through a vertex s
/// (docs/penetration_depth.md, section 7): where s is the shape's support,
/// F(w) = h_disk(w) - s.w + rho is h_K(w) + rho for K = disk - s, stationary
/// on the sphere where K's support point b - s is lambda w, lambda = h_K(w),
/// b a rim point (b - s normal to the rim tangent: the rim points nearest and
/// farthest s) or w = +-n (the disk's normals, always candidates). Along the
/// sphere's direction in the plane of w and n, h_K is linear, so its curvature
/// there is -lambda: a critical point with lambda > 0 is no minimum. Only the
/// nearest rim point with s's foot outside the rim has lambda = -|b - s| < 0,
/// along s - b (the sign whose disk support point is b), where F = rho -
/// |b - s| if s is the support: skipped where that would separate the sets
/// (wouldSeparate). A vertex on the disk's axis has every rim point at one
/// distance; there the disk's normals give the least F.
template <typename Search>
void addVertexCandidates(const DiskInShape& disk, const Vec3& s, Search* directions) {
  const Vec2 radial = disk.inPlane(s - disk.c);
  const double length_squared = radial.squaredNorm();
  if (!(length_squared > disk.r * disk.r)) return;  // the foot within the rim
  const double length = std::sqrt(length_squared);
  const Vec3 rim_offset = (disk.r / length) * (radial.x() * disk.u + radial.y() * disk.v);
  const Vec3 w = s - (disk.c + rim_offset);  // s minus its nearest rim point
  // F = rho - |w| there if s were the support (b the disk's support point
  // along w, for orthonormal axes): wouldSeparate's test, F < -slack, is
  // |w| > rho + slack, compared squared; the axes' check (three products)
  // only for the candidates it would skip.
  if (directions->prunes()) {
    const double margin = directions->inflation() + directions->pruneSlack();
    if (w.squaredNorm() > margin * margin && disk.hasOrthonormalAxes()) return;
  }
  directions->push_one(w);
}

/// Arcs of the disk's rim where an edge line's candidate can beat the search's
/// bound (addEdgeLineCandidates): at a minimiser on the edge's arc
/// b - x = (PD - offset) w with x on the line, offset the line's offset plus
/// the search's inflation; where b is farther than the offset from the line,
/// PD - offset = |b - x| >= that distance. The rim point b moves at speed r.
template <typename Search>
struct EdgeArcsThatCanBeatBound {
  const DiskInShape& disk;
  const Vec3 &s, &e;
  double offset;
  const Search& search;
  /// Arcs are halved for the test down to kPrunedArcWidth, as for disk-disk
  /// (their coefficients are formed only for the arcs that pass it).
  static constexpr double split_wider_than = kPrunedArcWidth;
  bool operator()(double cos_theta, double sin_theta, double radius) const {
    const Vec3 from_s = disk.c + disk.r * (cos_theta * disk.u + sin_theta * disk.v) - s;
    const double from_line = (from_s - from_s.dot(e) * e).norm() - disk.r * radius;
    return !(from_line > offset) || from_line + offset <= search.pruningBound();
  }
};

/// Where w is within this (cosine) of normal to the disk, its two signs'
/// support points nearly tie, and an edge line's candidate keeps both.
constexpr double kSupportSignTie = 1e-9;

/// Appends the directions w normal to the line {s + t e} (e unit) at which the
/// disk's support, restricted to such directions, is stationary: where an edge
/// is the shape's support (w . e = 0), F(w) = h_disk(w) - s.w, and its
/// critical points have the disk's support point b(theta) = c + r (cos u +
/// sin v) with b - x along w, x the line's point nearest b. Both conditions
/// (w normal to e and to the rim tangent b') give
///   E(theta) = ((b - s).e)(e.b') - (b - s).b' = 0,
/// a trigonometric polynomial of degree 2 (every root, trig_roots.h), and
/// w = b - x, which is also e x b' (w is normal to both). Both are appended:
/// e x b' knows w to the root's accuracy where b is near the line (a vertex
/// on the rim, a touching pair) and b - x where e is nearly along b', each
/// with the sign along which b is the disk's support. With d = c - s, a = d.e:
///   E = (a e.v - d.v) cos + (d.u - a e.u) sin + r (e.u)(e.v) cos 2theta
///       + r ((e.v)^2 - (e.u)^2)/2 sin 2theta   (b' taken for r = 1).
///
/// `offset`: where the line is the shape's support on that circle, the shape's
/// support along -w lies this far beyond it (0 for an edge; a cylinder's
/// radius for its axis). For a pair that shares a point, a root is visited
/// only where it can beat the search's bound: at a minimiser on the edge's arc
/// b - x = (PD - offset) w with x on the line (the Lagrange condition on the
/// circle w . e = 0), so PD - offset = |b - x| where b is farther than the
/// offset from the line (EdgeArcsThatCanBeatBound).
template <typename Search>
void addEdgeLineCandidates(const DiskInShape& disk, const Vec3& s, const Vec3& e,
                           Search* directions, double offset = 0.0) {
  using namespace trig_roots;
  const Vec3 d = disk.c - s;
  const double a = d.dot(e), e_u = e.dot(disk.u), e_v = e.dot(disk.v);
  TrigPolynomial E;
  E.C[1] = a * e_v - d.dot(disk.v);
  E.S[1] = d.dot(disk.u) - a * e_u;
  E.C[2] = disk.r * e_u * e_v;
  E.S[2] = 0.5 * disk.r * (e_v * e_v - e_u * e_u);
  const double size = d.norm() + disk.r;  // bounds |E|'s terms
  const double rho = offset + directions->inflation();
  // w (either form) with the sign along which b is the disk's support, where
  // F(w) = w.(b - x) / |w| + rho: the other sign has the opposite rim point
  // as its support, not a root, so it is no candidate of this line (w normal
  // to the disk within kSupportSignTie: both, as the rim points nearly tie).
  // Skipped where that F would separate the sets (wouldSeparate).
  const auto push_supported = [&](const Vec3& w, const Vec3& b, const Vec3& from_line) {
    const double along_radius = (b - disk.c).dot(w), length = w.norm();
    if (!(std::abs(along_radius) > kSupportSignTie * disk.r * length)) {
      directions->push_back(w);
      return;
    }
    const Vec3 supported = along_radius > 0.0 ? w : Vec3(-w);
    if (wouldSeparate(*directions, supported.dot(from_line) / length + rho)) return;
    directions->push_one(supported);
  };
  const auto visit = [&](double cos_theta, double sin_theta) {
    const Vec3 b = disk.c + disk.r * (cos_theta * disk.u + sin_theta * disk.v);
    const Vec3 from_line = (b - s) - (b - s).dot(e) * e;  // b - x
    push_supported(from_line, b, from_line);
    push_supported(e.cross(cos_theta * disk.v - sin_theta * disk.u), b, from_line);
  };
  // A search that does not prune has an infinite bound: every arc is kept.
  forEachRootAngle<2>(E, kBernsteinNoise * size, visit,
                      EdgeArcsThatCanBeatBound<Search>{disk, s, e,
                                                       offset + directions->inflation(),
                                                       *directions});
}

/// Appends the directions where a flat circular end of the shape (centre
/// (0, 0, z), normal z) is its support: F is there the disk-disk F of the disk
/// against the end, and its candidates are the disk-disk candidate set
/// (forEachDiskPairPenetrationCandidate; the smaller disk's rim is the one Q
/// follows). An end of radius 0 is a vertex.
///
/// For a pair that shares a point the search's bound prunes the roots as in
/// diskPenetration: where the end is the support F is the disk-disk F, so a
/// minimiser there is a critical rim pair with |b - a| = PD.
template <typename Search>
void addFlatEndCandidates(const DiskInShape& disk, const FlatEnd& end, Search* directions) {
  const Vec3 end_centre(0.0, 0.0, end.z);
  if (!(end.radius > 0.0)) {
    addVertexCandidates(disk, end_centre, directions);
    return;
  }
  const Mat3 R_disk = (Mat3() << disk.u, disk.v, disk.n).finished();
  const bool disk_is_smaller = disk.r <= end.radius;
  const PairInFrame1 pair =
      disk_is_smaller ? PairInFrame1::make(disk.c - end_centre, R_disk, end.radius, disk.r)
                      : PairInFrame1::make(R_disk.transpose() * (end_centre - disk.c),
                                           R_disk.transpose(), disk.r, end.radius);
  const double scale = pair.scale();
  const PairInFrame1 unit_pair =
      PairInFrame1::make(pair.c / scale, pair.R, pair.r1 / scale, pair.r2 / scale);
  const std::function<double()> bound = [&] { return directions->pruningBound() / scale; };
  forEachDiskPairPenetrationCandidate(
      unit_pair,
      [&](const Vec3& w) { directions->push_back(disk_is_smaller ? w : Vec3(R_disk * w)); },
      directions->prunes() ? &bound : nullptr);
}

}  // namespace internal
}  // namespace fcl_disk
