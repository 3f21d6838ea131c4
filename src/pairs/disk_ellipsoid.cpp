// Disk - fcl::Ellipsoid: a common point where the disk's point nearest the
// centre lies inside, else the generic solver with the ellipsoid's projection
// (the root t of Eberly's secular equation by safeguarded Newton) and its
// support.
// docs/disk_shape_distance.md, section 4.
#include "../disk_shape_pair.h"

namespace fcl_disk {
namespace internal {
namespace {

/// The projection's root t is found to this relative accuracy (of phi, and of
/// the bracket), within this many evaluations of phi.
constexpr double kSecularRootTolerance = 4 * std::numeric_limits<double>::epsilon();
constexpr int kMaxSecularSteps = 100;
/// Halley's step is Newton's divided by 1 - (Newton's step) phi'' / (2 phi');
/// where that divisor falls below this, far from the root, the step is
/// Newton's (Halley's would be more than twice as long, trusting the local
/// curvature too far).
constexpr double kMinHalleyDivisor = 0.5;
/// Semi-axes below this are flat (0): their squares, which the secular
/// equation divides by, would be subnormal or 0, and such an extent is below
/// the rounding of any scene the solver resolves (lengths >= kMinDiskRadius).
constexpr double kFlatSemiAxis = 1e-150;

/// The solid ellipsoid {sum (y_i / e_i)^2 <= 1}, in its frame. Semi-axes may be
/// 0 (a flat ellipse, a segment, a point).
struct EllipsoidTarget {
  Vec3 e;

  /// sum (y_i / e_i)^2 over the nonzero axes: y lies within the ellipsoid's
  /// extent along them iff it is at most 1.
  double levelOnAxes(const Vec3& y) const {
    double level = 0.0;
    for (int i = 0; i < 3; ++i) {
      if (e[i] > 0.0) level += (y[i] / e[i]) * (y[i] / e[i]);
    }
    return level;
  }

  Projection project(const Vec3& y) const {
    // Within the ellipsoid's extent along its nonzero axes: the projection drops
    // the zero-axis coordinates (for a solid ellipsoid, y itself), so D proj is
    // the identity on the nonzero axes and psi's Hessian is 1 on the zero axes.
    Vec3 flat_axes = Vec3::Zero(), y_on_axes = y;
    for (int i = 0; i < 3; ++i) {
      if (!(e[i] > 0.0)) flat_axes[i] = 1.0, y_on_axes[i] = 0.0;
    }
    const double level = levelOnAxes(y);
    if (level <= 1.0) return Projection{y_on_axes, FactoredHessian::diagonalOf(flat_axes)};
    // q_i = e_i^2 y_i / (t + e_i^2) with t > 0 the root of
    // F(t) = sum (e_i y_i / (t + e_i^2))^2 = 1 (F decreasing). Halley's method
    // runs on phi(t) = 1 / sqrt(F(t)) - 1, which is nearly linear in t (exactly,
    // for a sphere), from the radial estimate below, safeguarded by a bracket.
    const Vec3 e2 = e.cwiseProduct(e);
    const Vec3 ey = e.cwiseProduct(y);
    // Bracket: each term of F is at most 1 at the root, so t >= e_i |y_i| - e_i^2;
    // F(t) <= |e o y|^2 / (t + e_min^2)^2, so t <= |e o y| - e_min^2.
    double e_min = std::numeric_limits<double>::infinity();
    double lo = 0.0;
    for (int i = 0; i < 3; ++i) {
      if (!(e[i] > 0.0)) continue;
      e_min = std::min(e_min, e[i]);
      lo = std::max(lo, std::abs(ey[i]) - e2[i]);
    }
    double hi = std::max(ey.norm() - e_min * e_min, lo);
    // Start: y - q = t A q (A = diag(1 / e_i^2)); with q estimated by the radial
    // point y / sqrt(L) (L = levelOnAxes(y)) and |y - q| by (1 - 1/sqrt(L)) |y|,
    // t ~ (sqrt(L) - 1) |y| / |A y| (exact for a sphere). On the report's
    // ellipsoid cases it is within 3% of the root in the median, and a
    // projection takes 3.1 evaluations of phi (docs/disk_shape_distance.md,
    // section 4). Out of the bracket, or not finite
    // (A y overflows for semi-axes near kFlatSemiAxis), the bracket's end.
    const Vec3 a_y = y_on_axes.cwiseQuotient(e2.cwiseMax(std::numeric_limits<double>::min()));
    const double radial = (std::sqrt(level) - 1.0) * y_on_axes.norm() / a_y.norm();
    double t = radial > lo ? std::min(radial, hi) : lo;
    // With r_i = e_i y_i / (t + e_i^2): F = sum r_i^2 = f, F' = -2 g1 and
    // F'' = 6 g2 (g1 = sum r_i^2 / (t + e_i^2), g2 = sum r_i^2 / (t + e_i^2)^2).
    // So phi has the sign of 1 - sqrt f, Newton's step phi / phi' is
    // f (1 - sqrt f) / g1, and Halley's divides it by
    // 1 - (phi / phi') phi'' / (2 phi') = 1 - 1.5 (1 - sqrt f) (1 - f g2 / g1^2).
    // Done when q is on the surface to rounding (|1 - sqrt f| <= tolerance) or
    // the bracket has closed, relative to t + e_min^2: q_i moves by
    // dt / (t + e_i^2) of itself, so a bracket narrow against e_max^2 can still
    // be wide against a tiny axis's e_i^2 (e_min >= kFlatSemiAxis: no
    // underflow). As rtsafe (Numerical Recipes 9.4), bisection where the step
    // would leave the bracket or does not halve the step before, as where a
    // tiny semi-axis makes F stiff. q is computed with the last evaluation's
    // 1 / (t + e_i^2), so it is the point whose phi passed the test.
    Vec3 inverse;  // 1 / (t + e_i^2) at the last evaluated t (0 on flat axes)
    double step_before = hi - lo;
    for (int evaluation = 1;; ++evaluation) {
      double f = 0.0, g1 = 0.0, g2 = 0.0;
      for (int i = 0; i < 3; ++i) {
        inverse[i] = e[i] > 0.0 ? 1.0 / (t + e2[i]) : 0.0;
        const double ratio = ey[i] * inverse[i];
        const double term = ratio * ratio * inverse[i];
        f += ratio * ratio;
        g1 += term;
        g2 += term * inverse[i];
      }
      const double beyond = 1.0 - std::sqrt(f);  // > 0: t beyond the root
      if (beyond > 0.0) hi = t; else lo = t;
      if (!(std::abs(beyond) > kSecularRootTolerance)) break;
      if (hi - lo <= kSecularRootTolerance * std::max(t, e_min * e_min)) break;
      if (evaluation == kMaxSecularSteps) break;
      const double inverse_g1 = 1.0 / g1;
      const double newton = f * beyond * inverse_g1;
      const double divisor = 1.0 - 1.5 * beyond * (1.0 - f * g2 * inverse_g1 * inverse_g1);
      const double step = divisor > kMinHalleyDivisor ? newton / divisor : newton;
      double next = t - step;
      if (next > lo && next < hi && std::abs(2.0 * step) <= std::abs(step_before)) {
        step_before = step;
      } else {
        next = 0.5 * (lo + hi);
        step_before = hi - lo;
      }
      t = next;
    }
    Vec3 q_S, a, v;  // a = A q, v = M a, M = diag(e_i^2 / (t + e_i^2))
    Vec3 m_diagonal;
    for (int i = 0; i < 3; ++i) {
      q_S[i] = e2[i] * y[i] * inverse[i];
      a[i] = y[i] * inverse[i];
      m_diagonal[i] = e2[i] * inverse[i];
      v[i] = m_diagonal[i] * a[i];
    }
    // D proj = M - v v^T / (a.v) (implicit differentiation of q^T A q = 1), so
    // psi's Hessian is sum_i (1 - m_i) e_i e_i^T + v v^T / (a.v).
    FactoredHessian hessian = FactoredHessian::diagonalOf(Vec3::Ones() - m_diagonal);
    const double av = a.dot(v);
    if (av > 0.0) hessian.add(1.0 / av, v);
    return Projection{q_S, hessian};
  }

  Vec3 support(const Vec3& w) const {
    // argmax of w.y: A^-1 w / sqrt(w^T A^-1 w), A^-1 = diag(e_i^2).
    const Vec3 scaled = e.cwiseProduct(w);
    const double length = scaled.norm();
    if (!(length > 0.0)) return Vec3::Zero();  // w along only zero axes: every point ties
    return e.cwiseProduct(scaled) / length;
  }
};

template <typename S>
struct EllipsoidTraits {
  static bool valid(const fcl::Ellipsoid<S>& ellipsoid) {
    const auto& radii = ellipsoid.radii;
    return areValidShapeLengths({double(radii.x()), double(radii.y()), double(radii.z())});
  }
  static double boundingRadius(const fcl::Ellipsoid<S>& ellipsoid) {
    return double(ellipsoid.radii.maxCoeff());
  }
  static double inflation(const fcl::Ellipsoid<S>&) { return 0.0; }
  static EllipsoidTarget target(const fcl::Ellipsoid<S>& ellipsoid) {
    Vec3 e = ellipsoid.radii.template cast<double>();
    for (int i = 0; i < 3; ++i) {
      if (e[i] < kFlatSemiAxis) e[i] = 0.0;
    }
    return EllipsoidTarget{e};
  }
  /// Overlaps only (docs/disk_shape_distance.md, section 4): the disk's point
  /// nearest the centre, when it lies in the ellipsoid, is a common point
  /// (distance 0). A separated pair has no closed form (the projection is a
  /// root of the secular equation): not exact, the generic solver answers.
  static LeafToDisk closedForm(const DiskInShape& disk, const fcl::Ellipsoid<S>& ellipsoid,
                               double /*scale*/) {
    const Vec3 x = disk.point(disk.nearest(Vec3::Zero()));
    const EllipsoidTarget ellipsoid_target = target(ellipsoid);
    for (int i = 0; i < 3; ++i) {  // a flat axis holds only x_i = 0
      if (!(ellipsoid_target.e[i] > 0.0) && x[i] != 0.0) return LeafToDisk{};
    }
    return ellipsoid_target.levelOnAxes(x) <= 1.0 ? meetingAt(x) : LeafToDisk{};
  }
  /// The principal axes.
  template <typename Search>
  static void contactDirections(const EllipsoidTarget&, const DiskInShape&, Search* directions) {
    for (int i = 0; i < 3; ++i) directions->push_back(Vec3::Unit(i));
  }
};

}  // namespace

template <typename S>
struct DiskShapePair<fcl::Ellipsoid<S>>
    : GenericDiskShapePair<S, fcl::Ellipsoid<S>, EllipsoidTraits<S>> {};

}  // namespace internal
}  // namespace fcl_disk

FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::Ellipsoid)
