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
/// the bracket), within this many safeguarded Newton steps.
constexpr double kSecularRootTolerance = 4 * std::numeric_limits<double>::epsilon();
constexpr int kMaxSecularSteps = 100;
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
    if (levelOnAxes(y) <= 1.0) return Projection{y_on_axes, FactoredHessian::diagonalOf(flat_axes)};
    // q_i = e_i^2 y_i / (t + e_i^2) with t > 0 the root of
    // F(t) = sum (e_i y_i / (t + e_i^2))^2 = 1 (F decreasing). Newton runs on
    // phi(t) = 1 / sqrt(F(t)) - 1, which is nearly linear in t (exactly, for a
    // sphere): a few steps from anywhere, safeguarded by the bracket.
    const Vec3 e2 = e.cwiseProduct(e);
    const Vec3 ey = e.cwiseProduct(y);
    auto phi = [&](double t, double* derivative) {
      double f = 0.0, df = 0.0;
      for (int i = 0; i < 3; ++i) {
        if (!(e[i] > 0.0)) continue;
        const double ratio = ey[i] / (t + e2[i]);
        f += ratio * ratio;
        df -= 2.0 * ratio * ratio / (t + e2[i]);
      }
      const double root = std::sqrt(f);
      *derivative = -0.5 * df / (f * root);
      return 1.0 / root - 1.0;
    };
    // Bracket: phi(lo) <= 0 <= phi(hi); lo = e_min |y'| - e_max^2 (y' = y on the
    // nonzero axes: F(t) >= e_min^2 |y'|^2 / (t + e_max^2)^2) is below the root,
    // hi = |e o y| above it (F(t) <= |e o y|^2 / t^2).
    double e_min = std::numeric_limits<double>::infinity(), e_max = 0.0;
    for (int i = 0; i < 3; ++i) {
      if (e[i] > 0.0) e_min = std::min(e_min, e[i]);
      e_max = std::max(e_max, e[i]);
    }
    double lo = std::max(0.0, e_min * y_on_axes.norm() - e_max * e_max);
    double hi = std::max(ey.norm(), lo);
    // Safeguarded as rtsafe (Numerical Recipes 9.4): bisection when Newton
    // would leave the bracket or does not halve its step, as where a tiny
    // semi-axis makes F stiff and Newton's steps minute; done when q is on the
    // surface to rounding (|phi| = |F^-1/2 - 1| <= tolerance) or the bracket
    // has closed. A small step alone proves nothing there. Closed means
    // relative to t + e_min^2: q_i = e_i^2 y_i / (t + e_i^2) moves by
    // dt / (t + e_i^2) of itself, so a bracket narrow against e_max^2 can still
    // be wide against a tiny axis's e_i^2 (e_min >= kFlatSemiAxis: no underflow).
    double t = lo;
    double step = hi - lo, step_before = step;
    for (int iteration = 0; iteration < kMaxSecularSteps; ++iteration) {
      double derivative;
      const double value = phi(t, &derivative);
      if (value < 0.0) lo = t; else hi = t;
      if (!(std::abs(value) > kSecularRootTolerance)) break;
      if (hi - lo <= kSecularRootTolerance * std::max(t, e_min * e_min)) break;
      const double newton = derivative > 0.0 ? value / derivative
                                             : std::numeric_limits<double>::infinity();
      step_before = step;
      double next = t - newton;
      if (next > lo && next < hi && std::abs(2.0 * newton) <= std::abs(step_before)) {
        step = newton;
      } else {
        next = 0.5 * (lo + hi);
        step = hi - lo;
      }
      t = next;
    }
    Vec3 q_S, a, v;  // a = A q (A = diag(1 / e_i^2)), v = M a, M = diag(e_i^2 / (t + e_i^2))
    Vec3 m_diagonal;
    for (int i = 0; i < 3; ++i) {
      const double denominator = t + e2[i];
      const bool flat = !(e[i] > 0.0);
      q_S[i] = flat ? 0.0 : e2[i] * y[i] / denominator;
      a[i] = flat ? 0.0 : y[i] / denominator;
      m_diagonal[i] = flat ? 0.0 : e2[i] / denominator;
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
