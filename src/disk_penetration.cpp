// Signed distance and exact penetration depth of two disks. Derivation and
// notation (F, Q, rho, L, K, the charts): docs/penetration_depth.md.
#include "fcl_disk/disk_penetration.h"

#include <array>
#include <cmath>
#include <complex>
#include <limits>

#include "fcl_disk/exact_distance.h"
#include "pair_in_frame1.h"

namespace fcl_disk {
namespace {

using internal::PairInFrame1;
using internal::Vec2;
using internal::Vec3;

/// Q's degree as a trigonometric polynomial, and the degree of the algebraic
/// polynomial it becomes on a chart (t = tan(theta / 2)).
constexpr int kTrigDegree = 4;
constexpr int kPolyDegree = 2 * kTrigDegree;
/// Samples that determine a trigonometric polynomial of degree 4.
constexpr int kSamples = 2 * kTrigDegree + 1;
constexpr double kPi = 3.141592653589793;

/// A rim point of disk 2 closer than this (in scene sizes) to disk 1's axis has
/// no well-defined nearest point on rim 1; its partners are found from the
/// tangent condition instead. Above it the radial direction of a is known to
/// at least 1e-10 relative, far inside what the candidate needs.
constexpr double kOnAxisTolerance = 1e-6;

/// Q counts as vanishing identically when no coefficient exceeds this many
/// times the size of its terms rho^2 L^2 and r1^2 K^2 (their rounding is
/// ~1e-16 of it); then kFixedAnglesWhenQVanishes rim angles are the candidates.
constexpr double kQVanishes = 1e-12;
constexpr int kFixedAnglesWhenQVanishes = 64;

/// F at a kink within this of 0 (scene sizes: a few ulps, F's rounding) is PD = 0.
constexpr double kZeroDepth = 8 * std::numeric_limits<double>::epsilon();

/// Two rim points closer than this (scene sizes) give no direction b - a, and
/// tangents whose cross product is shorter than this no direction t1 x t2
/// (each known to ~1e-16: the direction to ~1e-7, an O(1e-14) error in F).
constexpr double kCoincidentRimPoints = 1e-9;
constexpr double kParallelTangents = 1e-9;

/// The witness of a disk is its support point along +-w unless |P w| is below
/// this (w within ~1e-9 rad of the disk's normal: the support point is then a
/// face point, fixed by the other disk's witness).
constexpr double kAlongNormal = 1e-9;

/// A rim pair (b, a) serves as the witnesses when |b - a - PD w| is below this
/// (scene sizes): 10x inside the 1e-12 promise for the witnesses, far above
/// the rounding of b, a and PD and the square of a root's error.
constexpr double kWitnessResidual = 1e-13;

/// The best rim pair is polished by at most kPolishIterations Newton steps,
/// stopped at a step (radians, summed over both angles) below
/// kPolishConverged (the resolution of an angle) or above kMaxPolishStep (the
/// pair was not next to a regular critical pair: kept as it is). The polished
/// pair is kept when its F exceeds the best by at most kPolishSlack (scene
/// sizes: rounding; both values are upper bounds on PD).
constexpr int kPolishIterations = 4;
constexpr double kPolishConverged = 1e-15;
constexpr double kMaxPolishStep = 0.1;
constexpr double kPolishSlack = 1e-15;

/// Root polishing stops at a Newton step (or bracket) this small in t (t lies
/// in [-1, 1]): 8 ulps of 1, the resolution of t, so the rim points and their
/// tangents are as accurate as double allows (the witnesses are support
/// points along the direction they give); or after kMaxRootIterations steps
/// (bisection alone needs ~50).
constexpr double kRootTolerance = 8 * std::numeric_limits<double>::epsilon();
constexpr int kMaxRootIterations = 100;
/// Horner's scheme for a degree-8 polynomial at |t| <= 1 rounds by at most
/// ~2 * 8 ulps of sum |p_j|: 32 ulps; once |p(t)| is below that, t is the root
/// to the polynomial's own resolution and further steps only chase rounding.
constexpr double kEvaluationRounding = 32 * std::numeric_limits<double>::epsilon();

// ---------------------------------------------------------------------------
// Trigonometric polynomials of degree 4 in real form:
// f(theta) = C[0] + sum_{k=1..4} C[k] cos(k theta) + S[k] sin(k theta).

struct TrigPolynomial {
  std::array<double, kTrigDegree + 1> C{}, S{};  // S[0] unused (0)

  /// The coefficients of the degree-4 trigonometric polynomial with values
  /// f(theta_j) at theta_j = 2 pi j / 9, j = 0..8: the discrete Fourier
  /// transform, exact for this degree (9 samples, no aliasing).
  static TrigPolynomial fromSamples(const std::array<double, kSamples>& values) {
    struct Table {
      double cos_kj[kTrigDegree + 1][kSamples], sin_kj[kTrigDegree + 1][kSamples];
      Table() {
        for (int k = 0; k <= kTrigDegree; ++k) {
          for (int j = 0; j < kSamples; ++j) {
            const double angle = 2 * kPi * k * j / kSamples;
            cos_kj[k][j] = std::cos(angle);
            sin_kj[k][j] = std::sin(angle);
          }
        }
      }
    };
    static const Table table;
    TrigPolynomial f;
    for (int k = 0; k <= kTrigDegree; ++k) {
      double c = 0, s = 0;
      for (int j = 0; j < kSamples; ++j) {
        c += values[j] * table.cos_kj[k][j];
        s += values[j] * table.sin_kj[k][j];
      }
      const double weight = (k == 0 ? 1.0 : 2.0) / kSamples;
      f.C[k] = weight * c;
      f.S[k] = k == 0 ? 0.0 : weight * s;
    }
    return f;
  }
};

/// cos and sin of the N angles 2 pi k / N.
template <int N>
struct AngleTable {
  std::array<double, N> cos, sin;
  AngleTable() {
    for (int k = 0; k < N; ++k) {
      cos[k] = std::cos(2 * kPi * k / N);
      sin[k] = std::sin(2 * kPi * k / N);
    }
  }
};

/// An algebraic polynomial p[0] + p[1] t + ... + p[8] t^8.
using Polynomial = std::array<double, kPolyDegree + 1>;

/// (1 + t^2)^4 cos(k theta) and (1 + t^2)^4 sin(k theta) at theta = 2 atan(t):
/// the real and imaginary parts of (1 + i t)^(2k) (1 + t^2)^(4 - k), since
/// e^{i theta} = (1 + i t)^2 / (1 + t^2). Integer coefficients.
struct ChartBasis {
  std::array<Polynomial, kTrigDegree + 1> cos_k{}, sin_k{};
  ChartBasis() {
    for (int k = 0; k <= kTrigDegree; ++k) {
      // (1 + i t)^(2k) = sum_j binom(2k, j) i^j t^j.
      using Complex = std::complex<double>;
      std::array<Complex, kPolyDegree + 1> power{};
      double binom = 1;
      for (int j = 0; j <= 2 * k; ++j) {
        static constexpr Complex kIPowers[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
        power[j] = binom * kIPowers[j % 4];
        binom = binom * (2 * k - j) / (j + 1);
      }
      // times (1 + t^2)^(4 - k) = sum_l binom(4 - k, l) t^(2l).
      double binom_l = 1;
      for (int l = 0; l <= kTrigDegree - k; ++l) {
        for (int j = 0; j <= 2 * k; ++j) {
          cos_k[k][j + 2 * l] += binom_l * power[j].real();
          sin_k[k][j + 2 * l] += binom_l * power[j].imag();
        }
        binom_l = binom_l * (kTrigDegree - k - l) / (l + 1);
      }
    }
  }
};

/// f on the chart theta = offset + 2 atan(t), times (1 + t^2)^4; offset 0 or
/// pi (cos and sin of k(pi + phi) are (-1)^k those of k phi).
Polynomial onChart(const TrigPolynomial& f, bool shifted_by_pi) {
  static const ChartBasis basis;
  Polynomial p{};
  for (int k = 0; k <= kTrigDegree; ++k) {
    const double sign = shifted_by_pi && k % 2 == 1 ? -1.0 : 1.0;
    const double C = sign * f.C[k], S = sign * f.S[k];
    for (int j = 0; j <= kPolyDegree; ++j) p[j] += C * basis.cos_k[k][j] + S * basis.sin_k[k][j];
  }
  return p;
}

double evaluate(const double* p, int degree, double t) {
  double value = p[degree];
  for (int j = degree - 1; j >= 0; --j) value = value * t + p[j];
  return value;
}

/// The root of p in [lo, hi], where p(lo) and p(hi) have opposite signs:
/// Newton steps kept inside the bracket, bisection when a step would leave it.
double rootInBracket(const double* p, const double* dp, int degree, double lo, double hi,
                     double p_lo) {
  // Start where the chord between the bracket's ends crosses zero.
  const double p_hi = evaluate(p, degree, hi);
  double t = p_hi != p_lo ? lo - p_lo * (hi - lo) / (p_hi - p_lo) : 0.5 * (lo + hi);
  if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
  // Horner's rounding bound at |t| <= 1: a value below it carries no sign.
  double magnitude = 0.0;
  for (int j = 0; j <= degree; ++j) magnitude += std::abs(p[j]);
  const double value_at_rounding = kEvaluationRounding * magnitude;
  for (int i = 0; i < kMaxRootIterations && hi - lo > kRootTolerance; ++i) {
    const double value = evaluate(p, degree, t);
    if (std::abs(value) <= value_at_rounding) return t;
    if ((value < 0) == (p_lo < 0)) {
      lo = t;
      p_lo = value;
    } else {
      hi = t;
    }
    const double slope = evaluate(dp, degree - 1, t);
    const double newton = slope != 0.0 ? t - value / slope : lo - 1;
    if (!(newton > lo && newton < hi)) {
      t = 0.5 * (lo + hi);
      continue;
    }
    // Newton converges from one side, so the bracket need not shrink: stop
    // on a step at the resolution of t.
    const bool converged = std::abs(newton - t) <= kRootTolerance;
    t = newton;
    if (converged) break;
  }
  return t;
}

/// p in the Bernstein basis of [-1, 1]: p(t) = sum_i b_i binom(8, i) s^i (1 - s)^(8 - i)
/// with t = 2 s - 1. By Descartes' rule for this basis, p has at most as many
/// roots in the interval as b has sign changes, and the same parity.
using Bernstein = std::array<double, kPolyDegree + 1>;

Bernstein toBernstein(const Polynomial& p) {
  // q(s) = p(2 s - 1) by Horner's scheme on polynomials in s.
  Polynomial q{};
  for (int j = kPolyDegree; j >= 0; --j) {
    for (int i = kPolyDegree; i >= 1; --i) q[i] = 2 * q[i - 1] - q[i];
    q[0] = p[j] - q[0];
  }
  // b_i = sum_{j <= i} binom(i, j) / binom(8, j) q_j.
  struct Weights {
    double w[kPolyDegree + 1][kPolyDegree + 1] = {};
    Weights() {
      static constexpr double kBinom8[kPolyDegree + 1] = {1, 8, 28, 56, 70, 56, 28, 8, 1};
      for (int i = 0; i <= kPolyDegree; ++i) {
        double binom_ij = 1;  // binom(i, j)
        for (int j = 0; j <= i; ++j) {
          w[i][j] = binom_ij / kBinom8[j];
          binom_ij = binom_ij * (i - j) / (j + 1);
        }
      }
    }
  };
  static const Weights weights;
  Bernstein b{};
  for (int i = 0; i <= kPolyDegree; ++i) {
    for (int j = 0; j <= i; ++j) b[i] += weights.w[i][j] * q[j];
  }
  return b;
}

int signChanges(const Bernstein& b) {
  int changes = 0;
  double last = 0.0;
  for (const double x : b) {
    if (x == 0.0) continue;
    if (last != 0.0 && (x < 0) != (last < 0)) ++changes;
    last = x;
  }
  return changes;
}

/// Subdivisions of [-1, 1] before an undecided interval (more than one sign
/// change, or none but a coefficient within the noise: a double root, or a
/// pair of roots rounding may merge) is taken as one candidate, its midpoint:
/// 2^-24 wide in t, within 6e-8 of the root(s), where F, stationary, is off by
/// ~1e-15 of the scene, and the best candidate is then polished anyway.
constexpr int kMaxSubdivisions = 24;

/// Bernstein coefficients within this many times the size of Q's terms (see
/// kQVanishes) of zero may be rounding: ~5e4 ulps, far above the rounding the
/// sampling, the Fourier transform and the change of basis leave (~1e3 ulps of
/// the chart polynomial, which is up to 16 Q), far below any coefficient a
/// clear sign carries.
constexpr double kBernsteinNoise = 1e-11;


/// At most this many intervals are examined per polynomial (a degree-8
/// polynomial with simple roots needs a few dozen); past it, each interval
/// left is taken as one candidate (its midpoint). Bounds the work when
/// rounding scatters sign changes through nearly vanishing coefficients.
constexpr int kMaxIntervals = 256;

/// Candidates one chart can yield: at most 8 roots and 7 extrema, the ends of
/// undecided intervals where |p| is within the noise, one midpoint per
/// undecided leaf, and one per interval left when the budget runs out.
constexpr int kMaxChartCandidates = 2 * kMaxIntervals + 2 * kPolyDegree;

/// Real roots of p (monomial basis) in [-1, 1], written to `out` (at most
/// kMaxChartCandidates), by Bernstein subdivision (de Casteljau halves). An
/// interval's ends are candidates where |p| is within `noise`, and the interval
/// is decided when its coefficients show
/// - no sign change and none within `noise` of zero: |p| > noise, no root;
/// - one sign change between its ends: one root, bracketed and polished;
/// - otherwise, when the coefficients of p' (n (b_{i+1} - b_i)) change sign at
///   most once: p has at most one extremum there, found by Newton within its
///   bracket and taken as a candidate (it marks a double root, or two roots
///   rounding may merge), and p is monotone on either side of it, so each side
///   holds a root exactly when p changes sign over it.
/// Undecided intervals are halved, down to kMaxSubdivisions (then the midpoint
/// is the candidate), within a budget of kMaxIntervals.
int rootsOnChart(const Polynomial& p, double noise, double* out) {
  Polynomial dp{}, ddp{};
  for (int j = 0; j < kPolyDegree; ++j) dp[j] = (j + 1) * p[j + 1];
  for (int j = 0; j + 1 < kPolyDegree; ++j) ddp[j] = (j + 1) * dp[j + 1];
  int count = 0;
  const auto add = [&](double t) {
    if (count < kMaxChartCandidates) out[count++] = t;
  };
  // The root of p in [lo, hi] if p changes sign over it (values given).
  const auto rootIfSignChange = [&](double lo, double hi, double p_lo, double p_hi) {
    if (p_lo == 0.0) {
      add(lo);
    } else if (p_hi != 0.0 && (p_lo < 0) != (p_hi < 0)) {
      add(rootInBracket(p.data(), dp.data(), kPolyDegree, lo, hi, p_lo));
    }
  };
  struct Interval {
    Bernstein b;
    double lo, hi;
    int depth;
  };
  std::array<Interval, kMaxSubdivisions + 2> stack;
  int size = 0, examined = 0;
  stack[size++] = {toBernstein(p), -1.0, 1.0, 0};
  while (size > 0) {
    const Interval interval = stack[--size];
    const double mid = 0.5 * (interval.lo + interval.hi);
    if (++examined > kMaxIntervals) {
      add(mid);
      continue;
    }
    const Bernstein& b = interval.b;
    // An end within the noise of zero may be a root that does not change sign
    // (a double root where a halving fell, as on the symmetry axis of a
    // symmetric pair): a candidate, whatever the interior holds.
    if (std::abs(b[0]) <= noise) add(interval.lo);
    if (std::abs(b[kPolyDegree]) <= noise) add(interval.hi);
    const int changes = signChanges(b);
    if (changes == 0) {
      double smallest = std::abs(b[0]);
      for (const double x : b) smallest = std::min(smallest, std::abs(x));
      if (smallest > noise) continue;  // |p| > noise on the interval: no root
    }
    if (changes == 1 && b[0] != 0.0 && b[kPolyDegree] != 0.0) {  // the ends differ in sign
      rootIfSignChange(interval.lo, interval.hi, b[0], b[kPolyDegree]);
      continue;
    }
    std::array<double, kPolyDegree> derivative;  // p' in the Bernstein basis, up to a factor
    for (int i = 0; i < kPolyDegree; ++i) derivative[i] = b[i + 1] - b[i];
    int derivative_changes = 0;
    double last = 0.0;
    for (const double x : derivative) {
      if (x == 0.0) continue;
      if (last != 0.0 && (x < 0) != (last < 0)) ++derivative_changes;
      last = x;
    }
    if (derivative_changes == 0) {  // p monotone: a root iff it changes sign
      rootIfSignChange(interval.lo, interval.hi, b[0], b[kPolyDegree]);
      continue;
    }
    if (derivative_changes == 1 && derivative[0] != 0.0 && derivative[kPolyDegree - 1] != 0.0) {
      const double extremum = rootInBracket(dp.data(), ddp.data(), kPolyDegree - 1, interval.lo,
                                            interval.hi, derivative[0]);
      add(extremum);
      const double p_extremum = evaluate(p.data(), kPolyDegree, extremum);
      rootIfSignChange(interval.lo, extremum, b[0], p_extremum);
      if (p_extremum != 0.0) rootIfSignChange(extremum, interval.hi, p_extremum, b[kPolyDegree]);
      continue;
    }
    if (interval.depth >= kMaxSubdivisions || size + 2 > int(stack.size())) {
      add(mid);
      continue;
    }
    // de Casteljau at s = 1/2: the left half's coefficients are the first
    // entries of each level, the right half's the last.
    Interval left{{}, interval.lo, mid, interval.depth + 1};
    Interval right{{}, mid, interval.hi, interval.depth + 1};
    Bernstein level = b;
    for (int r = 0; r <= kPolyDegree; ++r) {
      left.b[r] = level[0];
      right.b[kPolyDegree - r] = level[kPolyDegree - r];
      for (int i = 0; i < kPolyDegree - r; ++i) level[i] = 0.5 * (level[i] + level[i + 1]);
    }
    stack[size++] = right;
    stack[size++] = left;
  }
  return count;
}

// ---------------------------------------------------------------------------
// The pair in disk 1's frame, lengths in scene sizes.

struct Penetration {
  double depth;  ///< PD, scene sizes.
  Vec3 w;        ///< unit minimiser, frame 1.
  Vec3 p1, p2;   ///< witnesses, frame 1, scene sizes.
};

class PenetrationSearch {
 public:
  explicit PenetrationSearch(const PairInFrame1& pair)
      : c_(pair.c), u_(pair.R.col(0)), v_(pair.R.col(1)), r1_(pair.r1), r2_(pair.r2) {}

  /// F(w) = -c.w + r1 |P1 w| + r2 |P2 w|: translating disk 2 by t w separates
  /// the disks for every t > F(w). Keeps the smallest, with the rim points
  /// (b of disk 1, a of disk 2) the direction came from, if any.
  void consider(const Vec3& w, const Vec3* b = nullptr, const Vec3* a = nullptr) {
    const double p1 = std::sqrt(w.x() * w.x() + w.y() * w.y());
    const double in_plane2_u = u_.dot(w), in_plane2_v = v_.dot(w);
    const double value = -c_.dot(w) + r1_ * p1 +
                         r2_ * std::sqrt(in_plane2_u * in_plane2_u + in_plane2_v * in_plane2_v);
    if (!(value < best_.value)) return;
    best_.value = value;
    best_.w = w;
    best_.from_rims = b != nullptr;
    if (b) best_.b = *b, best_.a = *a;
  }

  /// The candidates of rim angle theta of disk 2 (given as cos, sin): its rim
  /// point a and the rim points b of disk 1 that make (b, a) critical for the
  /// distance between the rims (nearest and farthest to a), each giving the
  /// direction (b - a) / |b - a|.
  void considerRimAngle(double cos_theta, double sin_theta) {
    const Vec3 e2 = cos_theta * u_ + sin_theta * v_;  // outward radial of disk 2 at a
    const Vec3 a = c_ + r2_ * e2;
    const Vec3 t2 = -sin_theta * u_ + cos_theta * v_;
    const double rho = std::sqrt(a.x() * a.x() + a.y() * a.y());
    if (rho > kOnAxisTolerance) {
      const Vec3 radial(a.x() / rho, a.y() / rho, 0.0);
      considerPair(r1_ * radial, a, t2, e2);
      considerPair(-r1_ * radial, a, t2, e2);
      return;
    }
    // a on (or next to) disk 1's axis: every rim point of disk 1 is (nearly)
    // as far; the critical ones satisfy (b - a).t2 = 0, i.e.
    // r1 (t2x cos phi + t2y sin phi) = a.t2.
    const double m = std::sqrt(t2.x() * t2.x() + t2.y() * t2.y());
    const double target = a.dot(t2);
    if (!(r1_ * m >= std::abs(target)) || m == 0.0) return;
    const double base = std::atan2(t2.y(), t2.x());
    const double spread = std::acos(target / (r1_ * m));
    for (const double phi : {base + spread, base - spread}) {
      considerPair(Vec3(r1_ * std::cos(phi), r1_ * std::sin(phi), 0.0), a, t2, e2);
    }
  }

  /// A critical pair of the rims (b on rim 1, a on rim 2): b - a is normal to
  /// both tangents, so the directions are +-(b - a) / |b - a| (+ for an
  /// overlap, b - a = PD w; - for disks apart, where min F = -d) and +-t1 x t2,
  /// the same line without the cancellation of b - a for nearby rim points.
  /// Where the rims meet with parallel tangents (t1 x t2 = 0, b = a), a
  /// separating direction lies in both normal cones, {alpha n1 + beta e1,
  /// beta >= 0} and minus disk 2's, {alpha n2 - beta e2}: in a sector of the
  /// plane normal to the tangents whose edges include e1 and -e2 (the normals
  /// are the kinks, considered already).
  void considerPair(const Vec3& b, const Vec3& a, const Vec3& t2, const Vec3& e2) {
    const Vec3 gap = b - a;
    const double length = gap.norm();
    if (length > kCoincidentRimPoints) {
      consider(gap / length, &b, &a);
      consider(-gap / length, &b, &a);
    }
    const Vec3 e1 = b / r1_;
    const Vec3 t1(-e1.y(), e1.x(), 0.0);
    const Vec3 normal = t1.cross(t2);
    const double normal_length = normal.norm();
    if (normal_length > kParallelTangents) {
      consider(normal / normal_length, &b, &a);
      consider(-normal / normal_length, &b, &a);
    } else if (length <= kCoincidentRimPoints) {
      consider(e1, &b, &a);
      consider(-e2, &b, &a);
    }
  }

  /// Newton's method on the critical-pair equations of the rims,
  /// d/dphi |b - a|^2 = d/dtheta |b - a|^2 = 0, from the best rim pair: a root
  /// of Q is known only as well as Q's conditioning allows (to ~sqrt(eps) at a
  /// near-double root), and the witnesses need b - a along w to rounding. The
  /// polished pair replaces the best when its F is as small, to rounding.
  void polishBestRimPair() {
    if (!best_.from_rims) return;
    // The angles as unit vectors (cos, sin), turned by each Newton step and
    // renormalised: exact to third order in the step, no sin/cos per step.
    Vec2 phi = Vec2(best_.b.x(), best_.b.y()).normalized();
    const Vec3 e2_start = best_.a - c_;
    Vec2 theta = Vec2(e2_start.dot(u_), e2_start.dot(v_)).normalized();
    const auto turn = [](Vec2& angle, double step) {
      angle = Vec2(angle.x() - step * angle.y(), angle.y() + step * angle.x()).normalized();
    };
    for (int i = 0; i < kPolishIterations; ++i) {
      const Vec3 b(r1_ * phi.x(), r1_ * phi.y(), 0.0), db(-r1_ * phi.y(), r1_ * phi.x(), 0.0);
      const Vec3 e2 = theta.x() * u_ + theta.y() * v_;
      const Vec3 a = c_ + r2_ * e2, da = r2_ * (theta.x() * v_ - theta.y() * u_);
      const Vec3 g = b - a;
      const double grad_phi = g.dot(db), grad_theta = -g.dot(da);
      const double h_pp = db.dot(db) - g.dot(b), h_tt = da.dot(da) + r2_ * g.dot(e2);
      const double h_pt = -db.dot(da);
      const double det = h_pp * h_tt - h_pt * h_pt;
      if (!(std::abs(det) > 0.0)) break;
      const double step_phi = -(h_tt * grad_phi - h_pt * grad_theta) / det;
      const double step_theta = -(h_pp * grad_theta - h_pt * grad_phi) / det;
      const double step = std::abs(step_phi) + std::abs(step_theta);
      if (!(step < kMaxPolishStep)) break;  // not next to a regular critical pair
      turn(phi, step_phi);
      turn(theta, step_theta);
      if (step < kPolishConverged) break;
    }
    const Vec3 e2 = theta.x() * u_ + theta.y() * v_;
    const Vec3 a = c_ + r2_ * e2;
    const Vec3 b(r1_ * phi.x(), r1_ * phi.y(), 0.0);
    const Best before = best_;
    best_.value = std::numeric_limits<double>::infinity();
    considerPair(b, a, theta.x() * v_ - theta.y() * u_, e2);
    if (!(best_.value <= before.value + kPolishSlack)) best_ = before;
  }

  struct Best {
    double value = std::numeric_limits<double>::infinity();
    Vec3 w = Vec3::UnitZ();
    bool from_rims = false;  ///< w came from the rim pair (b, a), not a kink
    Vec3 b = Vec3::Zero(), a = Vec3::Zero();
  };
  const Best& best() const { return best_; }

 private:
  Vec3 c_, u_, v_;
  double r1_, r2_;
  Best best_;
};

/// The penetration with its witnesses. From a rim pair: its two rim points
/// (on the disks exactly, and b - a = PD w up to the square of the root's
/// error, b - a being stationary there). Otherwise (a kink): the support point of the
/// disk whose plane w is farther from normal to (a rim point), the other one
/// PD * w away (on the face of the disk w is normal to).
Penetration withWitnesses(const PairInFrame1& pair, const PenetrationSearch::Best& best) {
  const Vec3& w = best.w;
  Penetration out{best.value, w, Vec3::Zero(), Vec3::Zero()};
  // The rim pair is the support pair along w only if b - a = PD w; a pair
  // whose t1 x t2 merely lies along w is not.
  if (best.from_rims && (best.b - best.a - best.value * w).norm() <= kWitnessResidual) {
    out.p1 = best.b;
    out.p2 = best.a;
    return out;
  }
  const double in_plane1 = std::sqrt(w.x() * w.x() + w.y() * w.y());
  const double in_plane2 = pair.inPlane2(w);
  if (std::max(in_plane1, in_plane2) < kAlongNormal) {
    // Parallel planes: w is the common normal; coplanar (PD = 0 up to rounding).
    const auto common = internal::commonPoint(pair);
    out.p1 = out.p2 = common ? *common : Vec3(0.0, 0.0, 0.5 * pair.c.z());
  } else if (in_plane2 >= in_plane1) {
    const Vec3 P2w = pair.R.col(0).dot(w) * pair.R.col(0) + pair.R.col(1).dot(w) * pair.R.col(1);
    out.p2 = pair.c - (pair.r2 / in_plane2) * P2w;
    out.p1 = out.p2 + best.value * w;
  } else {
    out.p1 = Vec3(w.x(), w.y(), 0.0) * (pair.r1 / in_plane1);
    out.p2 = out.p1 - best.value * w;
  }
  return out;
}

/// The penetration of a pair in frame 1 whose lengths are in scene sizes.
/// `swapped`: the pair's disk 1 is the caller's disk 2 (the caller negates w),
/// which only changes the order of the kinks so that the tie-break is the
/// caller's +n1 either way.
Penetration penetrationInFrame1(const PairInFrame1& pair, bool swapped) {
  PenetrationSearch search(pair);
  // Disk 2's kinks are where |P2 w| = sqrt((u.w)^2 + (v.w)^2) vanishes, along
  // u x v: R's third column only to within an accepted rotation's defect.
  const Vec3 n2 = pair.R.col(0).cross(pair.R.col(1)).normalized();
  // The kinks first: their order is the documented tie-break (the caller's
  // +n1, -n1, +n2, -n2).
  if (swapped) {
    for (const Vec3& kink : {Vec3(-n2), n2, Vec3(-Vec3::UnitZ()), Vec3(Vec3::UnitZ())}) {
      search.consider(kink);
    }
  } else {
    for (const Vec3& kink : {Vec3(Vec3::UnitZ()), Vec3(-Vec3::UnitZ()), n2, Vec3(-n2)}) {
      search.consider(kink);
    }
  }
  // PD >= 0 for disks that share a point and every F(w) >= PD: a kink at 0 to
  // rounding (coplanar overlapping disks, a rim on the other's face) is the
  // minimum. (Apart pairs have min F = -d < 0: only touching ones stop here.)
  if (std::abs(search.best().value) <= kZeroDepth) {
    return withWitnesses(pair, search.best());
  }

  // Q(theta) = rho^2 L^2 - r1^2 K^2 along disk 2's rim a(theta) = c + r2 (cos u + sin v).
  const Vec3& c = pair.c;
  const Vec3 u = pair.R.col(0), v = pair.R.col(1);
  const double r1 = pair.r1, r2 = pair.r2;
  std::array<double, kSamples> samples;
  double terms = 0.0;  // the size of Q's two terms, for its rounding
  static const AngleTable<kSamples> sample_angles;
  for (int j = 0; j < kSamples; ++j) {
    const double cos_theta = sample_angles.cos[j], sin_theta = sample_angles.sin[j];
    const Vec3 a = c + r2 * (cos_theta * u + sin_theta * v);   // rim point
    const Vec3 da = r2 * (cos_theta * v - sin_theta * u);      // its derivative
    const double rho2 = a.x() * a.x() + a.y() * a.y();
    const double K = a.x() * da.x() + a.y() * da.y();  // (rho^2)' / 2
    const double L = c.dot(da);                        // (|a|^2)' / 2
    samples[j] = rho2 * L * L - r1 * r1 * K * K;
    terms = std::max(terms, rho2 * L * L + r1 * r1 * K * K);
  }
  const TrigPolynomial Q = TrigPolynomial::fromSamples(samples);
  double largest_coefficient = 0.0;
  for (int k = 0; k <= kTrigDegree; ++k) {
    largest_coefficient = std::max({largest_coefficient, std::abs(Q.C[k]), std::abs(Q.S[k])});
  }
  if (!(largest_coefficient > kQVanishes * terms)) {
    // Q = 0 to rounding: every rim angle is critical (rims at a constant
    // distance: coaxial disks, or rim 2 a Villarceau circle of a torus about
    // rim 1); the candidates are kFixedAnglesWhenQVanishes angles.
    static const AngleTable<kFixedAnglesWhenQVanishes> angles;
    for (int k = 0; k < kFixedAnglesWhenQVanishes; ++k) {
      search.considerRimAngle(angles.cos[k], angles.sin[k]);
    }
    search.polishBestRimPair();
    return withWitnesses(pair, search.best());
  }

  // Candidate angles: the roots of Q on both charts, and the midpoints of the
  // intervals where it may have a double root.
  for (const bool shifted : {false, true}) {
    std::array<double, kMaxChartCandidates> ts;
    const int num = rootsOnChart(onChart(Q, shifted), kBernsteinNoise * terms, ts.data());
    const double sign = shifted ? -1.0 : 1.0;
    for (int i = 0; i < num; ++i) {
      const double t = ts[i], denominator = 1.0 + t * t;
      search.considerRimAngle(sign * (1.0 - t * t) / denominator, sign * 2.0 * t / denominator);
    }
  }

  search.polishBestRimPair();
  return withWitnesses(pair, search.best());
}

template <typename S>
DiskSignedDistanceResult<S> nanSignedDistance() {
  const S nan = std::numeric_limits<S>::quiet_NaN();
  DiskSignedDistanceResult<S> result;
  result.signed_distance = nan;
  result.p_W1.setConstant(nan);
  result.p_W2.setConstant(nan);
  result.direction.setConstant(nan);
  return result;
}

}  // namespace

template <typename S>
DiskSignedDistanceResult<S> diskPenetration(S r1, const fcl::Transform3<S>& X_W1, S r2,
                                            const fcl::Transform3<S>& X_W2) {
  if (!internal::isValidDiskPair(r1, X_W1, r2, X_W2)) return nanSignedDistance<S>();
  // Q parameterises the rim of the pair's disk 2 and measures from disk 1's
  // axis: with the smaller disk as disk 2 its terms are of the size of its
  // features (with a disk 1e-5 the size of the other as disk 2's partner,
  // Q's structure near the small disk would sit 1e-20 below its terms, under
  // the rounding).
  const bool swapped = r2 > r1;
  const auto& X_WA = swapped ? X_W2 : X_W1;  // the frame the search runs in
  const PairInFrame1 pair = swapped ? PairInFrame1::fromWorld(r2, X_W2, r1, X_W1)
                                    : PairInFrame1::fromWorld(r1, X_W1, r2, X_W2);
  const double scale = pair.scale();
  const PairInFrame1 unit_pair =
      PairInFrame1::make(pair.c / scale, pair.R, pair.r1 / scale, pair.r2 / scale);
  const Penetration found = penetrationInFrame1(unit_pair, swapped);

  const internal::Mat3 R_WA = X_WA.linear().template cast<double>();
  const Vec3 c_A = X_WA.translation().template cast<double>();
  const Vec3 p_WA = c_A + R_WA * (found.p1 * scale), p_WB = c_A + R_WA * (found.p2 * scale);
  DiskSignedDistanceResult<S> result;
  result.signed_distance = S(-found.depth * scale);
  result.p_W1 = (swapped ? p_WB : p_WA).template cast<S>();
  result.p_W2 = (swapped ? p_WA : p_WB).template cast<S>();
  // Normalised: R_WA is orthonormal only to within kRotationDefectTolerance.
  // Swapped, w moves the caller's disk 1: disk 2 moves along -w.
  const Vec3 w_W = (R_WA * found.w).normalized();
  result.direction = (swapped ? Vec3(-w_W) : w_W).template cast<S>();
  return result;
}

template <typename S>
DiskSignedDistanceResult<S> signedDiskDistance(S r1, const fcl::Transform3<S>& X_W1, S r2,
                                               const fcl::Transform3<S>& X_W2) {
  const DiskDistanceResult<S> apart = exactDiskDistance(r1, X_W1, r2, X_W2);
  if (std::isnan(apart.distance)) return nanSignedDistance<S>();
  if (!(apart.distance > 0)) return diskPenetration(r1, X_W1, r2, X_W2);
  DiskSignedDistanceResult<S> result;
  result.signed_distance = apart.distance;
  result.p_W1 = apart.p_W1;
  result.p_W2 = apart.p_W2;
  result.direction = (apart.p_W2.template cast<double>() - apart.p_W1.template cast<double>())
                         .normalized()
                         .template cast<S>();
  return result;
}

template DiskSignedDistanceResult<float> diskPenetration(float, const fcl::Transform3<float>&,
                                                         float, const fcl::Transform3<float>&);
template DiskSignedDistanceResult<double> diskPenetration(double, const fcl::Transform3<double>&,
                                                          double,
                                                          const fcl::Transform3<double>&);
template DiskSignedDistanceResult<float> signedDiskDistance(float, const fcl::Transform3<float>&,
                                                            float,
                                                            const fcl::Transform3<float>&);
template DiskSignedDistanceResult<double> signedDiskDistance(
    double, const fcl::Transform3<double>&, double, const fcl::Transform3<double>&);

}  // namespace fcl_disk
