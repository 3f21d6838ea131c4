// Internal: cheap lower bounds on the distance from a disk to a box or a
// triangle, and the exact distance where a closed form holds, for the
// traversals of meshes and octrees (src/mesh_distance.h, src/octree_distance.h).
// Derivation: docs/meshes_and_octrees.md, "Distance traversal".
//
// Frame: the environment's (a mesh's frame M, an octree's frame O); the disk is
// a DiskInShape there (centre c, in-plane axes u, v, normal n, radius r).
// Units: lengths of that frame. Everything is in double.
//
// For a point x write a(x) = n.(x - c) (height over the disk's plane) and
// rho(x) = |(u.(x - c), v.(x - c))| (distance from the disk's axis). The disk
// point nearest x is x's foot on the plane, clamped to the rim, so
//   dist(x, disk)^2 = a(x)^2 + max(rho(x) - r, 0)^2,
// and over a set X, with a_min = min |a| and rho_min = min rho over X,
//   dist(X, disk) >= sqrt(a_min^2 + max(rho_min - r, 0)^2)        (1)
// (both minima taken separately). Equality holds when every point of X
// projects into the disk (rho <= r on X): then dist(X, disk) = a_min, reached
// at a vertex of a polytope X if a keeps one sign on it, and 0 at a point where
// a crosses 0 otherwise.
//
// Guarantee: each bound is below the true distance by at least its rounding
// pad (kEnvironmentBoundPad of the magnitudes involved), so a traversal that
// prunes a volume whose bound is >= its best distance loses at most that pad.
// Degenerate input: zero extents and zero-area triangles are sets like any
// other (a zero-area triangle's projected "inside" test can only report 0, a
// valid bound); NaN coordinates give a bound of 0 (never prune on NaN).
#pragma once

#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/kDOP.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <utility>

#include "disk_shape_solver.h"
#include "segment_to_disk.h"

namespace fcl_disk {
namespace internal {

/// The rounding pad of the bounds, relative to the largest magnitude in the
/// computation (|c|, r, and the box's centre and extents or the triangle's
/// vertices): each bound is ~30 roundings of terms no larger than that, each at
/// most one ulp of it; 64 ulps covers them twice over. A volume fitted in float
/// (FCL's BVs of a float mesh) contains its triangles only to float rounding, so
/// the traversals scale the pad by that type's epsilon instead.
constexpr double kEnvironmentBoundPadUlps = 64.0;

/// A lower bound on dist(box, disk), unpadded, for the box with centre o,
/// orthonormal axes A_k and half-extents e_k >= 0: the larger of
///  * dist(c, box) - r (the disk lies in the ball of radius r about c);
///  * dist(o, disk) minus the box's extent along the direction from o's
///    nearest disk point to o (separation along that direction). For a box
///    whose centre projects into the disk that is (1) with rho_min = 0: the
///    gap along n less the box's extent along n.
/// Adding (1) itself, with rho_min bounded through the box's extent towards
/// the axis, prunes a few more volumes in docs/scenes.md's environment but
/// costs more instructions per query than it saves there.
/// `R` maps a vector's coordinates in the environment's frame to the box's
/// (A^T); Identity for an axis-aligned box. The disk's axes are orthonormal
/// (orthonormalDiskInShape), so d - (n.d) n is d's in-plane part.
template <typename Rotation>
double diskBoxLowerBound(const DiskInShape& disk, const Vec3& o, const Rotation& R,
                         const Vec3& e) {
  const Vec3 d = o - disk.c;
  const Vec3 d_box = R * d, n_box = R * disk.n;
  const double a_o = disk.n.dot(d), x = disk.u.dot(d), y = disk.v.dot(d);
  const double rho = std::sqrt(x * x + y * y);
  const double rim_gap = std::max(rho - disk.r, 0.0);
  // From o's nearest disk point to o, in box coordinates: d's in-plane part
  // x u + y v is d - a_o n (orthonormal axes), so it needs no u or v turned
  // into the box.
  Vec3 from_disk_box = a_o * n_box;
  if (rim_gap > 0.0) from_disk_box += (rim_gap / rho) * (d_box - from_disk_box);
  const double centre_distance = std::sqrt(a_o * a_o + rim_gap * rim_gap);
  const double along = centre_distance > 0.0
                           ? centre_distance - e.dot(from_disk_box.cwiseAbs()) / centre_distance
                           : 0.0;
  const double ball = (d_box.cwiseAbs() - e).cwiseMax(0.0).norm() - disk.r;
  return std::max(ball, along);
}

inline double diskAlignedBoxLowerBound(const DiskInShape& disk, const Vec3& o, const Vec3& e) {
  return diskBoxLowerBound(disk, o, Mat3::Identity(), e);
}

/// An axis-aligned box in double: centre o, half-extents e >= 0.
struct AlignedBox {
  Vec3 o;
  Vec3 e;
};
/// FCL's AABB (a volume, an octree cell), its centre and half-extents formed
/// in S as FCL forms a cell's box.
template <typename S>
inline AlignedBox alignedBoxOf(const fcl::AABB<S>& box) {
  return {((box.min_ + box.max_) / 2).template cast<double>(),
          ((box.max_ - box.min_) / 2).template cast<double>()};
}
/// A k-DOP's first three slab pairs: the box along FCL's coordinate axes.
template <typename S, std::size_t N>
inline AlignedBox alignedBoxOf(const fcl::KDOP<S, N>& kdop) {
  const Vec3 low(kdop.dist(0), kdop.dist(1), kdop.dist(2));
  const Vec3 high(kdop.dist(N / 2), kdop.dist(N / 2 + 1), kdop.dist(N / 2 + 2));
  return {(low + high) / 2, (high - low) / 2};
}

/// The disk's half-extents along the frame's axes: r |(u_k, v_k)| (from the
/// in-plane axes: r sqrt(1 - n_k^2) loses every digit for n_k near 1).
inline Vec3 diskAxisExtents(const DiskInShape& disk) {
  return disk.r * Vec3(std::sqrt(disk.u.x() * disk.u.x() + disk.v.x() * disk.v.x()),
                       std::sqrt(disk.u.y() * disk.u.y() + disk.v.y() * disk.v.y()),
                       std::sqrt(disk.u.z() * disk.u.z() + disk.v.z() * disk.v.z()));
}

/// A lower bound on dist(box, disk), unpadded, cheaper and looser than
/// diskBoxLowerBound, for the collision traversals, which only ask whether a
/// volume is farther than a small tolerance: the larger of the gaps between
/// the box's and the disk's intervals along the box's axes (the disk's
/// half-extent along a unit a is r |(u.a, v.a)|) and along the disk's normal
/// (|n.(o - c)| less the box's half-extent along n). Separating-axis tests on
/// those four axes. The axis-aligned box with the disk's extents along the
/// frame's axes precomputed (diskAxisExtents), and an oriented box (`R` = A^T
/// as diskBoxLowerBound's).
inline double diskAlignedBoxSeparation(const DiskInShape& disk, const Vec3& disk_extents,
                                       const Vec3& o, const Vec3& e) {
  const Vec3 d = o - disk.c;
  const double axis_gap = (d.cwiseAbs() - e - disk_extents).maxCoeff();
  return std::max(axis_gap, std::abs(disk.n.dot(d)) - e.dot(disk.n.cwiseAbs()));
}
template <typename Rotation>
double diskBoxSeparation(const DiskInShape& disk, const Vec3& o, const Rotation& R, const Vec3& e) {
  const Vec3 d = o - disk.c;
  const Vec3 d_box = R * d, u_box = R * disk.u, v_box = R * disk.v, n_box = R * disk.n;
  const Vec3 disk_extents =
      disk.r * (u_box.cwiseAbs2() + v_box.cwiseAbs2()).cwiseSqrt();
  const double axis_gap = (d_box.cwiseAbs() - e - disk_extents).maxCoeff();
  return std::max(axis_gap, std::abs(disk.n.dot(d)) - e.dot(n_box.cwiseAbs()));
}

/// The largest magnitude a box bound is computed from, but for the disk's
/// share r + |c| (diskBoundMagnitude).
inline double boxBoundMagnitude(const Vec3& o, const Vec3& e) {
  return o.cwiseAbs().maxCoeff() + e.maxCoeff();
}
inline double diskBoundMagnitude(const DiskInShape& disk) {
  return disk.r + disk.c.cwiseAbs().maxCoeff();
}

/// A leaf (a triangle, a cell) against the disk: the certified distance with
/// nearest points (`exact`), or a lower bound (unpadded) for the solver.
struct LeafToDisk {
  bool exact = false;
  double distance = 0.0;
  double certified = 0.0;  ///< exact only: the certificate, <= the true distance
  Vec3 p_disk{Vec3::Zero()}, p_leaf{Vec3::Zero()};  ///< exact only
};

/// The exact leaf of a pair p_disk, p_leaf `upper` apart, certified to `lower`.
inline LeafToDisk exactLeaf(double upper, double lower, const Vec3& p_disk, const Vec3& p_leaf) {
  LeafToDisk answer;
  answer.exact = true;
  answer.distance = upper;
  answer.certified = std::min(lower, upper);
  answer.p_disk = p_disk;
  answer.p_leaf = p_leaf;
  return answer;
}

/// A leaf not settled, bounded below by `lower` (0 for a negative bound or NaN).
inline LeafToDisk boundedLeaf(double lower) {
  LeafToDisk answer;
  answer.distance = lower > 0.0 ? lower : 0.0;
  return answer;
}

/// A leaf whose best upper bound (the pair p_disk, p_leaf, `upper` apart) and
/// best lower bound are known: exact when they meet within kShapeGapTolerance
/// of the scene (the solver's own stopping test) plus `mismatch` (a Target's
/// supportMismatch: the bounds of a Convex with non-planar faces cannot meet
/// closer), else the lower bound (0 for NaN).
inline LeafToDisk certifiedOrBound(double lower, double upper, const Vec3& p_disk,
                                   const Vec3& p_leaf, double scale, double mismatch = 0.0) {
  if (upper - lower <= kShapeGapTolerance * scale + mismatch) {
    return exactLeaf(upper, lower, p_disk, p_leaf);
  }
  return boundedLeaf(lower);
}

/// certifiedOrBound with the lower bound given as numerator / length: a
/// certificate along an unnormalised direction of that length (positively
/// homogeneous). The test is taken times the length, so the division, which
/// only the returned bound needs, is off the test's chain. A length that is
/// not positive gives no bound.
inline LeafToDisk certifiedOrBoundAlong(double numerator, double length, double upper,
                                        const Vec3& p_disk, const Vec3& p_leaf, double scale,
                                        double mismatch = 0.0) {
  const bool positive = length > 0.0;
  const double lower =
      positive ? numerator / length : -std::numeric_limits<double>::infinity();
  if (positive &&
      upper * length - numerator <= (kShapeGapTolerance * scale + mismatch) * length) {
    return exactLeaf(upper, lower, p_disk, p_leaf);
  }
  return boundedLeaf(lower);
}

/// A solver's answer (nearest points, distance, certificate) as an exact leaf.
inline LeafToDisk exactLeafOf(const DiskShapeSolution& solution) {
  LeafToDisk answer;
  answer.exact = true;
  answer.distance = solution.distance;
  answer.certified = solution.lower_bound;
  answer.p_disk = solution.p;
  answer.p_leaf = solution.q;
  return answer;
}

/// Raises `lower` to the certificate along the direction of a pair of points
/// `distance` apart, w = (p_leaf - p_disk) / distance: least_along(w) - h_K(w),
/// `least_along(w)` the least w.y over the leaf. Both are positively
/// homogeneous, so they are taken along p_leaf - p_disk and divided by
/// `distance` once: the support's square root then runs beside the one that
/// gave `distance`, not after a division by it.
template <typename LeastAlong>
void certifyAlongPair(const DiskInShape& disk, LeastAlong&& least_along, double distance,
                      const Vec3& p_disk, const Vec3& p_leaf, double* lower) {
  if (!(distance > 0.0)) return;
  const Vec3 separation = p_leaf - p_disk;
  *lower = std::max(*lower, (least_along(separation) - disk.support(separation)) / distance);
}

/// A pair `upper` apart, exact when the certificate along it alone closes
/// (certifiedOrBound, `mismatch` as there): an overlap makes that certificate
/// negative, so a pair that only nearly touches is not taken for the distance.
template <typename LeastAlong>
LeafToDisk certifiedAlongItself(const DiskInShape& disk, LeastAlong&& least_along, double upper,
                                const Vec3& p_disk, const Vec3& p_leaf, double scale,
                                double mismatch = 0.0) {
  double lower = -std::numeric_limits<double>::infinity();
  certifyAlongPair(disk, least_along, upper, p_disk, p_leaf, &lower);
  return certifiedOrBound(lower, upper, p_disk, p_leaf, scale, mismatch);
}

/// The certificate along a segment's pair, in the direction
/// SegmentToDisk::certificateDirection gives (the one segmentToDisk's
/// precision is chosen for), w: least_along(w) - h_K(w), to be divided by
/// |w| (`length`), `least_along` as certifyAlongPair's.
struct AlongSegmentPair {
  double numerator;
  double length;
};
template <typename LeastAlong>
AlongSegmentPair alongSegmentPair(const DiskInShape& disk, LeastAlong&& least_along,
                                  const SegmentToDisk& pair) {
  const Vec3 w = pair.certificateDirection();
  return {least_along(w) - disk.support(w), w.norm()};
}

/// Raises `lower` to the certificate along a segment's pair (alongSegmentPair).
template <typename LeastAlong>
void certifyAlongSegmentPair(const DiskInShape& disk, LeastAlong&& least_along,
                             const SegmentToDisk& pair, double* lower) {
  const AlongSegmentPair along = alongSegmentPair(disk, least_along, pair);
  if (!(along.length > 0.0)) return;
  *lower = std::max(*lower, along.numerator / along.length);
}

/// certifiedAlongItself for a segment's pair, along its certificateDirection
/// (certifiedOrBoundAlong), X `inflation` thick about `least_along`'s set (a
/// capsule's radius): the pair's leaf point moved that far towards the disk.
template <typename LeastAlong>
LeafToDisk certifiedSegmentPair(const DiskInShape& disk, LeastAlong&& least_along,
                                const SegmentToDisk& pair, double scale, double mismatch = 0.0,
                                double inflation = 0.0) {
  const AlongSegmentPair along = alongSegmentPair(disk, least_along, pair);
  const double upper = pair.distance - inflation;
  const Vec3 p_leaf = inflation > 0.0 ? Vec3(pair.p_segment - (inflation / pair.distance) *
                                                                 (pair.p_segment - pair.p_disk))
                                       : pair.p_segment;
  return certifiedOrBoundAlong(along.numerator - inflation * along.length, along.length, upper,
                               pair.p_disk, p_leaf, scale, mismatch);
}

/// The stretch [low, high] of tau for which the in-plane point s + tau along
/// lies within the rim (s itself within it, but for rounding): between the
/// roots of |s + tau along|^2 = r^2. None for along = 0.
inline std::optional<std::pair<double, double>> stretchWithinRim(const DiskInShape& disk,
                                                                 const Vec2& s, const Vec2& along) {
  const double a = along.squaredNorm(), b = s.dot(along), c = s.squaredNorm() - disk.r * disk.r;
  if (!(a > 0.0)) return std::nullopt;
  const double root = std::sqrt(std::max(b * b - a * c, 0.0));
  return std::pair((-b - root) / a, (-b + root) / a);
}

/// The leaf's edges as candidates for the nearest pair (the rim or the face
/// against an edge, which neither a vertex nor a face settles), in order: the
/// nearest pair of the disk and each segment edges[i] (segmentToDisk) replaces
/// the upper bound when nearer, and the certificate along its direction raises
/// `lower` (certifyAlongSegmentPair); the rest are skipped once `lower` reaches
/// `worth_below` (a traversal drops a leaf bounded at or above its best).
/// Worth it (edgesWorthTrying) while the bounds are apart by more than the gap
/// tolerance and `lower` is below `worth_below`.
inline bool edgesWorthTrying(double lower, double upper, double scale, double worth_below) {
  return upper - lower > kShapeGapTolerance * scale && lower < worth_below;
}
template <int kEdges, typename LeastAlong>
void tryEdges(const DiskInShape& disk, const Vec3 (&edges)[kEdges][2], LeastAlong&& least_along,
              double worth_below, double* lower, double* upper, Vec3* upper_disk,
              Vec3* upper_leaf) {
  for (int i = 0; i < kEdges && *lower < worth_below; ++i) {
    const SegmentToDisk edge = segmentToDisk(disk, edges[i][0], edges[i][1]);
    if (edge.distance < *upper) {
      *upper = edge.distance;
      *upper_disk = edge.p_disk;
      *upper_leaf = edge.p_segment;
    }
    certifyAlongSegmentPair(disk, least_along, edge, lower);
  }
}

/// The points where a polytope's edge from vertex i to vertex j meets the
/// disk's plane, in the disk's in-plane coordinates, given each vertex's
/// height a over the plane and in-plane coordinates (x, y): a vertex on the
/// plane is itself such a point. The section of a convex polytope by the plane
/// is their convex hull. At most kMaxSectionPoints (a box: its 12 edges).
struct PlaneSection {
  static constexpr int kMaxSectionPoints = 12;
  Vec2 points[kMaxSectionPoints];
  int count = 0;

  void addEdge(double a_i, double x_i, double y_i, double a_j, double x_j, double y_j) {
    if (!((a_i < 0.0 && a_j > 0.0) || (a_i > 0.0 && a_j < 0.0)) || count == kMaxSectionPoints) {
      return;
    }
    const double t = a_i / (a_i - a_j);
    points[count++] = Vec2(x_i + t * (x_j - x_i), y_i + t * (y_j - y_i));
  }
  void addVertexOnPlane(double a, double x, double y) {
    if (a == 0.0 && count < kMaxSectionPoints) points[count++] = Vec2(x, y);
  }

  /// The rounding of a section point (an interpolation of corner coordinates)
  /// and of a cross product p x q, relative to |p| |q|: an orientation below it
  /// has no sign. Loose by design: a fan triangle that holds the centre with
  /// every edge beyond the rim has |p x q| >= 2 r^2 for each edge (its sides
  /// are >= 2r), far above it unless the section lies ~1e7 radii away, where
  /// the caller's other bounds decide.
  static constexpr double kOrientationRounding = 16 * std::numeric_limits<double>::epsilon();

  /// A point of the section within the disk of radius r about the origin (the
  /// disk's centre), if the section meets it: a section point within the
  /// rim; else the point nearest the centre of a segment between two section
  /// points (inside the convex section) that passes within the rim, which a
  /// boundary edge crossing the rim is; else the centre, when a triangle of
  /// the fan from the first point contains it with each of its three
  /// orientations signed beyond kOrientationRounding (the fan covers the
  /// section; a section of coincident points, the plane through a corner,
  /// has no such triangle).
  /// The disk lies in the plane, so it meets the polytope iff it meets the
  /// section.
  std::optional<Vec2> commonPointWithDisk(double r) const {
    const double r_squared = r * r;
    for (int i = 0; i < count; ++i) {
      if (points[i].squaredNorm() <= r_squared) return points[i];
    }
    for (int i = 0; i < count; ++i) {
      for (int j = i + 1; j < count; ++j) {
        const Vec2 edge = points[j] - points[i];
        const double length_squared = edge.squaredNorm();
        if (!(length_squared > 0.0)) continue;
        const double t = std::clamp(-points[i].dot(edge) / length_squared, 0.0, 1.0);
        const Vec2 nearest = points[i] + t * edge;
        if (nearest.squaredNorm() <= r_squared) return nearest;
      }
    }
    // +1 or -1 for an orientation p x q signed beyond its rounding, else 0.
    const auto orientation = [](const Vec2& p, const Vec2& q) {
      const double cross = p.x() * q.y() - p.y() * q.x();
      const double rounding = kOrientationRounding * std::sqrt(p.squaredNorm() * q.squaredNorm());
      return cross > rounding ? 1 : cross < -rounding ? -1 : 0;
    };
    for (int i = 1; i < count; ++i) {
      const int s0 = orientation(points[0], points[i]);
      if (s0 == 0) continue;
      for (int j = i + 1; j < count; ++j) {
        if (orientation(points[i], points[j]) == s0 && orientation(points[j], points[0]) == s0) {
          return Vec2::Zero();
        }
      }
    }
    return std::nullopt;
  }
};

/// A leaf met by the disk at a common point: distance 0.
inline LeafToDisk meetingAt(const Vec3& common_point) {
  LeafToDisk answer;
  answer.exact = true;
  answer.p_disk = answer.p_leaf = common_point;
  return answer;
}
/// The same at the disk's point of in-plane coordinates s (a section's common point).
inline LeafToDisk meetingAt(const DiskInShape& disk, const Vec2& s) {
  return meetingAt(disk.point(s));
}

/// The distance from the origin to the closed 2D triangle p0 p1 p2 (or a lower
/// bound 0 for a degenerate one whose line passes through the origin).
inline double originToTriangle2(const Vec2& p0, const Vec2& p1, const Vec2& p2) {
  const auto cross = [](const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); };
  const double e0 = cross(p0, p1), e1 = cross(p1, p2), e2 = cross(p2, p0);
  if ((e0 >= 0.0 && e1 >= 0.0 && e2 >= 0.0) || (e0 <= 0.0 && e1 <= 0.0 && e2 <= 0.0)) return 0.0;
  double nearest_squared = std::numeric_limits<double>::infinity();
  const Vec2* corners[3] = {&p0, &p1, &p2};
  for (int i = 0; i < 3; ++i) {
    const Vec2& a = *corners[i];
    const Vec2 edge = *corners[(i + 1) % 3] - a;
    const double length_squared = edge.squaredNorm();
    const double t =
        length_squared > 0.0 ? std::clamp(-a.dot(edge) / length_squared, 0.0, 1.0) : 0.0;
    nearest_squared = std::min(nearest_squared, (a + t * edge).squaredNorm());
  }
  return std::sqrt(nearest_squared);
}

/// A leaf's answer computed in lengths over a power of two near `scale`, the
/// scene's size (an exact scaling), and scaled back: `solve(unit_disk, to_unit,
/// unit_scale)` answers for the disk so scaled, with its own shape's lengths
/// times `to_unit`, and `unit_scale` in [1, 2). For closed forms that multiply
/// more than two lengths, whose products would otherwise leave the range of
/// doubles in scenes far from 1 in size. Not inlined: it is the rare path, and
/// a flattened caller (TriangleTraits::closedForm) would otherwise hold the
/// solver twice.
template <typename Solve>
[[gnu::noinline]] LeafToDisk inSceneUnits(const DiskInShape& disk, double scale, Solve&& solve) {
  const auto [to_unit, from_unit] = powersOfTwoAbout(scale);
  DiskInShape unit_disk = disk;
  unit_disk.c *= to_unit;
  unit_disk.r *= to_unit;
  LeafToDisk answer = solve(unit_disk, to_unit, scale * to_unit);
  answer.distance *= from_unit;
  answer.certified *= from_unit;
  answer.p_disk *= from_unit;
  answer.p_leaf *= from_unit;
  return answer;
}

/// The triangle p0 p1 p2 (frame of the disk's DiskInShape) against the disk,
/// without iterating (docs/meshes_and_octrees.md, "Distance traversal"):
///  * every vertex projects into the disk: (1) is exact (the first vertex of
///    least |a|; a crossing: the point of the first edge p0p1, p1p2, p2p0 whose
///    heights change sign or vanish, as both points);
///  * else (1) as the bound when it is already at `worth_below`;
///  * else the certificate of the generic solver, dist >= min_T w.y - h_K(w)
///    for unit w (h_K(w) = w.c + r |(u.w, v.w)|), on two directions: from the
///    vertex nearest the disk to its nearest disk point, and the triangle's
///    normal m (towards the disk); the upper bounds are that vertex's distance
///    and, when the disk's point deepest along -m lies over the triangle, its
///    height over the face. They are exact when the nearest pair is a vertex
///    and a disk point, or the face and a disk point; if the best upper bound
///    is within kShapeGapTolerance of the scene of the best lower bound, that
///    is the answer (the solver's own stopping test);
///  * else the same with the candidates of the two edges at that nearest
///    vertex (tryEdges): the rim or the face against an edge;
///  * else the lower bound, the largest of (1) and the certificates.
/// `scale`: the solver's scene size, r + the triangle's bounding radius + |c|;
/// `worth_below`: a traversal's best distance so far (it drops leaves bounded
/// at or above it), tryEdges'.
/// triangleToDisk for a scene within kTriangleUnscaledRange of 1 in size.
inline LeafToDisk triangleToDiskInUnits(const DiskInShape& disk, const Vec3& p0, const Vec3& p1,
                                        const Vec3& p2, double scale, double worth_below) {
  const Vec3* vertices[3] = {&p0, &p1, &p2};
  double a[3];
  Vec2 foot[3];
  double rim_gap[3];  // max(rho - r, 0)
  bool inside = true;
  for (int i = 0; i < 3; ++i) {
    const Vec3 d = *vertices[i] - disk.c;
    a[i] = disk.n.dot(d);
    foot[i] = Vec2(disk.u.dot(d), disk.v.dot(d));
    const double rho = foot[i].norm();
    rim_gap[i] = std::max(rho - disk.r, 0.0);
    inside &= rho <= disk.r;
  }
  const double lowest = std::min({a[0], a[1], a[2]}), highest = std::max({a[0], a[1], a[2]});
  const bool crosses = !(lowest > 0.0) && !(highest < 0.0);
  const double a_min = crosses ? 0.0 : std::min(std::abs(lowest), std::abs(highest));
  LeafToDisk answer;
  if (!std::isfinite(lowest) || !std::isfinite(highest)) return answer;  // bound 0
  if (inside) {
    answer.exact = true;
    answer.distance = answer.certified = a_min;
    if (!crosses) {
      int k = 0;
      for (int i = 1; i < 3; ++i) {
        if (std::abs(a[i]) < std::abs(a[k])) k = i;
      }
      answer.p_leaf = *vertices[k];
      answer.p_disk = disk.point(foot[k]);
      return answer;
    }
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      if (a[i] == 0.0) {
        answer.p_leaf = *vertices[i];
        break;
      }
      if ((a[i] < 0.0) != (a[j] < 0.0) || a[j] == 0.0) {
        const double t = a[i] / (a[i] - a[j]);
        answer.p_leaf = *vertices[i] + t * (*vertices[j] - *vertices[i]);
        break;
      }
    }
    answer.p_disk = answer.p_leaf;
    return answer;
  }
  if (crosses) {  // not every vertex over the disk: the section decides a meeting
    PlaneSection section;
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      section.addVertexOnPlane(a[i], foot[i].x(), foot[i].y());
      section.addEdge(a[i], foot[i].x(), foot[i].y(), a[j], foot[j].x(), foot[j].y());
    }
    if (const auto common = section.commonPointWithDisk(disk.r)) return meetingAt(disk, *common);
  }
  // (1), with rho_min the distance from the axis to the projected triangle.
  const double rho_gap = std::max(originToTriangle2(foot[0], foot[1], foot[2]) - disk.r, 0.0);
  double lower = std::sqrt(a_min * a_min + rho_gap * rho_gap);
  if (lower >= worth_below) {  // the traversal drops this leaf
    answer.distance = lower;
    return answer;
  }
  // The vertex nearest the disk.
  int k = 0;
  double nearest_squared[3];
  for (int i = 0; i < 3; ++i) {
    nearest_squared[i] = a[i] * a[i] + rim_gap[i] * rim_gap[i];
    if (nearest_squared[i] < nearest_squared[k]) k = i;
  }
  double upper = std::sqrt(nearest_squared[k]);
  Vec3 upper_disk = disk.point(disk.clampedToRim(foot[k]));
  Vec3 upper_triangle = *vertices[k];
  const auto least_along = [&](const Vec3& w) {
    return std::min({w.dot(p0), w.dot(p1), w.dot(p2)});
  };
  certifyAlongPair(disk, least_along, upper, upper_disk, upper_triangle, &lower);
  // The face: m its unit normal turned towards c. The bound takes the largest
  // m.p_i, so it holds when rounding leaves m off the normal of a sliver; the
  // upper bound measures to a convex combination of the vertices, a point of
  // the triangle whatever m is. Skipped when the traversal drops the leaf
  // already.
  const Vec3 normal = (p1 - p0).cross(p2 - p0);
  const double normal_squared = normal.squaredNorm();
  if (normal_squared > 0.0 && lower < worth_below) {
    Vec3 m = normal / std::sqrt(normal_squared);
    if (m.dot(disk.c - p0) < 0.0) m = -m;
    const Vec3 deepest = disk.lowestAlong(m);
    const double height = m.dot(deepest) - std::max({m.dot(p0), m.dot(p1), m.dot(p2)});
    if (height > 0.0) {
      lower = std::max(lower, height);
      // Barycentric coordinates of deepest's foot on the face.
      const Vec3 from0 = deepest - p0, from1 = deepest - p1, from2 = deepest - p2;
      const double w0 = (p2 - p1).cross(from1).dot(normal), w1 = (p0 - p2).cross(from2).dot(normal),
                   w2 = (p1 - p0).cross(from0).dot(normal);
      if (w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0) {
        const Vec3 on_face = (w0 * p0 + w1 * p1 + w2 * p2) / (w0 + w1 + w2);
        const double gap = (deepest - on_face).norm();
        if (gap < upper) {
          upper = gap;
          upper_disk = deepest;
          upper_triangle = on_face;
        }
      }
    }
  }
  if (edgesWorthTrying(lower, upper, scale, worth_below)) {
    // The edge to the nearer of the other vertices first.
    int first = (k + 1) % 3, second = (k + 2) % 3;
    if (nearest_squared[second] < nearest_squared[first]) std::swap(first, second);
    const Vec3& near = *vertices[k];
    const Vec3 edges[2][2] = {{near, *vertices[first]}, {near, *vertices[second]}};
    tryEdges(disk, edges, least_along, worth_below, &lower, &upper, &upper_disk, &upper_triangle);
  }
  return certifiedOrBound(lower, upper, upper_disk, upper_triangle, scale);
}

/// Scenes within this factor of 1 in size are solved in their own lengths by
/// triangleToDisk: its face test multiplies lengths to the fifth power, which
/// stays a normal double there.
constexpr double kTriangleUnscaledRange = 1e50;

/// The answer of triangleToDiskInUnits; for scenes outside
/// kTriangleUnscaledRange, with the triangle and the disk in lengths over a
/// power of two near `scale` (exact), scaled back (unscaled, at 1e-73 the
/// fifth powers underflow and the triangle's origin comes out certified as its
/// nearest point).
inline LeafToDisk triangleToDisk(const DiskInShape& disk, const Vec3& p0, const Vec3& p1,
                                 const Vec3& p2, double scale,
                                 double worth_below = std::numeric_limits<double>::infinity()) {
  if (scale >= 1.0 / kTriangleUnscaledRange && scale <= kTriangleUnscaledRange) {
    return triangleToDiskInUnits(disk, p0, p1, p2, scale, worth_below);
  }
  return inSceneUnits(disk, scale, [&](const DiskInShape& unit_disk, double to_unit,
                                       double unit_scale) {
    return triangleToDiskInUnits(unit_disk, p0 * to_unit, p1 * to_unit, p2 * to_unit, unit_scale,
                                 worth_below * to_unit);
  });
}

/// The least w.y over the box centre o, half-extents h: w.o - h.|w|.
inline double alignedBoxLeastAlong(const Vec3& o, const Vec3& h, const Vec3& w) {
  return w.dot(o) - h.dot(w.cwiseAbs());
}

/// The box's face normal to side * e_j (box centre o, half-extents h) against
/// the disk: the disk's point deepest towards it, that point's height over the
/// face's plane (> 0: the plane separates the sets by that much), whether it
/// lies beyond the plane over the face (then its foot on the face is the box's
/// point nearest the disk, at that height), and that foot.
struct BoxFaceGap {
  Vec3 deepest;
  double height;
  bool over_face;
  Vec3 foot;
};
inline BoxFaceGap boxFaceGap(const DiskInShape& disk, const Vec3& o, const Vec3& h, int j,
                             double side) {
  BoxFaceGap gap;
  gap.deepest = disk.lowestAlongAxis(j, side);
  gap.height = side * (gap.deepest[j] - o[j]) - h[j];
  const int k = (j + 1) % 3, l = (j + 2) % 3;
  gap.over_face = gap.height > 0.0 && std::abs(gap.deepest[k] - o[k]) <= h[k] &&
                  std::abs(gap.deepest[l] - o[l]) <= h[l];
  gap.foot = gap.deepest;
  gap.foot[j] = o[j] + side * h[j];
  return gap;
}

/// Where the segment from a to b crosses the disk's plane within the rim, in
/// in-plane coordinates: a common point of the segment and the disk. None if
/// it does not (a segment lying in the plane is tried at a only).
inline std::optional<Vec2> segmentCrossingWithinRim(const DiskInShape& disk, const Vec3& a,
                                                    const Vec3& b) {
  const double z_a = disk.n.dot(a - disk.c), z_b = disk.n.dot(b - disk.c);
  if (!((z_a <= 0.0 && z_b >= 0.0) || (z_a >= 0.0 && z_b <= 0.0))) return std::nullopt;
  const double t = z_a != z_b ? z_a / (z_a - z_b) : 0.0;
  const Vec2 s = disk.inPlane(a + t * (b - a) - disk.c);
  if (!(s.squaredNorm() <= disk.r * disk.r)) return std::nullopt;
  return s;
}

/// A common point of the disk and the box's face normal to e_j (box centre o,
/// half-extents h), in in-plane coordinates, given a disk point m on the
/// face's plane: the disk meets that plane along the chord through m whose
/// in-plane direction (-v_j, u_j) keeps y_j constant; the middle of the
/// chord's stretch within the face's rectangle (both other slabs), if the
/// stretch is not empty. None when it is, or when the disk is parallel to the
/// plane (no chord).
inline std::optional<Vec2> faceChordWithinRim(const DiskInShape& disk, const Vec3& o,
                                              const Vec3& h, int j, const Vec3& m) {
  const Vec2 s_m = disk.inPlane(m - disk.c);
  const Vec2 along(-disk.v[j], disk.u[j]);
  const auto chord = stretchWithinRim(disk, s_m, along);
  if (!chord) return std::nullopt;
  auto [low, high] = *chord;
  for (const int k : {(j + 1) % 3, (j + 2) % 3}) {  // clip to |y_k - o_k| <= h_k
    const double rate = disk.u[k] * along.x() + disk.v[k] * along.y();
    const double start = m[k] - o[k];
    if (rate == 0.0) {
      if (!(std::abs(start) <= h[k])) return std::nullopt;
      continue;
    }
    const double t0 = (-h[k] - start) / rate, t1 = (h[k] - start) / rate;
    low = std::max(low, std::min(t0, t1));
    high = std::min(high, std::max(t0, t1));
  }
  if (!(low <= high)) return std::nullopt;
  return Vec2(s_m + (0.5 * (low + high)) * along);
}

/// The axis-aligned box centre o, half-extents h (frame of the disk's
/// DiskInShape) against the disk by its nearest feature, found by projection:
/// q = proj_box(c) and p = the disk point nearest q (q's foot on the disk's
/// plane, clamped to the rim). The slabs |x_i - o_i| <= h_i that p lies
/// outside name the feature of the box nearest p, which is solved in closed
/// form:
///  * none: p is a common point (distance 0, p as both points);
///  * one, e_j: the face turned towards p. The disk's point deepest towards it
///    (lowestAlongAxis), if it lies over the face, is the nearest disk point and
///    its height over the face the distance (the face's plane separates the
///    sets); if it lies beyond the face's rectangle, the feature of that point
///    is taken instead, once; if it reaches the face's plane, the disk's chord
///    in that plane meets the face at a common point (faceChordWithinRim), or
///    not exact;
///  * two: the edge along the third axis at p's side of the other two
///    (segmentToDisk); an overlap leaves its certificate open, and the edge's
///    crossing of the disk's plane within the rim is a common point
///    (segmentCrossingWithinRim);
///  * three: the corner at p's side, and its nearest disk point.
/// An edge's or a corner's pair is exact when the certificate along its
/// direction closes within kShapeGapTolerance of the scene (certifiedOrBound).
/// Not exact means only "not settled here": alignedBoxToDisk then sweeps the
/// corners. `scale`: the solver's, r + |h| + |c - o|.
inline LeafToDisk alignedBoxToDiskByNearestFeature(const DiskInShape& disk, const Vec3& o,
                                                   const Vec3& h, double scale) {
  const LeafToDisk not_settled;
  const Vec3 q = (disk.c - o).cwiseMax(-h).cwiseMin(h) + o;
  Vec3 p = disk.point(disk.nearest(q));
  // A face whose deepest disk point lies beyond its rectangle hands that point
  // on to the edge or corner it lies over (one more pass).
  for (int pass = 0; pass < 2; ++pass) {
    const Vec3 offset = p - o;
    Vec3 side;
    int outside_count = 0, outside_axis = 0, inside_axis = 0;
    for (int i = 0; i < 3; ++i) {
      side[i] = offset[i] < 0.0 ? -1.0 : 1.0;
      if (std::abs(offset[i]) > h[i]) {
        ++outside_count;
        outside_axis = i;
      } else {
        inside_axis = i;
      }
    }
    if (!std::isfinite(offset.sum() + h.sum())) return not_settled;
    if (outside_count == 0) {
      LeafToDisk answer;
      answer.exact = true;
      answer.p_disk = answer.p_leaf = p;
      return answer;
    }
    const auto least_along = [&](const Vec3& w) { return alignedBoxLeastAlong(o, h, w); };
    const auto certified = [&](double upper, const Vec3& p_disk, const Vec3& p_box) {
      return certifiedAlongItself(disk, least_along, upper, p_disk, p_box, scale);
    };
    if (outside_count == 3) {
      const Vec3 corner = o + side.cwiseProduct(h);
      // On the first pass p is already the disk point nearest q, and q is
      // this corner when the centre lies beyond its three faces.
      const Vec3 p_disk = pass == 0 && corner == q ? p : disk.point(disk.nearest(corner));
      return certified((corner - p_disk).norm(), p_disk, corner);
    }
    if (outside_count == 2) {
      const int i = inside_axis;
      Vec3 from = o + side.cwiseProduct(h), to = from;
      from[i] = o[i] - h[i];
      to[i] = o[i] + h[i];
      const SegmentToDisk edge = segmentToDisk(disk, from, to);
      if (LeafToDisk by_edge = certifiedSegmentPair(disk, least_along, edge, scale);
          by_edge.exact) {
        return by_edge;
      }
      if (const auto common = segmentCrossingWithinRim(disk, from, to)) return meetingAt(disk, *common);
      return not_settled;
    }
    const int j = outside_axis;
    const BoxFaceGap face = boxFaceGap(disk, o, h, j, side[j]);
    if (!(face.height > 0.0)) {
      // p lies beyond the face's plane, the deepest point on or inside it:
      // the segment between them crosses the plane at m.
      const double p_height = side[j] * (p[j] - o[j]) - h[j];
      const Vec3 m = p + (p_height / (p_height - face.height)) * (face.deepest - p);
      if (const auto common = faceChordWithinRim(disk, o, h, j, m)) return meetingAt(disk, *common);
      return not_settled;
    }
    if (face.over_face) {
      LeafToDisk answer;
      answer.exact = true;
      answer.distance = answer.certified = face.height;
      answer.p_disk = face.deepest;
      answer.p_leaf = face.foot;
      return answer;
    }
    p = face.deepest;
  }
  return not_settled;
}

/// The axis-aligned box centre o, half-extents h (frame of the disk's
/// DiskInShape) against the disk: by its nearest feature where that settles it
/// (alignedBoxToDiskByNearestFeature); else as triangleToDisk: exact by (1) when every
/// corner projects into the disk (the first corner of least |a| in the order
/// x fastest, - before +; a crossing: the point where a vanishes on the segment
/// from the lowest to the highest corner); else the certificate on the
/// direction from the nearest corner to its nearest disk point, and on the
/// normals of the three faces turned towards c (upper bounds: that corner's
/// distance; a face's height over the disk when the disk's point deepest
/// towards it lies over the face), the answer when within kShapeGapTolerance
/// of the scene; else the same with the candidates of the three edges at the
/// nearest corner (tryEdges); else the largest lower bound, with
/// diskBoxLowerBound's.
/// `scale`: the solver's, r + |h| + |c - o|; `worth_below`: tryEdges'.
inline LeafToDisk alignedBoxToDisk(const DiskInShape& disk, const Vec3& o, const Vec3& h,
                                   double scale,
                                   double worth_below = std::numeric_limits<double>::infinity()) {
  if (LeafToDisk by_feature = alignedBoxToDiskByNearestFeature(disk, o, h, scale);
      by_feature.exact) {
    return by_feature;
  }
  LeafToDisk answer;
  const Vec3 d = o - disk.c;
  const double a_o = disk.n.dot(d), x_o = disk.u.dot(d), y_o = disk.v.dot(d);
  // Corner k = o + (s_0 h_0, s_1 h_1, s_2 h_2), s_i = bit i of k ? + : -. Its
  // height a and in-plane x, y: the centre's plus the steps along e_0, e_1
  // (four sums, shared by both signs of s_2) plus the step along e_2.
  const Vec3 a_step = disk.n.cwiseProduct(h), x_step = disk.u.cwiseProduct(h),
             y_step = disk.v.cwiseProduct(h);
  double a[8], x[8], y[8];
  for (int k = 0; k < 4; ++k) {
    const double s0 = (k & 1) ? 1.0 : -1.0, s1 = (k & 2) ? 1.0 : -1.0;
    const double a01 = s0 * a_step[0] + s1 * a_step[1], x01 = s0 * x_step[0] + s1 * x_step[1],
                 y01 = s0 * y_step[0] + s1 * y_step[1];
    a[k] = (a_o - a_step[2]) + a01, a[k + 4] = (a_o + a_step[2]) + a01;
    x[k] = (x_o - x_step[2]) + x01, x[k + 4] = (x_o + x_step[2]) + x01;
    y[k] = (y_o - y_step[2]) + y01, y[k + 4] = (y_o + y_step[2]) + y01;
  }
  bool inside = true;
  int lowest = 0, highest = 0, nearest = 0;
  double nearest_squared = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 8; ++k) {
    const double rho = std::sqrt(x[k] * x[k] + y[k] * y[k]);
    inside &= rho <= disk.r;
    const double rim_gap = std::max(rho - disk.r, 0.0);
    const double squared = a[k] * a[k] + rim_gap * rim_gap;
    if (squared < nearest_squared) nearest_squared = squared, nearest = k;
    if (a[k] < a[lowest]) lowest = k;
    if (a[k] > a[highest]) highest = k;
  }
  if (!std::isfinite(a[lowest]) || !std::isfinite(a[highest]) ||
      !std::isfinite(nearest_squared)) {
    return answer;  // bound 0
  }
  const auto corner = [&](int k) {
    return Vec3(o.x() + ((k & 1) ? h.x() : -h.x()), o.y() + ((k & 2) ? h.y() : -h.y()),
                o.z() + ((k & 4) ? h.z() : -h.z()));
  };
  const bool crosses = !(a[lowest] > 0.0) && !(a[highest] < 0.0);
  if (inside) {
    answer.exact = true;
    if (crosses) {
      const double t = a[highest] > a[lowest] ? a[highest] / (a[highest] - a[lowest]) : 0.0;
      answer.p_leaf = corner(highest) + t * (corner(lowest) - corner(highest));
      answer.p_disk = answer.p_leaf;
      answer.distance = answer.certified = 0.0;
      return answer;
    }
    const int k = a[lowest] > 0.0 ? lowest : highest;
    answer.distance = answer.certified = std::abs(a[k]);
    answer.p_leaf = corner(k);
    answer.p_disk = disk.point(Vec2(x[k], y[k]));
    return answer;
  }
  if (crosses) {  // not every corner over the disk: the section decides a meeting
    PlaneSection section;
    for (int k = 0; k < 8; ++k) {
      section.addVertexOnPlane(a[k], x[k], y[k]);
      for (int i = 0; i < 3; ++i) {  // the edge to the corner with bit i set
        const int l = k | (1 << i);
        if (l != k) section.addEdge(a[k], x[k], y[k], a[l], x[l], y[l]);
      }
    }
    if (const auto common = section.commonPointWithDisk(disk.r)) return meetingAt(disk, *common);
  }
  double lower = diskAlignedBoxLowerBound(disk, o, h);
  // The nearest corner.
  double upper = std::sqrt(nearest_squared);
  Vec3 upper_box = corner(nearest);
  Vec3 upper_disk = disk.point(disk.clampedToRim(Vec2(x[nearest], y[nearest])));
  const auto least_along = [&](const Vec3& w) { return alignedBoxLeastAlong(o, h, w); };
  certifyAlongPair(disk, least_along, upper, upper_disk, upper_box, &lower);
  // The faces turned towards c: normal m = sign(c_j - o_j) e_j.
  for (int j = 0; j < 3; ++j) {
    const BoxFaceGap face = boxFaceGap(disk, o, h, j, disk.c[j] < o[j] ? -1.0 : 1.0);
    if (!(face.height > 0.0)) continue;
    lower = std::max(lower, face.height);
    if (face.over_face && face.height < upper) {
      upper = face.height;
      upper_disk = face.deepest;
      upper_box = face.foot;
    }
  }
  if (edgesWorthTrying(lower, upper, scale, worth_below)) {
    const Vec3 from = corner(nearest);
    const Vec3 edges[3][2] = {
        {from, corner(nearest ^ 1)}, {from, corner(nearest ^ 2)}, {from, corner(nearest ^ 4)}};
    tryEdges(disk, edges, least_along, worth_below, &lower, &upper, &upper_disk, &upper_box);
  }
  return certifiedOrBound(lower, upper, upper_disk, upper_box, scale);
}

/// The largest magnitude a triangle bound is computed from, but for the
/// disk's share.
inline double triangleBoundMagnitude(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  return std::max({p0.cwiseAbs().maxCoeff(), p1.cwiseAbs().maxCoeff(), p2.cwiseAbs().maxCoeff()});
}

}  // namespace internal
}  // namespace fcl_disk
