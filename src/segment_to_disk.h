// Internal: the pair of nearest points of a disk and a segment, by a 1D convex
// minimisation along the segment. The closed forms of the box, the triangle
// and the capsule (src/environment_bounds.h, src/pairs/disk_capsule.cpp) take
// it as their candidate for the rim or the face against an edge, and certify
// it with their own support function. docs/disk_shape_distance.md, section 4,
// "The segment solver".
//
// Frame, units: the disk's DiskInShape frame (centre c, orthonormal in-plane
// axes u, v, normal n, radius r) and its lengths. The segment is
// s(t) = a + t (b - a), t in [0, 1]. With z(t) = n.(s - c) and
// (x(t), y(t)) = (u.(s - c), v.(s - c)), all linear in t, and
// rho = |(x, y)|,
//   g(t) = dist(s(t), disk)^2 / 2 = (z^2 + max(rho - r, 0)^2) / 2,
//   g'(t) = z z' + max(rho - r, 0) (x x' + y y') / rho,
//   g''(t) = z'^2 + [rho > r] ((1 - r / rho) (x'^2 + y'^2) + (r / rho) rho'^2),
// rho' = (x x' + y y') / rho. g'' >= 0: g is convex and C^1 (g'' jumps where
// rho = r), so its minimiser over [0, 1] is an end where g' points outward, or
// the root of g' inside. The segment's stretch over the disk's face, where
// rho^2 = A t^2 + 2 B t + C <= r^2 (A = x'^2 + y'^2, B = x0 x' + y0 y',
// C = x0^2 + y0^2, between the roots of the quadratic), has g = z^2 / 2: where
// g' changes sign across it the root is -z0 / z' in closed form, clamped to
// it. Else the root lies on one side of it, where g is smooth, and Newton's
// method finds it, kept in the bracket where g' changes sign (bisection when a
// step leaves it).
//
// Guarantee: none by itself. The answer is a pair of points, one on each set,
// so its distance is an upper bound; callers certify it with the duality
// bound dist >= min_X w.y - h_K(w) along certificateDirection() (s - p, with
// its component along the segment dropped where t is inside (0, 1)) and keep
// it only when the two meet within kShapeGapTolerance of the scene.
// Precision: the iteration stops where a point eps off the optimum costs that
// certificate O(scale (eps / d)^2), under 1e-14 of the scene
// (kSegmentStepOverDistance); along s - p itself it would cost
// O(eps |b - a| / d), first order, as X's least w.y has a kink at the optimal
// w (normal to the segment, where its ends tie), and so would need t to the
// last bits.
// Degenerate cases: a zero-length segment is its point (t = 0); a segment
// meeting the disk gives distance 0 with s = p up to rounding (nothing to
// certify: callers decide meetings otherwise). Ties: where g is flat (a
// segment parallel to the disk, over its face) the start of the stretch over
// the face.
#pragma once

#include <algorithm>
#include <cmath>

#include "disk_shape_solver.h"

namespace fcl_disk {
namespace internal {

/// A Newton step in t below this ends the iteration once taken: Newton's
/// error after a step s is about M s^2 (M = |g'''| / (2 g''), of order 1 for
/// t in [0, 1]), so ~1e-18 here, under double's rounding of t.
constexpr double kSegmentNewtonStepTolerance = 1e-9;
/// So does a step s with s^2 |b - a| <= this times the distance d at t: the
/// point is then off the optimum by about eps = M s^2 |b - a| <= 1e-9 M d,
/// which lengthens the pair by O(eps^2 / d) and turns its direction in the
/// plane normal to the segment by O(eps / d), costing the certificate along
/// certificateDirection() O(scale (eps / d)^2), 1e-18 M^2 of the scene. Away
/// from contact it ends the iteration a step before the absolute tolerance
/// (test/test_disk_shape_cases.cpp, EdgePairsSettleInClosedForm).
constexpr double kSegmentStepOverDistance = 1e-9;
/// A bisection step in t below this ends it (bisection gains one bit per
/// step): a few ulps of t in [0, 1].
constexpr double kSegmentStepTolerance = 4 * std::numeric_limits<double>::epsilon();
/// The iteration's quantities reach the fifth power of lengths (the Newton
/// step's rho^3 g''): lengths outside this range (scenes beyond 1e50 or under
/// 1e-50 of the caller's unit) are first divided by the largest of them, so
/// that those powers stay normal doubles (t does not depend on the unit).
constexpr double kSegmentUnitRangeLow = 1e-50, kSegmentUnitRangeHigh = 1e50;
/// A cap on the iterations: Newton converges in a handful; bisection halves
/// the bracket each time, so 64 steps reach the tolerance from any bracket.
constexpr int kMaxSegmentIterations = 64;

struct SegmentToDisk {
  double t = 0.0;
  double distance = 0.0;  ///< |p_segment - p_disk|
  Vec3 p_disk{Vec3::Zero()}, p_segment{Vec3::Zero()};
  Vec3 along{Vec3::Zero()};          ///< b - a
  double inverse_along_squared = 0;  ///< 1 / |b - a|^2 (0 for a = b), off the query's chain

  /// The direction to certify the pair along: p_segment - p_disk, less its
  /// component along the segment where t is inside (0, 1). There the optimal
  /// separation is normal to the segment, and the certificate is smooth in
  /// the directions normal to it nearby, along which every point of the
  /// segment is equally low (see the header's Precision). Not normalised
  /// (of the separation's size); zero when the points meet.
  Vec3 certificateDirection() const {
    const Vec3 separation = p_segment - p_disk;
    if (!(t > 0.0 && t < 1.0)) return separation;
    return separation - (separation.dot(along) * inverse_along_squared) * along;
  }
};

/// The pair of nearest points of the disk and the segment a b (see above).
inline SegmentToDisk segmentToDisk(const DiskInShape& disk, const Vec3& a, const Vec3& b) {
  const Vec3 from_centre = a - disk.c, step = b - a;
  const Vec2 planar_from_centre(disk.u.dot(from_centre), disk.v.dot(from_centre));
  const Vec2 planar_step(disk.u.dot(step), disk.v.dot(step));
  // The iteration's lengths, in the caller's unit unless kSegmentUnitRange*
  // says otherwise.
  double z0 = disk.n.dot(from_centre), x0 = planar_from_centre.x(), y0 = planar_from_centre.y();
  double dz = disk.n.dot(step), dx = planar_step.x(), dy = planar_step.y();
  double radius = disk.r;
  const double extent = std::max({std::abs(z0), std::abs(x0), std::abs(y0), std::abs(dz),
                                  std::abs(dx), std::abs(dy), radius});
  if (extent > 0.0 && !(extent >= kSegmentUnitRangeLow && extent <= kSegmentUnitRangeHigh)) {
    const double unit = 1.0 / extent;
    z0 *= unit, x0 *= unit, y0 *= unit, dz *= unit, dx *= unit, dy *= unit, radius *= unit;
  }
  const double planar_squared = dx * dx + dy * dy;
  const double length_squared = planar_squared + dz * dz;
  // g'(t).
  const auto slope = [&](double t) {
    const double z = z0 + t * dz, x = x0 + t * dx, y = y0 + t * dy;
    const double rho = std::sqrt(x * x + y * y);
    const double rim_gap = rho - radius;
    return rim_gap > 0.0 ? z * dz + rim_gap * (x * dx + y * dy) / rho : z * dz;
  };
  // Newton's step -g'/g'' at t, and g' times a positive factor (its sign keeps
  // the bracket). Off the face (rho > r), with m = x x' + y y' = rho rho',
  //   rho g' = z z' rho + (rho - r) m,   rho^3 g'' = z'^2 rho^3 + (rho - r) A rho^2 + r m^2,
  // and the step is -rho^2 (rho g') / (rho^3 g''): one division after the
  // square root on the iteration's chain, where g' and g'' take two.
  struct NewtonStep {
    double scaled_slope, step, distance_squared;  // distance_squared = 2 g(t)
  };
  const auto newtonStep = [&](double t) {
    const double z = z0 + t * dz, x = x0 + t * dx, y = y0 + t * dy;
    const double rho_squared = x * x + y * y;
    const double rho = std::sqrt(rho_squared);
    const double rim_gap = rho - radius;
    if (!(rim_gap > 0.0)) return NewtonStep{z * dz, -(z * dz) / (dz * dz), z * z};
    const double m = x * dx + y * dy;
    const double scaled_slope = z * dz * rho + rim_gap * m;
    const double scaled_curvature =
        (dz * dz * rho + rim_gap * planar_squared) * rho_squared + radius * m * m;
    return NewtonStep{scaled_slope, -rho_squared * scaled_slope / scaled_curvature,
                      z * z + rim_gap * rim_gap};
  };

  double t;
  const double slope_low = slope(0.0);
  const double slope_high = slope(1.0);
  if (!(slope_low < 0.0)) {
    t = 0.0;
  } else if (!(slope_high > 0.0)) {
    t = 1.0;
  } else {
    // g'(low) < 0 < g'(high).
    double low = 0.0, high = 1.0, slope_at_low = slope_low, slope_at_high = slope_high;
    bool over_face = false;
    // The stretch over the face, [t_in, t_out] within [0, 1]: the roots of
    // A t^2 + 2 B t + (C - r^2), the larger-magnitude one first (no
    // cancellation).
    const double B = x0 * dx + y0 * dy, C_minus_r2 = x0 * x0 + y0 * y0 - radius * radius;
    const double discriminant = B * B - planar_squared * C_minus_r2;
    if (planar_squared > 0.0 && discriminant >= 0.0) {
      const double root = std::sqrt(discriminant);
      const double k = B < 0.0 ? root - B : -(B + root);
      const double t_k = k / planar_squared, t_other = k != 0.0 ? C_minus_r2 / k : t_k;
      const double t_in = std::max(std::min(t_k, t_other), 0.0);
      const double t_out = std::min(std::max(t_k, t_other), 1.0);
      if (t_in < t_out) {
        const double slope_in = t_in > 0.0 ? slope(t_in) : slope_low;
        const double slope_out = t_out < 1.0 ? slope(t_out) : slope_high;
        if (slope_in > 0.0) {
          high = t_in, slope_at_high = slope_in;
        } else if (slope_out < 0.0) {
          low = t_out, slope_at_low = slope_out;
        } else {  // g = z^2 / 2 there: its root, or any t where z' = 0
          t = dz != 0.0 ? std::clamp(-z0 / dz, t_in, t_out) : t_in;
          over_face = true;
        }
      }
    }
    if (!over_face) {
      t = low + (high - low) * (slope_at_low / (slope_at_low - slope_at_high));  // g' interpolated
      for (int iteration = 0; iteration < kMaxSegmentIterations; ++iteration) {
        const NewtonStep at = newtonStep(t);
        if (at.scaled_slope == 0.0) break;
        (at.scaled_slope < 0.0 ? low : high) = t;
        const double next = t + at.step;
        if (next > low && next < high) {
          // s^2 |b - a| <= k d, squared: no square root.
          const double taken = (next - t) * (next - t);
          const bool converged =
              std::abs(next - t) <= kSegmentNewtonStepTolerance ||
              taken * taken * length_squared <=
                  kSegmentStepOverDistance * kSegmentStepOverDistance * at.distance_squared;
          t = next;
          if (converged) break;
        } else if (std::abs(next - t) <= kSegmentStepTolerance) {
          // Converged onto the bracket's end it just set, by rounding.
          t = std::clamp(next, low, high);
          break;
        } else {
          const double middle = 0.5 * (low + high);
          const bool converged = std::abs(middle - t) <= kSegmentStepTolerance;
          t = middle;
          if (converged) break;
        }
      }
    }
  }
  SegmentToDisk answer;
  answer.t = t;
  answer.p_segment = a + t * step;
  answer.p_disk = disk.point(
      disk.clampedToRim(planar_from_centre + t * planar_step));
  answer.distance = (answer.p_segment - answer.p_disk).norm();
  answer.along = step;
  const double along_squared = step.squaredNorm();
  answer.inverse_along_squared = along_squared > 0.0 ? 1.0 / along_squared : 0.0;
  return answer;
}

}  // namespace internal
}  // namespace fcl_disk
