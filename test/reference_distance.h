// An independent, high-precision reference for the disk-disk distance, for tests
// and for the speed/error report. Header-only; depends on Eigen and the standard
// library only (no fcl, no fcl_disk solver), so a bug in the production solver
// cannot leak into the values it is judged against.
//
// Notation: disk i has centre c_i, orthonormal frame (u_i, v_i, n_i) (n_i the unit
// normal) and radius r_i; the disk is {c_i + a u_i + b v_i : a^2 + b^2 <= r_i^2}.
//
// METHOD (primal and brute-force-flavoured on purpose; the production solver runs
// Newton on a dual function, this does not):
//   Every candidate below is a real pair (p, q) with p in disk 1 and q in disk 2,
//   so each |p - q| is an upper bound on the distance; the answer is the smallest.
//   (i)   Intersection, closed form: for non-parallel planes each disk meets the
//         other's plane in a chord of the line L = plane1 ∩ plane2 (centre-to-L
//         distance |n_j.(c_i - c_j)| / |P_i n_j|, computed from in-plane
//         components so near-parallel planes keep their digits); if the chords
//         overlap, the midpoint of the overlap is a common point.
//   (ii)  Face cases, closed form: the rim point of disk j extreme along -+n_i
//         (c_j -+ r_j P_j n_i / |P_j n_i|) with its projection onto disk i; the
//         KKT sign conditions (that point is on the near side and projects inside
//         disk i) hold exactly when this is the optimum, and the minimum over all
//         candidates picks it then. For parallel planes: a point over the middle
//         of the overlap of the projections (face-face optimum, distance |h|).
//   (iii) Rim searches: F_1(theta) = dist(rim_1(theta), disk 2) and
//         F_2(phi) = dist(rim_2(phi), disk 1), point-to-disk distance in closed
//         form. Global 1-D minimum by dense sampling (kReferenceRimSamples = 720
//         per rim) and refinement of the sampled local minima of F and of the
//         sign changes - to + of G = d(F^2/2)/dtheta between samples (G is
//         continuous: squared distance to a convex set is C^1). Refinement is
//         bisection on G when G brackets a root (angle to machine precision,
//         which the certificate below needs when F is tiny), else golden
//         section on F (to F's noise floor). A bracket is skipped when a
//         rigorous bound proves it cannot beat the best value so far:
//         F^2/2 = psi(rim(theta)) with psi = dist^2/2 convex, |grad psi| = F
//         and |rim''| = r, so F^2/2(theta0 + t) >= F0^2/2 + G0 t - F0 r t^2/2
//         from either end of a sample interval. In the first pass at most
//         kReferenceFirstPassRefinements brackets per rim are refined (lowest
//         sampled value first): rims at constant distance (coaxial) have a
//         rounding-noise local minimum every few samples.
//   Why this is the distance: unless the planes are parallel with overlapping
//   projections (covered by (ii)), one point of a nearest pair lies on a rim (two
//   face-interior points would need q - p parallel to both normals; if the disks
//   intersect, the common segment ends on a rim), so min(F_1, F_2) = distance.
//   (i) and (ii) are redundant with (iii) in exact arithmetic; they supply exact
//   answers where the 1-D functions are flat or kinked.
//
// SELF-CERTIFICATE: the disks are convex, so for ANY unit w (pointing 1 -> 2)
//   d >= w.(c2 - c1) - r1 |P1 w| - r2 |P2 w|          (support functions)
// The reference evaluates this at several w (from q - p, from t1 x t2 for rim
// tangents t_i, the normals, the centre line) and returns the best as
// lower_bound. This only CHECKS the primal answer (a different method would have
// to produce a w, the search does not use one); if the gap is large the search is
// repeated with kReferenceRetryFactor times denser sampling.
//
// ACCURACY: all arithmetic in long double (x87 80-bit, 64-bit mantissa,
// eps = 1.08e-19) relative to c1, so far-from-origin poses cost nothing beyond
// the exactness of c2 - c1. scale = max(1, r1 + r2 + |c1 - c2|). Validated on
// every family of disk_families.h (double and float poses; seeds 1 and 7 x 3000
// cases, seed 99 x 1000 with brute force, plus the test seed) and on
// hand-derived closed forms:
//   - certificate gap (distance - lower_bound) <= 2e-19 * scale everywhere
//     except pairs at rounding-level separation (touching, d ~ 1e-17), where
//     |q - p| gives no clean direction: <= 3.2e-17 * scale (and <= d);
//   - never above a 20000-samples-per-rim brute force by more than 2e-19 *
//     scale (the search misses no basin);
//   - constructed exact distances (rim-rim and face cases built from the KKT
//     conditions, coplanar, coaxial, touching, interlocked) reproduced to within
//     0.22 of the pose-rounding bound, i.e. the remaining difference is the
//     rounding of the poses to double/float, not the reference;
//   - closed forms (coaxial |h|, parallel sqrt(h^2 + max(0, D - r1 - r2)^2),
//     coplanar D - r1 - r2, facts.md counterexample A 1/2 - 1/sqrt5 and B
//     0.062393, perpendicular and 1e-12-tilt cases): error <= 1e-19 * scale.
// So the reference is good to ~1e-17 * scale, five orders below the 1e-12 the
// production solver is held to. long double suffices: the worst terms are
// eps * scale, eps * r_max (radius ratio 1e6) and a 1e-12 tilt computed from
// in-plane components to 1e-19 absolute; __float128 is not needed or used.
// Cost: ~75-200 us per pair (x87 long double; 2 x 720 samples + refinement).
// Input interpretation: the frame is re-orthonormalised in long double (n first,
// then u, v = n x u). A double rotation is orthonormal only to ~1e-16, so "the"
// disk of a double pose is defined to ~1e-16 * r; for float poses to ~1e-7 * r.
// That ambiguity, not this code, limits comparisons with float solvers.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace fcl_disk_reference {

using Real = long double;
using Vector3R = Eigen::Matrix<Real, 3, 1>;
using Matrix3R = Eigen::Matrix<Real, 3, 3>;

/// Samples per rim in the first pass. 720 (half a degree) resolves every basin of
/// the families used here (no retry was ever needed in validation); a missed
/// basin would show up in the certificate and trigger a denser pass.
constexpr int kReferenceRimSamples = 720;
/// Density multiplier of each retry pass, and how many passes at most.
constexpr int kReferenceRetryFactor = 16;
constexpr int kReferenceMaxRetries = 2;
/// Retry when distance - lower_bound exceeds this times the scene scale: well
/// above the long-double noise of the certificate (~1e-18) and well below the
/// 1e-12 the production solver is held to.
constexpr Real kReferenceRetryGap = 1e-16L;

/// A disk in long double: centre, orthonormal frame (u, v in-plane, n normal),
/// radius.
struct RefDisk {
  Vector3R centre{Vector3R::Zero()};
  Vector3R u{Vector3R::UnitX()};
  Vector3R v{Vector3R::UnitY()};
  Vector3R n{Vector3R::UnitZ()};
  Real radius{1};
};

/// Builds a RefDisk from a centre, a rotation whose columns are (u, v, n) and a
/// radius. The rotation is re-orthonormalised in long double keeping n's
/// direction first (the plane matters most for near-parallel and coplanar
/// pairs), then u's in-plane direction; v = n x u.
inline RefDisk makeRefDisk(const Vector3R& centre, const Matrix3R& rotation, Real radius) {
  RefDisk disk;
  disk.centre = centre;
  disk.n = rotation.col(2).normalized();
  const Vector3R u_in_plane = rotation.col(0) - disk.n.dot(rotation.col(0)) * disk.n;
  disk.u = u_in_plane.normalized();
  disk.v = disk.n.cross(disk.u);
  disk.radius = radius;
  return disk;
}

/// Converter from an Eigen isometry X_W (double or float) and a radius; the
/// inputs are converted exactly (every float/double is a long double).
template <typename S>
RefDisk makeRefDisk(const Eigen::Transform<S, 3, Eigen::Isometry>& X_W, S radius) {
  return makeRefDisk(X_W.translation().template cast<Real>(),
                     X_W.linear().template cast<Real>(), static_cast<Real>(radius));
}

/// Which candidate produced the reference answer (informational).
enum class ReferenceMethod {
  intersection_chords,  ///< (i): common point of the two chords on L.
  parallel_faces,       ///< (ii): point over the overlap of the projections.
  face1,                ///< (ii): rim point of disk 2 over disk 1's face.
  face2,                ///< (ii): rim point of disk 1 over disk 2's face.
  rim1_search,          ///< (iii): point on rim 1, projected onto disk 2.
  rim2_search,          ///< (iii): point on rim 2, projected onto disk 1.
};

inline const char* referenceMethodName(ReferenceMethod m) {
  switch (m) {
    case ReferenceMethod::intersection_chords: return "intersection_chords";
    case ReferenceMethod::parallel_faces: return "parallel_faces";
    case ReferenceMethod::face1: return "face1";
    case ReferenceMethod::face2: return "face2";
    case ReferenceMethod::rim1_search: return "rim1_search";
    case ReferenceMethod::rim2_search: return "rim2_search";
  }
  return "?";
}

/// The reference answer. Points are in the input (world) frame.
struct ReferenceResult {
  Real distance{0};             ///< distance between the disks (an upper bound up to rounding).
  Vector3R p1{Vector3R::Zero()};  ///< nearest point on disk a.
  Vector3R p2{Vector3R::Zero()};  ///< nearest point on disk b.
  Real lower_bound{0};          ///< duality certificate: lower_bound <= true distance (up to rounding).
  Real scale{1};                ///< max(1, r1 + r2 + |c1 - c2|).
  ReferenceMethod method{ReferenceMethod::rim1_search};
  int rim_samples{0};           ///< samples per rim in the last pass.

  Real certifiedGap() const { return distance - lower_bound; }
};

namespace detail {

/// sqrt(a^2 + b^2) in long double. Its exponent range (1e+-4932) makes
/// overflow and underflow impossible for any float/double input, so this is as
/// accurate as hypot and 25x faster (hypotl is a libm call on x87).
inline Real norm2(Real a, Real b) { return std::sqrt(a * a + b * b); }

struct PointOnDisk {
  Vector3R point;
  Real distance;  ///< |x - point|, computed from components, not by subtraction.
};

/// Closed-form nearest point of a disk to x: drop the normal component, clamp
/// the in-plane part to the radius.
inline PointOnDisk closestPointOnDisk(const Vector3R& x, const RefDisk& disk) {
  const Vector3R rel = x - disk.centre;
  const Real a = disk.u.dot(rel);
  const Real b = disk.v.dot(rel);
  const Real h = disk.n.dot(rel);
  const Real rho = norm2(a, b);
  if (rho <= disk.radius) {
    return {disk.centre + a * disk.u + b * disk.v, std::fabs(h)};
  }
  const Real shrink = disk.radius / rho;
  return {disk.centre + (shrink * a) * disk.u + (shrink * b) * disk.v,
          norm2(h, rho - disk.radius)};
}

struct Candidate {
  Vector3R p;  ///< on disk a
  Vector3R q;  ///< on disk b
  Real distance;
  ReferenceMethod method;
};

/// An angle held as (cos, sin). Long-double cos/sin cost ~150 ns each on x87,
/// so angles are built from a table plus a Taylor-series offset instead.
struct UnitAngle {
  Real c{1}, s{0};
};

constexpr Real kTwoPi = 6.283185307179586476925286766559005768L;

/// base rotated by delta, |delta| <= 0.1: the series are truncated after the
/// delta^11 / delta^12 terms, whose successors are < 1e-23.
inline UnitAngle offsetAngle(const UnitAngle& base, Real delta) {
  const Real d2 = delta * delta;
  // Horner form with constant reciprocals (x87 division is slow).
  const Real sin_d =
      delta * (1 - d2 * (1.0L / 6) *
                       (1 - d2 * (1.0L / 20) *
                                (1 - d2 * (1.0L / 42) *
                                         (1 - d2 * (1.0L / 72) * (1 - d2 * (1.0L / 110))))));
  const Real cos_d =
      1 - d2 * (1.0L / 2) *
              (1 - d2 * (1.0L / 12) *
                       (1 - d2 * (1.0L / 30) *
                                (1 - d2 * (1.0L / 56) *
                                         (1 - d2 * (1.0L / 90) * (1 - d2 * (1.0L / 132))))));
  return {base.c * cos_d - base.s * sin_d, base.s * cos_d + base.c * sin_d};
}

/// cos/sin of 2 pi k / kReferenceRimSamples, computed once.
inline const std::vector<UnitAngle>& baseAngleTable() {
  static const std::vector<UnitAngle> table = [] {
    std::vector<UnitAngle> t(kReferenceRimSamples);
    for (int k = 0; k < kReferenceRimSamples; ++k) {
      const Real theta = kTwoPi * k / kReferenceRimSamples;
      t[k] = {std::cos(theta), std::sin(theta)};
    }
    return t;
  }();
  return table;
}

/// Angle 2 pi k / samples (any k, any samples > 0), from the base table plus an
/// offset smaller than one base step.
inline UnitAngle gridAngle(long long k, long long samples) {
  k = ((k % samples) + samples) % samples;
  if (samples == kReferenceRimSamples) return baseAngleTable()[k];
  const long long base_index = k * kReferenceRimSamples / samples;
  const Real delta = kTwoPi * Real(k * kReferenceRimSamples - base_index * samples) /
                     (Real(samples) * kReferenceRimSamples);
  return offsetAngle(baseAngleTable()[base_index], delta);
}

/// F(theta) = dist(rim point of `rim_disk` at theta, `other`) and
/// G(theta) = d/dtheta F^2/2, both in `other`'s coordinates (a, b, h): the rim
/// point is base + cos(theta) col_cos + sin(theta) col_sin there, so each
/// evaluation is a few multiply-adds and two square roots.
class RimToDisk {
 public:
  RimToDisk(const RefDisk& rim_disk, const RefDisk& other) : rim_(rim_disk), other_(other) {
    Matrix3R to_other;
    to_other.row(0) = other.u.transpose();
    to_other.row(1) = other.v.transpose();
    to_other.row(2) = other.n.transpose();
    const Vector3R base = to_other * (rim_disk.centre - other.centre);
    const Vector3R col_cos = rim_disk.radius * (to_other * rim_disk.u);
    const Vector3R col_sin = rim_disk.radius * (to_other * rim_disk.v);
    for (int i = 0; i < 3; ++i) {
      base_[i] = base(i);
      col_cos_[i] = col_cos(i);
      col_sin_[i] = col_sin(i);
    }
  }

  Real radius() const { return rim_.radius; }

  // Plain scalars: Eigen's long-double temporaries are not inlined and tripled
  // the cost of this, the innermost function.
  void evaluate(const UnitAngle& angle, Real* f, Real* g) const {
    const Real x = base_[0] + angle.c * col_cos_[0] + angle.s * col_sin_[0];
    const Real y = base_[1] + angle.c * col_cos_[1] + angle.s * col_sin_[1];
    const Real z = base_[2] + angle.c * col_cos_[2] + angle.s * col_sin_[2];
    const Real dx = angle.c * col_sin_[0] - angle.s * col_cos_[0];
    const Real dy = angle.c * col_sin_[1] - angle.s * col_cos_[1];
    const Real dz = angle.c * col_sin_[2] - angle.s * col_cos_[2];
    const Real rho = norm2(x, y);
    const Real excess = rho - other_.radius;
    if (excess <= 0) {
      *f = std::fabs(z);
      *g = z * dz;
    } else {
      *f = norm2(z, excess);
      const Real k = excess / rho;
      *g = z * dz + k * (x * dx + y * dy);
    }
  }

  Real value(const UnitAngle& angle) const {
    Real f, g;
    evaluate(angle, &f, &g);
    return f;
  }

  Real slope(const UnitAngle& angle) const {
    Real f, g;
    evaluate(angle, &f, &g);
    return g;
  }

  Vector3R rimPoint(const UnitAngle& angle) const {
    return rim_.centre + rim_.radius * (angle.c * rim_.u + angle.s * rim_.v);
  }

 private:
  const RefDisk& rim_;
  const RefDisk& other_;
  Real base_[3], col_cos_[3], col_sin_[3];  ///< in other's (u, v, n) coordinates
};

struct RimMinimum {
  UnitAngle angle;
  Real value;
};

/// Refines a local minimum of F on the arc from `start` over `width` radians
/// (width <= 0.1). If G = d(F^2/2)/dtheta goes from - to + over the arc (the
/// usual case) bisection on G pins the angle to machine precision, which the
/// certificate needs when F is tiny; otherwise (G flat at rounding level, or a
/// kink) golden section on F gets the value to F's noise floor.
inline RimMinimum refineRimMinimum(const RimToDisk& fn, const UnitAngle& start, Real width) {
  auto at = [&start](Real delta) { return offsetAngle(start, delta); };
  const UnitAngle end = at(width);
  Real f_start, g_start, f_end, g_end;
  fn.evaluate(start, &f_start, &g_start);
  fn.evaluate(end, &f_end, &g_end);
  RimMinimum best = f_start <= f_end ? RimMinimum{start, f_start} : RimMinimum{end, f_end};
  auto consider = [&best](const UnitAngle& angle, Real f) {
    if (f < best.value) best = {angle, f};
  };

  if (g_start < 0 && g_end > 0) {
    Real left = 0, right = width;
    for (int iter = 0; iter < 200; ++iter) {
      const Real mid = left + (right - left) / 2;
      if (!(left < mid && mid < right)) break;
      if (fn.slope(at(mid)) < 0) {
        left = mid;
      } else {
        right = mid;
      }
    }
    for (Real t : {left, right}) consider(at(t), fn.value(at(t)));
    return best;
  }

  const Real inv_phi = (std::sqrt(Real(5)) - 1) / 2;
  Real a = 0, b = width;
  Real x1 = b - inv_phi * (b - a), x2 = a + inv_phi * (b - a);
  Real f1 = fn.value(at(x1)), f2 = fn.value(at(x2));
  consider(at(x1), f1);
  consider(at(x2), f2);
  for (int iter = 0; iter < 200 && a < x1 && x1 < x2 && x2 < b; ++iter) {
    if (f1 <= f2) {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - inv_phi * (b - a);
      f1 = fn.value(at(x1));
      consider(at(x1), f1);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + inv_phi * (b - a);
      f2 = fn.value(at(x2));
      consider(at(x2), f2);
    }
  }
  return best;
}

/// Rigorous lower bound of phi = F^2/2 on one sample interval of length step,
/// from the values and slopes at both ends. phi(theta) = psi(rim(theta)) with
/// psi = dist^2/2 convex and |grad psi| = F, and |rim''| = r, so
///   phi(theta0 + t) >= phi0 + g0 t - F0 r t^2 / 2
/// (and the mirror image from the right end). The bound is the minimum over the
/// interval of the larger of these two concave quadratics: it is attained at an
/// end or where they cross.
inline Real intervalLowerBoundPhi(Real f0, Real g0, Real f1, Real g1, Real r, Real step) {
  const Real phi0 = f0 * f0 / 2, phi1 = f1 * f1 / 2;
  const Real c0 = f0 * r / 2, c1 = f1 * r / 2;
  auto left = [&](Real t) { return phi0 + g0 * t - c0 * t * t; };
  auto right = [&](Real t) { return phi1 - g1 * (step - t) - c1 * (step - t) * (step - t); };
  auto upper_envelope = [&](Real t) { return std::max(left(t), right(t)); };
  Real bound = std::min(upper_envelope(0), upper_envelope(step));
  // left - right = k0 + k1 t + k2 t^2
  const Real k0 = phi0 - phi1 + g1 * step + c1 * step * step;
  const Real k1 = g0 - g1 - 2 * c1 * step;
  const Real k2 = c1 - c0;
  auto try_root = [&](Real t) {
    if (t > 0 && t < step) bound = std::min(bound, upper_envelope(t));
  };
  if (std::fabs(k2) * step <= 1e-6L * std::fabs(k1)) {
    if (k1 != 0) try_root(-k0 / k1);
  } else {
    const Real disc = k1 * k1 - 4 * k2 * k0;
    if (disc >= 0) {
      const Real sq = std::sqrt(disc);
      try_root((-k1 + sq) / (2 * k2));
      try_root((-k1 - sq) / (2 * k2));
    }
  }
  return bound;
}

/// Caps the refinements per rim in the first pass (brackets are refined in order
/// of their sampled value): functions that are flat to rounding (coaxial
/// circles) have a noise-induced local minimum every few samples, and refining
/// them all costs milliseconds without changing the answer. Passes after a
/// failed certificate refine every bracket.
constexpr int kReferenceFirstPassRefinements = 12;

/// Global minimum of F over the whole rim: sampling, bracket detection,
/// Lipschitz pruning, refinement. `best_so_far` (from other candidates) lets
/// brackets be skipped early; max_refinements < 0 means no cap.
inline RimMinimum minimiseOverRim(const RimToDisk& fn, int samples, Real best_so_far,
                                  Real noise, int max_refinements) {
  const Real step = kTwoPi / samples;
  std::vector<UnitAngle> angles(samples);
  std::vector<Real> f(samples), g(samples);
  for (int k = 0; k < samples; ++k) {
    angles[k] = gridAngle(k, samples);
    fn.evaluate(angles[k], &f[k], &g[k]);
  }

  RimMinimum best{angles[0], f[0]};
  for (int k = 1; k < samples; ++k)
    if (f[k] < best.value) best = {angles[k], f[k]};
  Real bound = std::min(best_so_far, best.value);

  struct Bracket {
    int first;  ///< sample index of the left end (may be -1: F is periodic)
    int width;  ///< in samples (1 or 2)
    Real key;   ///< smallest sampled F in the bracket, for ordering
    Real lower_bound_phi;  ///< rigorous lower bound of F^2/2 on the bracket
  };
  std::vector<Bracket> brackets;
  auto wrap = [samples](int k) { return (k % samples + samples) % samples; };
  auto interval_bound = [&](int k) {
    return intervalLowerBoundPhi(f[wrap(k)], g[wrap(k)], f[wrap(k + 1)], g[wrap(k + 1)],
                                 fn.radius(), step);
  };
  for (int k = 0; k < samples; ++k) {
    const Real prev = f[wrap(k - 1)], next = f[wrap(k + 1)];
    if (f[k] <= prev && f[k] <= next) {
      brackets.push_back({k - 1, 2, f[k], std::min(interval_bound(k - 1), interval_bound(k))});
    } else if (g[k] < 0 && g[wrap(k + 1)] > 0) {
      // A minimum between samples that the F comparison did not flag.
      brackets.push_back({k, 1, std::min(f[k], next), interval_bound(k)});
    }
  }
  std::sort(brackets.begin(), brackets.end(),
            [](const Bracket& x, const Bracket& y) { return x.key < y.key; });
  int refined = 0;
  for (const Bracket& br : brackets) {
    // Skip brackets that provably cannot beat what we have (up to noise).
    if (br.lower_bound_phi > bound * bound / 2 + noise * bound) continue;
    if (max_refinements >= 0 && refined >= max_refinements) break;
    ++refined;
    const RimMinimum m = refineRimMinimum(fn, angles[wrap(br.first)], step * br.width);
    if (m.value < best.value) best = m;
    bound = std::min(bound, best.value);
  }
  return best;
}

/// Duality lower bound for a unit direction w (pointing from disk a to disk b).
inline Real dualBound(const Vector3R& w, const RefDisk& a, const RefDisk& b) {
  const Real in_plane_a = norm2(a.u.dot(w), a.v.dot(w));
  const Real in_plane_b = norm2(b.u.dot(w), b.v.dot(w));
  return w.dot(b.centre - a.centre) - a.radius * in_plane_a - b.radius * in_plane_b;
}

/// Best certificate over a handful of directions; every unit w gives a valid
/// bound, so trying more can only tighten it.
inline Real certificate(const Candidate& best, const RefDisk& a, const RefDisk& b) {
  Real lower = 0;
  auto try_direction = [&](Vector3R w) {
    const Real len = w.norm();
    if (!(len > 0) || !std::isfinite(len)) return;
    w /= len;
    lower = std::max(lower, std::max(dualBound(w, a, b), dualBound(-w, a, b)));
  };
  try_direction(best.q - best.p);
  try_direction(a.n);
  try_direction(b.n);
  const Vector3R centre_line = b.centre - a.centre;
  try_direction(centre_line);
  try_direction(centre_line - a.n.dot(centre_line) * a.n);
  try_direction(centre_line - b.n.dot(centre_line) * b.n);
  // At a rim-rim optimum w is normal to both rim tangents: w ~ t1 x t2. This
  // direction stays accurate when |q - p| is too small to give one.
  const Vector3R tangent_a = a.n.cross(best.p - a.centre);
  const Vector3R tangent_b = b.n.cross(best.q - b.centre);
  try_direction(tangent_a.cross(tangent_b));
  // Face optimum with the other disk's extreme rim point: w = n.
  return lower;
}

inline void consider(Candidate* best, const Candidate& c) {
  if (c.distance < best->distance) *best = c;
}

/// (i): closed-form common point of the two disks, if the chords they cut on
/// L = plane_a ∩ plane_b overlap.
inline void intersectionCandidate(const RefDisk& a, const RefDisk& b, Candidate* best) {
  // e_a = projection of n_b onto a's plane (length sin angle), from in-plane
  // components so that a 1e-12 tilt keeps full relative precision.
  const Real nb_u = a.u.dot(b.n), nb_v = a.v.dot(b.n);
  const Real na_u = b.u.dot(a.n), na_v = b.v.dot(a.n);
  const Real sin_a = norm2(nb_u, nb_v), sin_b = norm2(na_u, na_v);
  if (!(sin_a > 0) || !(sin_b > 0)) return;  // parallel planes: handled by the face-face candidate
  const Vector3R e_a = nb_u * a.u + nb_v * a.v;
  const Vector3R e_b = na_u * b.u + na_v * b.v;
  const Real height_a_over_b = b.n.dot(a.centre - b.centre);
  const Real height_b_over_a = a.n.dot(b.centre - a.centre);
  const Real offset_a = std::fabs(height_a_over_b) / sin_a;  // centre a to L, in a's plane
  const Real offset_b = std::fabs(height_b_over_a) / sin_b;
  if (!(offset_a <= a.radius) || !(offset_b <= b.radius)) return;
  const Vector3R foot_a = a.centre - (height_a_over_b / (sin_a * sin_a)) * e_a;
  const Vector3R foot_b = b.centre - (height_b_over_a / (sin_b * sin_b)) * e_b;
  const Real half_a = std::sqrt((a.radius - offset_a) * (a.radius + offset_a));
  const Real half_b = std::sqrt((b.radius - offset_b) * (b.radius + offset_b));
  const Vector3R direction = a.n.cross(e_a) / sin_a;  // unit, along L
  const Real t_b = direction.dot(foot_b - foot_a);    // foot_a is t = 0
  const Real lo = std::max(-half_a, t_b - half_b);
  const Real hi = std::min(half_a, t_b + half_b);
  if (lo > hi) return;
  const Vector3R common = foot_a + ((lo + hi) / 2) * direction;
  const PointOnDisk p = closestPointOnDisk(common, a);
  const PointOnDisk q = closestPointOnDisk(common, b);
  consider(best, {p.point, q.point, (q.point - p.point).norm(), ReferenceMethod::intersection_chords});
}

/// (ii) for one face: the rim point of `rim_disk` extreme towards `face_disk`'s
/// plane on either side, projected onto `face_disk`. Both signs are tried; the
/// wrong side only gives a longer (still real) pair.
inline void faceCandidates(const RefDisk& face_disk, const RefDisk& rim_disk, bool face_is_a,
                           Candidate* best) {
  const Real nf_u = rim_disk.u.dot(face_disk.n), nf_v = rim_disk.v.dot(face_disk.n);
  const Real len = norm2(nf_u, nf_v);
  if (!(len > 0)) return;  // parallel: every rim point is equally extreme
  const Vector3R toward_normal = (nf_u / len) * rim_disk.u + (nf_v / len) * rim_disk.v;
  for (Real side : {Real(1), Real(-1)}) {
    // Lowest point along side * n_face: rim point c - side r P n / |P n|.
    const Vector3R rim_point = rim_disk.centre - side * rim_disk.radius * toward_normal;
    const PointOnDisk on_face = closestPointOnDisk(rim_point, face_disk);
    if (face_is_a) {
      consider(best, {on_face.point, rim_point, on_face.distance, ReferenceMethod::face1});
    } else {
      consider(best, {rim_point, on_face.point, on_face.distance, ReferenceMethod::face2});
    }
  }
}

/// (ii) for (nearly) parallel planes: a point of a over the middle of the overlap
/// of b's projection with a, along the line of centres.
inline void parallelFacesCandidate(const RefDisk& a, const RefDisk& b, Candidate* best) {
  const Vector3R rel = b.centre - a.centre;
  const Real x = a.u.dot(rel), y = a.v.dot(rel);
  const Real centre_gap = norm2(x, y);
  const Real lo = std::max(-a.radius, centre_gap - b.radius);
  const Real hi = std::min(a.radius, centre_gap + b.radius);
  if (lo > hi) return;
  const Real t = (lo + hi) / 2;
  Vector3R point = a.centre;
  if (centre_gap > 0) point += (t / centre_gap) * (x * a.u + y * a.v);
  const PointOnDisk p = closestPointOnDisk(point, a);
  const PointOnDisk q = closestPointOnDisk(p.point, b);
  consider(best, {p.point, q.point, q.distance, ReferenceMethod::parallel_faces});
}

}  // namespace detail

/// Reference distance between disks a and b (see the file comment for method
/// and accuracy). Works relative to a's centre; points are returned in the input
/// frame.
inline ReferenceResult referenceDiskDistance(const RefDisk& a_in, const RefDisk& b_in) {
  using namespace detail;
  const Vector3R origin = a_in.centre;
  RefDisk a = a_in, b = b_in;
  a.centre.setZero();
  b.centre = b_in.centre - origin;

  const Real scale = std::max(Real(1), a.radius + b.radius + b.centre.norm());
  // Rounding noise of one F evaluation: coordinates of size ~scale in long double.
  const Real noise = 64 * std::numeric_limits<Real>::epsilon() * scale;

  Candidate best{a.centre, b.centre, std::numeric_limits<Real>::infinity(),
                 ReferenceMethod::parallel_faces};
  intersectionCandidate(a, b, &best);
  parallelFacesCandidate(a, b, &best);
  faceCandidates(a, b, /*face_is_a=*/true, &best);
  faceCandidates(b, a, /*face_is_a=*/false, &best);

  const RimToDisk rim_a(a, b);
  const RimToDisk rim_b(b, a);
  Real lower = 0;
  int samples = kReferenceRimSamples;
  for (int pass = 0; pass <= kReferenceMaxRetries; ++pass) {
    const int max_refinements = pass == 0 ? kReferenceFirstPassRefinements : -1;
    const RimMinimum ma = minimiseOverRim(rim_a, samples, best.distance, noise, max_refinements);
    if (ma.value < best.distance) {
      const Vector3R p = rim_a.rimPoint(ma.angle);
      consider(&best, {p, closestPointOnDisk(p, b).point, ma.value, ReferenceMethod::rim1_search});
    }
    const RimMinimum mb = minimiseOverRim(rim_b, samples, best.distance, noise, max_refinements);
    if (mb.value < best.distance) {
      const Vector3R q = rim_b.rimPoint(mb.angle);
      consider(&best, {closestPointOnDisk(q, a).point, q, mb.value, ReferenceMethod::rim2_search});
    }
    lower = certificate(best, a, b);
    if (best.distance - lower <= kReferenceRetryGap * scale) break;
    if (pass < kReferenceMaxRetries) samples *= kReferenceRetryFactor;
  }

  ReferenceResult result;
  result.distance = best.distance;
  result.p1 = best.p + origin;
  result.p2 = best.q + origin;
  result.lower_bound = lower;  // not clamped: lower > distance would expose a bug
  result.scale = scale;
  result.method = best.method;
  result.rim_samples = samples;
  return result;
}

/// Convenience overload for Eigen isometries (double or float) and radii.
template <typename S>
ReferenceResult referenceDiskDistance(S r1, const Eigen::Transform<S, 3, Eigen::Isometry>& X_W1,
                                      S r2, const Eigen::Transform<S, 3, Eigen::Isometry>& X_W2) {
  return referenceDiskDistance(makeRefDisk(X_W1, r1), makeRefDisk(X_W2, r2));
}

/// Distance from a world point to a disk (closed form, long double), for
/// checking that reported nearest points lie on their disks.
inline Real referencePointToDisk(const Vector3R& x, const RefDisk& disk) {
  return detail::closestPointOnDisk(x, disk).distance;
}

}  // namespace fcl_disk_reference
