// Disk - fcl::Ellipsoid, in the ellipsoid's frame. Closed
// forms first: a common point where the disk's point nearest the centre lies
// inside; the face case; else Newton's method on the saddle point of the
// Fenchel dual along the rim, certified by the duality gap, with the overlap
// decided by the disk's least level where the dual cannot separate the pair.
// Pairs these leave open (a flat ellipsoid, a rim iteration that does not
// close) go to the generic solver with the ellipsoid's projection (the root t
// of Eberly's secular equation by safeguarded Newton) and its support.
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

  /// The radial estimate of the projection's root t for y outside, at level
  /// L (levelOnAxes): y - q = t A q (A = diag(1 / e_i^2), `squares` = e_i^2)
  /// with q taken as the radial point y / sqrt(L) and |y - q| as
  /// (1 - 1 / sqrt(L)) |y|, so t ~ (sqrt(L) - 1) |y| / |A y| (exact for a
  /// sphere).
  static double radialRootEstimate(const Vec3& y, const Vec3& squares, double level) {
    return (std::sqrt(level) - 1.0) * y.norm() / y.cwiseQuotient(squares).norm();
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
    // In lengths over a power of two near the largest semi-axis (exact): the
    // sums below hold up to fourth powers of lengths, which leave the range of
    // doubles for lengths far from 1 (unscaled, at 1e-88 q lands 19% off the
    // surface).
    const auto [to_unit, from_unit] = powersOfTwoAbout(e.maxCoeff());
    const Vec3 eu = e * to_unit, yu = y * to_unit, yu_on_axes = y_on_axes * to_unit;
    const Vec3 e2 = eu.cwiseProduct(eu);
    const Vec3 ey = eu.cwiseProduct(yu);
    // Bracket: each term of F is at most 1 at the root, so t >= e_i |y_i| - e_i^2;
    // F(t) <= |e o y|^2 / (t + e_min^2)^2, so t <= |e o y| - e_min^2.
    double e_min = std::numeric_limits<double>::infinity();
    double lo = 0.0;
    for (int i = 0; i < 3; ++i) {
      if (!(eu[i] > 0.0)) continue;
      e_min = std::min(e_min, eu[i]);
      lo = std::max(lo, std::abs(ey[i]) - e2[i]);
    }
    double hi = std::max(ey.norm() - e_min * e_min, lo);
    // Start: radialRootEstimate. On the report's ellipsoid cases it is within
    // 3% of the root in the median, and a projection takes 3.1 evaluations of
    // phi (docs/disk_shape_distance.md, section 4). Out of the bracket, or not
    // finite (A y overflows for semi-axes near kFlatSemiAxis), the bracket's end.
    const double radial =
        radialRootEstimate(yu_on_axes, e2.cwiseMax(std::numeric_limits<double>::min()), level);
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
        inverse[i] = eu[i] > 0.0 ? 1.0 / (t + e2[i]) : 0.0;
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
      q_S[i] = e2[i] * yu[i] * inverse[i] * from_unit;
      a[i] = yu[i] * inverse[i];
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
    // argmax of w.y: A^-1 w / sqrt(w^T A^-1 w), A^-1 = diag(e_i^2), which does
    // not depend on w's length: w is taken over a power of two near its
    // largest component (exact), since certificates pass it at any length
    // (along a pair's separation), and |E w|'s square would leave the doubles.
    const double largest = w.cwiseAbs().maxCoeff();
    if (!(largest > 0.0 && largest <= std::numeric_limits<double>::max())) return Vec3::Zero();
    const Vec3 scaled = e.cwiseProduct(w * powersOfTwoAbout(largest).first);
    const double length = scaled.norm();
    if (!(length > 0.0)) return Vec3::Zero();  // w along only zero axes: every point ties
    return e.cwiseProduct(scaled) / length;
  }
};

/// The rim iteration (ellipsoidAgainstRim) gives up, for the generic solver,
/// after this many Newton steps on L: on the report's 2,000 cases it proves
/// 1,365 pairs, 1,355 of them within 4 steps and all within 8 (on 100,000
/// cases of the same generator, seed 777: 66,582, 66,090 within 4).
constexpr int kMaxRimSteps = 8;
/// ... and when its certificate G(w / |w|) is still not positive after this
/// many, which on the report's cases happens to 35 pairs that overlap (the
/// dual optimum is then w = 0, where L is not smooth) and to 1 apart:
/// ellipsoidOverlap decides, and a pair apart goes to the generic solver.
constexpr int kStepsToSeparate = 3;
/// The certificate (three square roots and a division beyond the step's own
/// quantities) is evaluated only after a saddle step no larger than this, the
/// larger of |dw| / |w| and the turn in radians: Newton converges
/// quadratically, so after a larger step the gap cannot close yet. On the
/// report's 2,000 cases every certificate that closes follows a step of at most
/// 1.6e-3 (4.3e-3 on the 100,000 above), and 3,831 evaluations after every
/// step become 2,130. The lower bound is also formed at step
/// kStepsToSeparate, for its test.
constexpr double kCertifyAfterStep = 1e-2;
/// ellipsoidOverlap's Newton steps on its secular equation; undecided after
/// (a pair touching to rounding).
constexpr int kMaxOverlapSteps = 12;
/// Semi-axes below this many scene sizes go to the generic solver: in the
/// closed forms' units of the scene's size their squares would be subnormal
/// (the sums of squares of the rim iteration lose their precision there).
constexpr double kMinUnitSemiAxis = 1e-150;

/// Whether the disk meets the ellipsoid (docs/disk_shape_distance.md, section
/// 4, "Ellipsoid"): the least of the level l(y) = sum (y_i / e_i)^2 over the
/// disk, l(c + U s) = |b + A s|^2 (A = E^-1 U, b = E^-1 c), is at most 1. A
/// trust-region problem in s, |s| <= r: the minimiser of the whole plane if it
/// lies in the disk, else s(mu) = -(Q + mu I)^-1 g (Q = A^T A, g = A^T b) with
/// |s(mu)| = r, found by Newton's method on 1 / |s(mu)| - 1 / r from mu = 0
/// (which approaches the root from below, monotonically). Each step decides as
/// soon as it can: r s / |s| is a disk point, so its level <= 1 proves an
/// overlap (that point is common); l(s) + mu (|s|^2 - r^2) is the Lagrangian's
/// minimum, a lower bound of the least level, so above 1 it proves the pair
/// apart. `e` all > 0.
struct OverlapVerdict {
  enum Kind { undecided, overlap, apart } kind;
  Vec3 common_point;
};
OverlapVerdict ellipsoidOverlap(const Vec3& e, const DiskInShape& disk) {
  const Vec3 inverse_e = e.cwiseInverse();
  const Vec3 b = disk.c.cwiseProduct(inverse_e);
  const Vec3 a_u = disk.u.cwiseProduct(inverse_e), a_v = disk.v.cwiseProduct(inverse_e);
  const double q_uu = a_u.squaredNorm(), q_uv = a_u.dot(a_v), q_vv = a_v.squaredNorm();
  const Vec2 g(a_u.dot(b), a_v.dot(b));
  const double r2 = disk.r * disk.r;
  const auto level = [&](const Vec2& s) { return (b + s.x() * a_u + s.y() * a_v).squaredNorm(); };
  double mu = 0.0;
  for (int step = 0; step < kMaxOverlapSteps; ++step) {
    const double m_uu = q_uu + mu, m_vv = q_vv + mu;
    const double det = m_uu * m_vv - q_uv * q_uv;
    if (!(det > 0.0)) break;
    const Vec2 s = Vec2(q_uv * g.y() - m_vv * g.x(), q_uv * g.x() - m_uu * g.y()) / det;
    const double s2 = s.squaredNorm();
    if (mu == 0.0 && s2 <= r2) {
      if (level(s) <= 1.0) return {OverlapVerdict::overlap, disk.point(s)};
      return {OverlapVerdict::apart, Vec3::Zero()};
    }
    if (level(s) + mu * (s2 - r2) > 1.0) return {OverlapVerdict::apart, Vec3::Zero()};
    const double length = std::sqrt(s2);
    const Vec2 on_rim = s * (disk.r / length);
    if (level(on_rim) <= 1.0) return {OverlapVerdict::overlap, disk.point(on_rim)};
    // d|s|^2 / dmu = -2 s^T (Q + mu I)^-1 s.
    const Vec2 t = Vec2(m_vv * s.x() - q_uv * s.y(), m_uu * s.y() - q_uv * s.x()) / det;
    const double next = mu + s2 * (length / disk.r - 1.0) / s.dot(t);
    if (!(next > mu)) break;
    mu = next;
  }
  return {OverlapVerdict::undecided, Vec3::Zero()};
}

/// A separated pair that is not the face case, whose p* is therefore on the
/// rim (docs/disk_shape_distance.md, section 4, "Ellipsoid"), from `rim`
/// (unit, in-plane) and the dual start `w` (of the distance's length and
/// direction: ellipsoidApart). Newton's method on the saddle point of
///   L(w, theta) = -|E w| - w.p(theta) - |w|^2 / 2,
///   p(theta) = c + r (cos theta u + sin theta v):
/// max over w of L is |p(theta) - E|^2 / 2 (the Fenchel dual of the point's
/// distance), min over theta of that is d^2 / 2. Its gradient,
/// (q - p - w, -w.p'), with q = -E^2 w / |E w| the ellipsoid's point least
/// along w, vanishes at w* = q* - p*. L is smooth wherever w != 0. Every
/// iterate is a feasible pair (p, q), |q - p| an upper bound,
/// and G(w / |w|) = (-|E w| - w.c - r |U^T w|) / |w| (the certificate of docs
/// section 2 along w) a lower bound: exact when they meet within
/// kShapeGapTolerance of the scene. Else not exact (the generic solver
/// answers), or the common point ellipsoidOverlap finds.
LeafToDisk ellipsoidAgainstRim(const EllipsoidTarget& ellipsoid, const DiskInShape& disk,
                               Vec2 rim, Vec3 w, double scale) {
  const Vec3 e2 = ellipsoid.e.cwiseProduct(ellipsoid.e);
  const double tolerance = kShapeGapTolerance * scale;
  // The saddle steps scale the turn's numerator and denominator (both of the
  // size of sigma r^2, a length to the fourth) by this, the last step's
  // 1 / (sigma r^2), so that the Cayley rotation's squares of them stay of
  // the size of 1 at any length scale; at the start |w|^2 r^2 stands for it.
  const double inverse_r2 = 1.0 / (disk.r * disk.r);
  double turn_scale = inverse_r2 / w.squaredNorm();
  bool small_step = false;  // the last step was within kCertifyAfterStep
  for (int step = 0;; ++step) {
    const Vec3 e2_w = e2.cwiseProduct(w);
    const double a = std::sqrt(w.dot(e2_w));
    if (!(a > 0.0)) return LeafToDisk{};
    const Vec3 q = e2_w * (-1.0 / a);
    const Vec3 radial = rim.x() * disk.u + rim.y() * disk.v;
    const Vec3 p = disk.c + disk.r * radial;
    if (small_step || step == kStepsToSeparate) {
      const double lower =
          (-a - w.dot(disk.c) - disk.r * disk.inPlane(w).norm()) / w.norm();
      if (small_step) {
        const double upper = (q - p).norm();
        if (upper - lower <= tolerance) return certifiedOrBound(lower, upper, p, q, scale);
      }
      if (!(lower > 0.0) && step == kStepsToSeparate) {
        const OverlapVerdict verdict = ellipsoidOverlap(ellipsoid.e, disk);
        return verdict.kind == OverlapVerdict::overlap ? meetingAt(verdict.common_point)
                                                       : LeafToDisk{};
      }
    }
    if (step == kMaxRimSteps) return LeafToDisk{};
    // Newton: M dw + p' dtheta = q - p - w, p'.dw - w.(p - c) dtheta = -w.p',
    // M = I + (E^2 - q q^T) / a = D - q q^T / a, D = diag(1 + e_i^2 / a), by
    // Sherman and Morrison: M^-1 x = a d o x + z (z.x) / sigma with
    // d_i = 1 / (a + e_i^2), z = D^-1 q = -e2 o w o d and sigma = a - q^T D^-1 q,
    // summed as sum e_i^2 w_i^2 d_i (> 0, no cancellation: a^2 = sum e_i^2 w_i^2).
    // dtheta = N / D' with N = p'.M^-1 (q - p - w) + w.p' and
    // D' = p'.M^-1 p' + w.(p - c), taken times sigma so that the turn, its
    // Cayley rotation and 1 / sigma are three divisions side by side: the
    // iteration is a chain of dependent operations, whose latency sets its time.
    const Vec3 tangent = disk.r * (rim.x() * disk.v - rim.y() * disk.u);  // p'
    const Vec3 d = (Vec3::Constant(a) + e2).cwiseInverse();
    const Vec3 z = -e2_w.cwiseProduct(d);
    const double sigma = -z.dot(w);
    const Vec3 residual = q - p - w;
    const Vec3 a_d_tangent = a * d.cwiseProduct(tangent);
    const double z_tangent = z.dot(tangent);
    const double numerator =
        (sigma * (a_d_tangent.dot(residual) + w.dot(tangent)) + z_tangent * z.dot(residual)) *
        turn_scale;
    const double denominator =
        (sigma * (a_d_tangent.dot(tangent) + disk.r * w.dot(radial)) + z_tangent * z_tangent) *
        turn_scale;
    const double inverse_sigma = 1.0 / sigma;
    const double turn = numerator / denominator;
    // The Cayley rotation by 2 atan(turn / 2), over the common denominator.
    const double numerator2 = numerator * numerator;
    const double denominator2 = 4.0 * denominator * denominator;
    const double inverse_rotation = 1.0 / (denominator2 + numerator2);
    const double cos = (denominator2 - numerator2) * inverse_rotation;
    const double sin = 4.0 * numerator * denominator * inverse_rotation;
    if (!std::isfinite(turn) || !std::isfinite(inverse_rotation) || !(inverse_rotation > 0.0)) {
      return LeafToDisk{};
    }
    const Vec3 y = residual - turn * tangent;  // dw = M^-1 y
    const Vec3 dw = a * d.cwiseProduct(y) + z * (z.dot(y) * inverse_sigma);
    small_step = std::abs(turn) <= kCertifyAfterStep &&
                 dw.squaredNorm() <= kCertifyAfterStep * kCertifyAfterStep * w.squaredNorm();
    w += dw;
    rim = Vec2(cos * rim.x() - sin * rim.y(), cos * rim.y() + sin * rim.x());
    turn_scale = inverse_sigma * inverse_r2;
  }
}

/// The closed forms of a pair whose disk's point nearest the centre is outside
/// the ellipsoid (docs/disk_shape_distance.md, section 4, "Ellipsoid"). The
/// face case: the ellipsoid's point extreme towards the disk's plane, on one
/// side of it, projecting into the disk. Else the rim iteration from the rim
/// point towards where the ellipsoid comes nearest the plane (the foot of that
/// extreme point, or of its centre where the plane cuts it), with w from that
/// point along the ellipsoid's normal line through it. Lengths in units of
/// about the scene's size (`scale` in [1, 2)); every semi-axis > 0; `disk`
/// orthonormal.
LeafToDisk ellipsoidApart(const EllipsoidTarget& ellipsoid, const DiskInShape& disk,
                          double scale) {
  const Vec3& e = ellipsoid.e;
  const double centre_height = -disk.n.dot(disk.c);  // the ellipsoid's centre over the plane
  const Vec3 e_n = e.cwiseProduct(disk.n);
  const double reach = e_n.norm();  // h_E(n) = h_E(-n) = |E n|
  const double height = std::abs(centre_height) - reach;  // <= 0: the plane cuts it
  Vec3 nearest_plane = Vec3::Zero();
  if (height > 0.0) {
    nearest_plane = ((centre_height >= 0.0 ? -1.0 : 1.0) / reach) * e.cwiseProduct(e_n);
    const Vec2 s = disk.inPlane(nearest_plane - disk.c);
    if (s.squaredNorm() <= disk.r * disk.r) {
      const Vec3 p = disk.point(s);
      const LeafToDisk face = certifiedOrBound(height, (nearest_plane - p).norm(), p,
                                               nearest_plane, scale);
      if (face.exact) return face;
    }
  }
  const Vec2 towards = disk.inPlane(nearest_plane - disk.c);
  const double towards_length = towards.norm();
  if (!(towards_length > 0.0)) return LeafToDisk{};
  const Vec2 rim = towards / towards_length;
  const Vec3 rim_point = disk.point(disk.r * rim);
  const double rim_level = ellipsoid.levelOnAxes(rim_point);
  if (rim_level <= 1.0) return meetingAt(rim_point);
  // w from the rim point p to q(t) = (I + t A)^-1 p (A = E^-2), the point of
  // the ellipsoid's level surface whose normal line passes through p, at the
  // radial estimate of the projection's root t (the projection's start):
  // q(t) - p = -t (E^2 + t I)^-1 p has the length and direction of p's
  // separation from the ellipsoid to first order. A shorter w (to p's radial
  // point on the ellipsoid) sends the saddle step through w = 0.
  const Vec3 e2 = e.cwiseProduct(e);
  const double t = EllipsoidTarget::radialRootEstimate(rim_point, e2, rim_level);
  return ellipsoidAgainstRim(ellipsoid, disk, rim,
                             -t * rim_point.cwiseQuotient(e2 + Vec3::Constant(t)), scale);
}

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
                               double scale) {
    const Vec3 x = disk.point(disk.nearest(Vec3::Zero()));
    const EllipsoidTarget ellipsoid_target = target(ellipsoid);
    for (int i = 0; i < 3; ++i) {  // a flat axis holds only x_i = 0
      if (!(ellipsoid_target.e[i] > 0.0) && x[i] != 0.0) return LeafToDisk{};
    }
    const double level = ellipsoid_target.levelOnAxes(x);
    if (level <= 1.0) return meetingAt(x);
    if (!(ellipsoid_target.e.minCoeff() > 0.0)) return LeafToDisk{};
    // The separated cases work in lengths over a power of two near the scene's
    // size (exact), so that the squares and fourth powers of lengths they form
    // (|E w|^2 is one) stay normal doubles at every length scale.
    return inSceneUnits(disk, scale, [&](const DiskInShape& unit_disk, double to_unit,
                                         double unit_scale) {
      const EllipsoidTarget unit_ellipsoid{ellipsoid_target.e * to_unit};
      if (!(unit_ellipsoid.e.minCoeff() >= kMinUnitSemiAxis)) return LeafToDisk{};
      return ellipsoidApart(unit_ellipsoid, unit_disk, unit_scale);
    });
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
