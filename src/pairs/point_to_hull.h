// Internal: the simplex of a point set's convex hull nearest a point y (one,
// two or three of the set's points, whose hull holds y's nearest point), by
// the Gilbert-Johnson-Keerthi iteration: it reads only the set's support (the
// index of a point most along a direction), nothing of the hull's faces
// (docs/disk_shape_distance.md, section 4, "Convex").
//
// Frame: the set's own; lengths in its units. Guarantee: none beyond a
// feasible point of the hull (a convex combination of the simplex's points)
// and, where `inside()`, y within a tetrahedron of the set's points whose
// faces' orientations are signed beyond their rounding. The caller certifies
// what it builds from the simplex (ConvexTraits::closedFormBySupport), so a
// simplex stopped short by rounding only costs it a pass. Ties: the
// support's (its first point); the simplex's regions are tested in a fixed
// order, so the answer depends only on the points and y.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <utility>

#include "../disk_shape_solver.h"

namespace fcl_disk {
namespace internal {

/// The iteration stops when the support point along -v (v = q - y, q the
/// simplex's point nearest y), w relative to y, leaves |v|^2 - v.w, which
/// bounds |v|^2 - dist(y, hull)^2 from above, below this fraction of |v|^2:
/// q's feature no longer changes then but for ties at rounding, and the
/// caller's certificate, not this test, decides the answer.
constexpr double kHullSimplexProgress = 1e-13;
/// Steps before the iteration gives up on a point set whose rounding makes it
/// cycle: each step adds a point the simplex did not hold, and the hull's
/// nearest simplex is reached in a few.
constexpr int kMaxHullSimplexSteps = 48;
/// The rounding of a face orientation (a - y).((b - a) x (c - a)), relative
/// to |a - y| |b - a| |c - a|: a few eps for its products and sums, doubled.
constexpr double kSimplexOrientationRounding = 32 * std::numeric_limits<double>::epsilon();

/// A simplex of the set's points, relative to y.
struct HullSimplex {
  int count = 0;                 ///< 1-3 points; 4: y inside a tetrahedron of them
  std::array<int, 4> index{};    ///< the points' indices in the set
  /// point - y
  std::array<Vec3, 4> relative{{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()}};
  Vec3 v{Vec3::Zero()};          ///< the simplex's point nearest y, minus y
  bool inside() const { return count == 4; }
};

namespace hull_simplex {

/// Keeps the listed points of `s`, in that order, with v.
inline void keep(HullSimplex* s, std::initializer_list<int> which, const Vec3& v) {
  HullSimplex kept;
  for (const int k : which) {
    kept.index[kept.count] = s->index[k];
    kept.relative[kept.count] = s->relative[k];
    ++kept.count;
  }
  kept.v = v;
  *s = kept;
}

/// The point of the segment of points 0, 1 nearest the origin; the simplex
/// reduced to the points of its region.
inline void nearestOnSegment(HullSimplex* s) {
  const Vec3 a = s->relative[0], b = s->relative[1];
  const Vec3 ab = b - a;
  const double along = -a.dot(ab), length_squared = ab.squaredNorm();
  if (!(along > 0.0)) return keep(s, {0}, a);
  if (!(along < length_squared)) return keep(s, {1}, b);
  s->v = a + (along / length_squared) * ab;
}

/// The point of the triangle of points i, j, k nearest the origin, by its
/// Voronoi regions (Ericson, Real-Time Collision Detection, 5.1.5); the
/// simplex reduced to the points of its region (count 3: the face).
inline void nearestOnTriangle(HullSimplex* s, int i, int j, int k) {
  const Vec3 a = s->relative[i], b = s->relative[j], c = s->relative[k];
  const Vec3 ab = b - a, ac = c - a;
  const double d1 = -ab.dot(a), d2 = -ac.dot(a);
  if (d1 <= 0.0 && d2 <= 0.0) return keep(s, {i}, a);
  const double d3 = -ab.dot(b), d4 = -ac.dot(b);
  if (d3 >= 0.0 && d4 <= d3) return keep(s, {j}, b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return keep(s, {i, j}, a + (d1 / (d1 - d3)) * ab);
  const double d5 = -ab.dot(c), d6 = -ac.dot(c);
  if (d6 >= 0.0 && d5 <= d6) return keep(s, {k}, c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return keep(s, {i, k}, a + (d2 / (d2 - d6)) * ac);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    return keep(s, {j, k}, b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b));
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) {  // a sliver whose regions rounding left empty: its nearest edge
    HullSimplex best = *s;
    keep(&best, {i, j}, Vec3::Zero());
    nearestOnSegment(&best);
    for (const auto& [p, q] : {std::pair(i, k), std::pair(j, k)}) {
      HullSimplex trial = *s;
      keep(&trial, {p, q}, Vec3::Zero());
      nearestOnSegment(&trial);
      if (trial.v.squaredNorm() < best.v.squaredNorm()) best = trial;
    }
    *s = best;
    return;
  }
  keep(s, {i, j, k}, a + (vb / sum) * ab + (vc / sum) * ac);
}

/// Whether the origin lies on the side of the plane of points i, j, k where
/// point l lies, both beyond their orientation's rounding: only then is that
/// face left out of the search of a tetrahedron. A flat tetrahedron (four
/// coplanar vertices: the two triangles of a quadrilateral face) has point l
/// on every face's plane to rounding, on a side rounding picks; were that
/// side trusted, the origin off the plane could be found on the inner side of
/// all four faces, inside a tetrahedron of no volume (a fuzz_disk_shapes
/// input: a disk point 3.9e-5 off a hull taken as common).
inline bool clearlyInsideFace(const HullSimplex& s, int i, int j, int k, int l) {
  const Vec3& a = s.relative[i];
  const Vec3 ab = s.relative[j] - a, ac = s.relative[k] - a, al = s.relative[l] - a;
  const Vec3 normal = ab.cross(ac);
  const double origin_side = -normal.dot(a), point_side = normal.dot(al);
  const double rounding_per_length = kSimplexOrientationRounding * ab.norm() * ac.norm();
  const double origin_rounding = rounding_per_length * a.norm();
  const double point_rounding = rounding_per_length * al.norm();
  return (origin_side > origin_rounding && point_side > point_rounding) ||
         (origin_side < -origin_rounding && point_side < -point_rounding);
}

/// The point of the tetrahedron of points 0-3 nearest the origin: the nearest
/// of its faces the origin may lie beyond; the origin itself (count 4) when
/// it lies clearly inside every face.
inline void nearestOnTetrahedron(HullSimplex* s) {
  static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};
  HullSimplex best;
  bool found = false;
  for (const auto& f : kFaces) {
    if (clearlyInsideFace(*s, f[0], f[1], f[2], f[3])) continue;
    HullSimplex trial = *s;
    nearestOnTriangle(&trial, f[0], f[1], f[2]);
    if (!found || trial.v.squaredNorm() < best.v.squaredNorm()) best = trial, found = true;
  }
  if (found) {
    *s = best;
  } else {
    s->v = Vec3::Zero();
  }
}

inline void reduce(HullSimplex* s) {
  switch (s->count) {
    case 1: s->v = s->relative[0]; return;
    case 2: return nearestOnSegment(s);
    case 3: return nearestOnTriangle(s, 0, 1, 2);
    default: return nearestOnTetrahedron(s);
  }
}

}  // namespace hull_simplex

/// The simplex of the hull's point nearest y, from `start` (1-3 points, e.g.
/// the last query point's simplex; its relative points are recomputed).
/// `most_along(w)` returns the index of a point maximising w.x, `point(i)`
/// the point. Stops when the support no longer progresses
/// (kHullSimplexProgress), returns a point the simplex holds, or |v| stops
/// decreasing, when y is inside, or after kMaxHullSimplexSteps.
template <typename MostAlong, typename PointOf>
HullSimplex nearestHullSimplex(const Vec3& y, const HullSimplex& start, MostAlong&& most_along,
                               PointOf&& point) {
  HullSimplex s = start;
  for (int k = 0; k < s.count; ++k) s.relative[k] = point(s.index[k]) - y;
  hull_simplex::reduce(&s);
  for (int step = 0; step < kMaxHullSimplexSteps && !s.inside(); ++step) {
    const double v_squared = s.v.squaredNorm();
    if (!(v_squared > 0.0)) break;
    const int next = most_along(Vec3(-s.v));
    const Vec3 w = point(next) - y;
    if (v_squared - s.v.dot(w) <= kHullSimplexProgress * v_squared) break;
    bool held = false;
    for (int k = 0; k < s.count; ++k) held |= s.index[k] == next;
    if (held) break;
    HullSimplex grown = s;
    grown.index[grown.count] = next;
    grown.relative[grown.count] = w;
    ++grown.count;
    hull_simplex::reduce(&grown);
    if (!grown.inside() && !(grown.v.squaredNorm() < v_squared)) break;
    s = grown;
  }
  return s;
}

}  // namespace internal
}  // namespace fcl_disk
