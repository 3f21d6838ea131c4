// Internal: the generic certified solver for a disk against a convex set X, given
// X's projection and support in the disk's frame. Derivation and notation:
// docs/disk_shape_distance.md (psi, g, H, the certificate g(w), inflation rho).
//
// Frame D: the disk is {(s, 0) : |s| <= r}, s in R^2, centre at the origin, normal
// +Z. Everything is in double, relative to the disk's centre.
//
// A Target (the convex set X, posed in D) provides
//   Projection project(const Vec3& x) const;  // q = proj_X(x), and psi's Hessian
//   Vec3 support(const Vec3& w) const;        // a point of X maximising w.y
// and the solver works on X inflated by `rho` >= 0 (a sphere is a point
// inflated, a capsule a segment): dist(x, X + B_rho) = max(dist(x, X) - rho, 0).
#pragma once

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "fcl_disk/disk_shape_distance.h"
#include "pair_in_frame1.h"

namespace fcl_disk {
namespace internal {

using Mat2 = Eigen::Matrix2d;

/// proj_X(x) and the Hessian of psi_3(x) = dist(x, X)^2 / 2 there, I - D proj_X(x)
/// (symmetric, 0 <= H <= I; 0 inside X). Where proj_X is not differentiable
/// (region boundaries) either side's Hessian will do: the solver's line search
/// and certificate do not rely on it, only its speed does.
struct Projection {
  Vec3 q;
  Mat3 hessian;
};

/// What the solver is asked: the distance, or only whether the sets meet (which
/// may stop as soon as either answer is proven).
enum class SolverGoal { distance, intersection };

struct DiskShapeSolution {
  Vec3 p{Vec3::Zero()};   ///< point of the disk, frame D.
  Vec3 q{Vec3::Zero()};   ///< point of X + B_rho, frame D.
  double distance{0};     ///< |q - p|; 0 with p == q when the sets meet.
  double lower_bound{0};  ///< the certificate, <= the true distance.
  int iterations{0};
  bool intersecting{false};
};

// ---------------------------------------------------------------------------
// Tolerances (relative to scale: the problem is homogeneous in length, so the
// solver behaves the same at every length scale).

/// The iteration stops when the certified gap |q - p| - g is below this many
/// scene sizes: 45 ulps, under the 1e-12 promise and above the rounding noise of
/// evaluating both bounds (the disk-disk solver's kGapTolerance).
constexpr double kShapeGapTolerance = 1e-14;
/// Closer than this many scene sizes counts as touching for the intersection
/// goal (the disk-disk intersection test's tolerance).
constexpr double kShapeTouchingTolerance = kTouchingTolerance;
/// The rounding of the gradient (x - q)_xy, relative to scale: x and q carry
/// a few ulps of scale each.
constexpr double kShapeGradientRounding = 8 * std::numeric_limits<double>::epsilon();
/// Iteration cap. Converged pairs need 1-6 (Newton on a piecewise quadratic or
/// smooth psi); the cap only bounds the work on flat, degenerate optima, whose
/// answer the certificate then qualifies.
constexpr int kMaxShapeIterations = 40;
/// A point within this relative distance of the rim counts as on it.
constexpr double kShapeOnRim = 4 * std::numeric_limits<double>::epsilon();
/// Rim Newton is tried while the gradient points inwards by less than this
/// fraction of its length (rounding noise on a nearly tangential gradient).
constexpr double kShapeInwardGradient = 1e-3;
/// Largest turn of one rim Newton step, and halvings before the model step.
constexpr double kShapeMaxRimStep = 1.5707963267948966;  // pi / 2
constexpr int kShapeMaxRimHalvings = 8;
/// Tikhonov term of the disk-constrained model step, relative to trace(H) (plus
/// an absolute floor relative to the curvature scale 1): only pins the step along
/// psi's flat directions.
constexpr double kShapeModelRegularisation = 1e-10;
/// Line search: regula falsi on psi' to this flatness/resolution, at most this
/// many evaluations.
constexpr int kShapeLineSearchSteps = 60;
constexpr double kShapeLineSearchFlatness = 1e-6;
constexpr double kShapeLineSearchResolution = 1e-15;
/// The multiplier of the disk-constrained model step, found to this relative
/// accuracy within this many secant/bisection steps.
constexpr double kShapeSecularTolerance = 1e-15;
constexpr int kShapeSecularIterations = 48;
/// psi decreasing by less than this many scale^2 in a step: the rounding floor.
constexpr double kShapeStagnation = 4 * std::numeric_limits<double>::epsilon() *
                                    std::numeric_limits<double>::epsilon();

// ---------------------------------------------------------------------------

/// psi at the disk point s, with what the iteration needs.
struct ShapeIterate {
  Vec2 s;
  Vec3 q;        ///< proj_X(x), x = (s, 0).
  double psi;    ///< |x - q|^2 / 2.
  Vec2 gradient; ///< (x - q)_xy.
  Mat3 hessian3; ///< X's psi Hessian at x, frame D.
  Mat2 hessian;  ///< its top-left 2x2 block: psi's Hessian over the disk.
};

template <typename Target>
ShapeIterate evaluateAt(const Target& target, const Vec2& s) {
  const Vec3 x(s.x(), s.y(), 0.0);
  const Projection projection = target.project(x);
  const Vec3 residual = x - projection.q;
  return ShapeIterate{s, projection.q, 0.5 * residual.squaredNorm(), residual.head<2>(),
                      projection.hessian, projection.hessian.template topLeftCorner<2, 2>()};
}

/// The certificate g(w) = min_{y in X + B_rho} w.y - max_{k in disk} w.k
///                      = w.support(-w) - rho|w| - r|w_xy|
/// for any w (positively homogeneous: divided by |w| here), a lower bound of
/// the distance (docs/disk_shape_distance.md, section 2).
template <typename Target>
double certificateAlong(const Target& target, double r, double rho, const Vec3& w) {
  const double length = w.norm();
  if (!(length > 0.0)) return 0.0;
  const double lowest = w.dot(target.support(-w));
  return (lowest - r * std::sqrt(w.x() * w.x() + w.y() * w.y())) / length - rho;
}

/// The best of the certificate at the disk normals (where g has its kink for a
/// disk, so face optima are certified there), along the separation q - x and,
/// while the gap to `distance` is still above `gap_tolerance`, along
/// H3 (q - x): X's psi Hessian at x keeps the components of q - x normal to
/// the feature of X that q lies on (a face's normal, the plane normal to an
/// edge) and drops the rest, which for small distances is rounding (q - x knows
/// its direction only to about eps * scale / d).
template <typename Target>
double certificateAt(const Target& target, double r, double rho, const Vec3& x, const Vec3& q,
                     const Mat3& hessian3, double distance, double gap_tolerance) {
  double best = std::max(certificateAlong(target, r, rho, Vec3::UnitZ()),
                         certificateAlong(target, r, rho, -Vec3::UnitZ()));
  const Vec3 separation = q - x;
  best = std::max(best, certificateAlong(target, r, rho, separation));
  if (distance - best > gap_tolerance) {
    best = std::max(best, certificateAlong(target, r, rho, hessian3 * separation));
  }
  return std::max(best, 0.0);
}

/// Minimiser over alpha in (0, 1] of psi(s + alpha step), by regula falsi
/// (Illinois) on psi', which is monotone (psi is convex along the line): finds
/// the kinks of psi'' where the step crosses between regions of X's projection.
template <typename Target>
Vec2 shapeLineSearch(const Target& target, const ShapeIterate& at, const Vec2& step, double slope,
                     ShapeIterate* at_end) {
  ShapeIterate next = evaluateAt(target, at.s + step);
  double derivative_hi = next.gradient.dot(step);
  double alpha = 1.0;
  if (derivative_hi > 0.0) {
    double lo = 0.0, hi = 1.0, derivative_lo = slope;
    ShapeIterate at_lo = at;
    int last_side = 0;
    for (int k = 0; k < kShapeLineSearchSteps; ++k) {
      alpha = (lo * derivative_hi - hi * derivative_lo) / (derivative_hi - derivative_lo);
      if (!(alpha > lo && alpha < hi)) alpha = 0.5 * (lo + hi);
      next = evaluateAt(target, at.s + alpha * step);
      const double derivative = next.gradient.dot(step);
      if (derivative > 0.0) {
        hi = alpha, derivative_hi = derivative;
        if (last_side == 1) derivative_lo *= 0.5;
        last_side = 1;
      } else {
        lo = alpha, derivative_lo = derivative, at_lo = next;
        if (last_side == -1) derivative_hi *= 0.5;
        last_side = -1;
        if (derivative >= kShapeLineSearchFlatness * slope) break;
      }
      if (hi - lo <= kShapeLineSearchResolution * hi) break;
    }
    if (next.psi > at_lo.psi) alpha = lo, next = at_lo;
  }
  *at_end = next;
  return alpha * step;
}

/// The step delta minimising g.delta + delta'(H + tau I)delta / 2 subject to
/// |s + delta| <= r (the disk-disk solver's stepOnDisk, docs/exact_distance.md
/// section 4): the Newton step if it stays in the disk, else the multiplier mu of
/// the disk by safeguarded secant steps on |s + delta(mu)|^2 - r^2.
///
/// The gradient's components along H's eigenvectors that are below its rounding
/// (gradient_rounding: g = (x - q)_xy is a difference of coordinates of size
/// scale) are dropped first. In exact arithmetic g is orthogonal to H's null
/// space (g is an eigenvector of the 3-D Hessian with eigenvalue 1), so such a
/// component is rounding only, and (H + tau I)^-1 would turn it into a long
/// step along a flat direction, away from the optimum.
inline Vec2 modelStepOnDisk(const Mat2& H, const Vec2& g_raw, const Vec2& s, double r,
                            double gradient_rounding) {
  Eigen::SelfAdjointEigenSolver<Mat2> eigen;
  eigen.computeDirect(H);
  Vec2 g = Vec2::Zero();
  for (int i = 0; i < 2; ++i) {
    const Vec2 v = eigen.eigenvectors().col(i);
    const double component = v.dot(g_raw);
    if (std::abs(component) > gradient_rounding) g += component * v;
  }
  if (g.squaredNorm() == 0.0) return Vec2::Zero();
  const double tau = kShapeModelRegularisation * (H.trace() + 1.0);
  auto step_for = [&](double mu) -> Vec2 {
    const double a = H(0, 0) + tau + mu, b = H(0, 1), d = H(1, 1) + tau + mu;
    const Vec2 rhs = g + mu * s;
    return Vec2(-(d * rhs.x() - b * rhs.y()), -(a * rhs.y() - b * rhs.x())) / (a * d - b * b);
  };
  const double slack = s.squaredNorm() - r * r;
  auto excess = [&](const Vec2& delta) { return 2.0 * s.dot(delta) + delta.squaredNorm() + slack; };
  Vec2 delta = step_for(0.0);
  double f_lo = excess(delta);
  if (f_lo <= 0.0) return delta;
  double mu_lo = 0.0, mu_hi = std::max((g.norm() + tau * s.norm()) / r, tau);
  Vec2 delta_hi = step_for(mu_hi);
  double f_hi = excess(delta_hi);
  for (int grow = 0; f_hi > 0.0 && grow < kShapeSecularIterations; ++grow) {
    mu_lo = mu_hi, f_lo = f_hi;
    mu_hi *= 4.0;
    delta_hi = step_for(mu_hi);
    f_hi = excess(delta_hi);
  }
  Vec2 best = delta_hi;
  int last_side = 0;
  for (int iteration = 0; iteration < kShapeSecularIterations; ++iteration) {
    double mu = mu_hi - f_hi * (mu_hi - mu_lo) / (f_hi - f_lo);
    if (!(mu > mu_lo && mu < mu_hi)) mu = 0.5 * (mu_lo + mu_hi);
    delta = step_for(mu);
    const double f = excess(delta);
    if (f > 0.0) {
      mu_lo = mu, f_lo = f;
      if (last_side == 1) f_hi *= 0.5;
      last_side = 1;
    } else {
      mu_hi = mu, f_hi = f, best = delta;
      if (last_side == -1) f_lo *= 0.5;
      last_side = -1;
      if (f >= -kShapeSecularTolerance * r * r) break;
    }
    if (mu_hi - mu_lo <= kShapeSecularTolerance * mu_hi) break;
  }
  return best;
}

/// (cos, sin) of a turn by about dtheta: the rational (Cayley) rotation by
/// 2 atan(dtheta / 2), unit to rounding and equal to the turn by dtheta to third
/// order, so rim Newton stays quadratic without trigonometry.
inline Vec2 cayleyTurn(double dtheta) {
  const double h = 0.5 * dtheta;
  const double inverse = 1.0 / (1.0 + h * h);
  return Vec2((1.0 - h * h) * inverse, 2.0 * h * inverse);
}

/// The point of the disk nearest y (frame D): y's foot on the plane, clamped to the rim.
inline Vec2 nearestOnDisk(const Vec3& y, double r) {
  const Vec2 foot = y.head<2>();
  const double length = foot.norm();
  return length > r ? Vec2(foot.x() * (r / length), foot.y() * (r / length)) : foot;
}

/// Minimises psi(s) = dist(x(s), X)^2 / 2 over the disk |s| <= r by the feasible
/// Newton iteration of docs/disk_shape_distance.md section 3 and certifies the
/// answer; the result is for X inflated by rho (>= 0). `scale` sets every
/// tolerance. Every iterate is a feasible pair, so `distance` is always an upper
/// bound and `lower_bound` a lower bound of the true distance.
template <typename Target>
DiskShapeSolution solveDiskShape(const Target& target, double r, double rho, double scale,
                                 SolverGoal goal) {
  const double gap_tolerance = kShapeGapTolerance * scale;
  const double touching = kShapeTouchingTolerance * scale;
  // Start: the disk point nearest proj_X(disk centre) (one alternating projection).
  ShapeIterate at = evaluateAt(target, nearestOnDisk(target.project(Vec3::Zero()).q, r));
  DiskShapeSolution solution;

  // The answer at the current iterate, with its certificate `lower` (core units).
  auto finish = [&](int iteration, double lower) {
    const Vec3 x(at.s.x(), at.s.y(), 0.0);
    const double core_distance = std::sqrt(2.0 * at.psi);
    solution.iterations = iteration;
    solution.p = x;
    if (core_distance <= rho) {  // x lies in X + B_rho: a common point
      solution.q = x;
      solution.distance = 0.0;
      solution.lower_bound = 0.0;
      solution.intersecting = true;
      return solution;
    }
    // The point of X + B_rho nearest x: from q towards x by rho.
    solution.q = at.q + (rho / core_distance) * (x - at.q);
    solution.distance = core_distance - rho;
    solution.lower_bound = std::min(lower, solution.distance);
    solution.intersecting = false;
    return solution;
  };

  for (int iteration = 1; iteration <= kMaxShapeIterations; ++iteration) {
    const Vec3 x(at.s.x(), at.s.y(), 0.0);
    const double core_distance = std::sqrt(2.0 * at.psi);
    if (core_distance <= rho) return finish(iteration, 0.0);
    const double distance = core_distance - rho;
    const double lower =
        certificateAt(target, r, rho, x, at.q, at.hessian3, distance, gap_tolerance);
    if (goal == SolverGoal::intersection) {
      if (distance <= touching) return finish(iteration, lower);
      if (lower > touching) return finish(iteration, lower);
    }
    if (distance - lower <= gap_tolerance) return finish(iteration, lower);

    // The step: Newton along the rim when the point is on it with a
    // non-negative multiplier, else the disk-constrained model step.
    const Vec2 s = at.s;
    const double radius = s.norm();
    const bool near_rim = radius >= r * (1.0 - kShapeOnRim) && radius > 0.0;
    bool moved = false;
    ShapeIterate next;
    if (near_rim) {
      const Vec2 radial = s / radius;
      const Vec2 tangent(-radial.y(), radial.x());
      const double outward = -at.gradient.dot(radial);
      const bool on_rim =
          outward >= 0.0 || outward * outward <= kShapeInwardGradient * kShapeInwardGradient *
                                                      at.gradient.squaredNorm();
      if (on_rim) {
        // psi(theta)' = r sigma, psi'' = r kappa (lengths): dtheta = -sigma / kappa.
        const double sigma = at.gradient.dot(tangent);
        const double kappa = r * tangent.dot(at.hessian * tangent) + std::max(outward, 0.0);
        double dtheta = kappa > 0.0 ? -sigma / kappa : -std::copysign(kShapeMaxRimStep, sigma);
        dtheta = std::clamp(dtheta, -kShapeMaxRimStep, kShapeMaxRimStep);
        for (int halving = 0; halving < kShapeMaxRimHalvings && !moved; ++halving) {
          const Vec2 rotation = cayleyTurn(dtheta);
          const Vec2 s_next = r * (rotation.x() * radial + rotation.y() * tangent);
          next = evaluateAt(target, s_next);
          moved = next.psi < at.psi;
          dtheta *= 0.5;
        }
      }
    }
    if (!moved) {
      const Vec2 step =
          modelStepOnDisk(at.hessian, at.gradient, s, r, kShapeGradientRounding * scale);
      const double slope = at.gradient.dot(step);
      if (!(slope < 0.0)) return finish(iteration, lower);  // stationary to rounding
      shapeLineSearch(target, at, step, slope, &next);
      moved = next.psi < at.psi;
    }
    if (!moved) return finish(iteration, lower);  // no representable decrease
    const double decrease = at.psi - next.psi;
    at = next;
    if (decrease <= kShapeStagnation * scale * scale) {
      const Vec3 x_next(at.s.x(), at.s.y(), 0.0);
      return finish(iteration, certificateAt(target, r, rho, x_next, at.q, at.hessian3,
                                             std::sqrt(2.0 * at.psi) - rho, gap_tolerance));
    }
  }
  const Vec3 x_last(at.s.x(), at.s.y(), 0.0);
  return finish(kMaxShapeIterations,
                certificateAt(target, r, rho, x_last, at.q, at.hessian3,
                              std::sqrt(2.0 * at.psi) - rho, gap_tolerance));
}

}  // namespace internal
}  // namespace fcl_disk
