// Internal: real roots of a trigonometric polynomial of degree <= 4 on the
// whole circle, found rigorously (every root, and a candidate at every place a
// double root may hide): the polynomial is mapped to two bounded charts,
// theta = 2 atan t and pi + 2 atan t with t in [-1, 1], where it becomes an
// algebraic polynomial of twice its degree, whose roots are isolated by Bernstein
// subdivision (Descartes' rule) and polished by Newton steps within their
// brackets. Used by the penetration-depth solvers; derivation in
// docs/penetration_depth.md, section 2.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <utility>

namespace fcl_disk {
namespace internal {
namespace trig_roots {

/// The largest degree handled as a trigonometric polynomial, and the degree of
/// the algebraic polynomial it becomes on a chart (t = tan(theta / 2)). A
/// polynomial of lower degree D is searched as one (forEachRootAngle<D>): its
/// chart polynomial has degree 2 D, half the subdivision work.
constexpr int kTrigDegree = 4;
constexpr int kPolyDegree = 2 * kTrigDegree;
/// Samples that determine a trigonometric polynomial of degree 4.
constexpr int kSamples = 2 * kTrigDegree + 1;
constexpr double kPi = 3.141592653589793;

/// Root polishing stops at a Newton step (or bracket) this small in t (t lies
/// in [-1, 1]): 8 ulps of 1, the resolution of t, so the angle is as accurate
/// as double allows; or after kMaxRootIterations steps (bisection alone needs
/// ~50).
constexpr double kRootTolerance = 8 * std::numeric_limits<double>::epsilon();
constexpr int kMaxRootIterations = 100;

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

/// An algebraic polynomial p[0] + p[1] t + ... + p[N] t^N.
template <int N>
using Polynomial = std::array<double, N + 1>;

/// (1 + t^2)^D cos(k theta) and (1 + t^2)^D sin(k theta) at theta = 2 atan(t):
/// the real and imaginary parts of (1 + i t)^(2k) (1 + t^2)^(D - k), since
/// e^{i theta} = (1 + i t)^2 / (1 + t^2). Integer coefficients.
template <int D>
struct ChartBasis {
  std::array<Polynomial<2 * D>, D + 1> cos_k{}, sin_k{};
  ChartBasis() {
    for (int k = 0; k <= D; ++k) {
      // (1 + i t)^(2k) = sum_j binom(2k, j) i^j t^j.
      using Complex = std::complex<double>;
      std::array<Complex, 2 * D + 1> power{};
      double binom = 1;
      for (int j = 0; j <= 2 * k; ++j) {
        static constexpr Complex kIPowers[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
        power[j] = binom * kIPowers[j % 4];
        binom = binom * (2 * k - j) / (j + 1);
      }
      // times (1 + t^2)^(D - k) = sum_l binom(D - k, l) t^(2l).
      double binom_l = 1;
      for (int l = 0; l <= D - k; ++l) {
        for (int j = 0; j <= 2 * k; ++j) {
          cos_k[k][j + 2 * l] += binom_l * power[j].real();
          sin_k[k][j + 2 * l] += binom_l * power[j].imag();
        }
        binom_l = binom_l * (D - k - l) / (l + 1);
      }
    }
  }
};

/// f (of degree <= D) on the chart theta = offset + 2 atan(t), times
/// (1 + t^2)^D; offset 0 or pi (cos and sin of k(pi + phi) are (-1)^k those of
/// k phi).
template <int D>
Polynomial<2 * D> onChart(const TrigPolynomial& f, bool shifted_by_pi) {
  static const ChartBasis<D> basis;
  Polynomial<2 * D> p{};
  for (int k = 0; k <= D; ++k) {
    const double sign = shifted_by_pi && k % 2 == 1 ? -1.0 : 1.0;
    const double C = sign * f.C[k], S = sign * f.S[k];
    for (int j = 0; j <= 2 * D; ++j) p[j] += C * basis.cos_k[k][j] + S * basis.sin_k[k][j];
  }
  return p;
}

inline double evaluate(const double* p, int degree, double t) {
  double value = p[degree];
  for (int j = degree - 1; j >= 0; --j) value = value * t + p[j];
  return value;
}

/// The root of p in [lo, hi], where p(lo) and p(hi) have opposite signs:
/// Newton steps kept inside the bracket, bisection when a step would leave it.
inline double rootInBracket(const double* p, const double* dp, int degree, double lo, double hi,
                     double p_lo) {
  // Start where the chord between the bracket's ends crosses zero.
  const double p_hi = evaluate(p, degree, hi);
  double t = p_hi != p_lo ? lo - p_lo * (hi - lo) / (p_hi - p_lo) : 0.5 * (lo + hi);
  if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
  // No stop on a value at rounding level: the bracket may also hold a place
  // where p only touches zero (a double root), and only its sign change
  // locates the root it brackets.
  for (int i = 0; i < kMaxRootIterations && hi - lo > kRootTolerance; ++i) {
    const double value = evaluate(p, degree, t);
    if (value == 0.0) return t;
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

/// p in the Bernstein basis of [lo, hi]: p(t) = sum_i b_i binom(N, i) s^i (1 - s)^(N - i)
/// with t = lo + (hi - lo) s. By Descartes' rule for this basis, p has at most as many
/// roots in the interval as b has sign changes, and the same parity.
template <int N>
using Bernstein = std::array<double, N + 1>;

template <int N>
Bernstein<N> toBernstein(const Polynomial<N>& p, double lo, double hi) {
  // q(s) = p(lo + (hi - lo) s) by Horner's scheme on polynomials in s.
  const double width = hi - lo;
  Polynomial<N> q{};
  for (int j = N; j >= 0; --j) {
    for (int i = N; i >= 1; --i) q[i] = width * q[i - 1] + lo * q[i];
    q[0] = p[j] + lo * q[0];
  }
  // b_i = sum_{j <= i} binom(i, j) / binom(N, j) q_j.
  struct Weights {
    double w[N + 1][N + 1] = {};
    Weights() {
      double binom_N[N + 1];
      binom_N[0] = 1;
      for (int j = 0; j < N; ++j) binom_N[j + 1] = binom_N[j] * (N - j) / (j + 1);
      for (int i = 0; i <= N; ++i) {
        double binom_ij = 1;  // binom(i, j)
        for (int j = 0; j <= i; ++j) {
          w[i][j] = binom_ij / binom_N[j];
          binom_ij = binom_ij * (i - j) / (j + 1);
        }
      }
    }
  };
  static const Weights weights;
  Bernstein<N> b{};
  for (int i = 0; i <= N; ++i) {
    for (int j = 0; j <= i; ++j) b[i] += weights.w[i][j] * q[j];
  }
  return b;
}

/// toBernstein on the dyadic intervals [-1 + 2k / 2^d, -1 + 2 (k + 1) / 2^d] of
/// depth d < kDepths, the intervals the root search splits [-1, 1] into for an
/// arc test, as linear maps of p's coefficients (column j: the image of t^j),
/// so that forming an interval's coefficients is one matrix-vector product.
template <int N>
struct DyadicBernsteinMaps {
  static constexpr int kDepths = 5;
  std::array<std::array<Bernstein<N>, N + 1>, (1 << kDepths) - 1> maps;
  DyadicBernsteinMaps() {
    for (int depth = 0; depth < kDepths; ++depth) {
      const double width = 2.0 / (1 << depth);
      for (int k = 0; k < (1 << depth); ++k) {
        for (int j = 0; j <= N; ++j) {
          Polynomial<N> monomial{};
          monomial[j] = 1.0;
          maps[(1 << depth) - 1 + k][j] =
              toBernstein<N>(monomial, -1.0 + k * width, -1.0 + (k + 1) * width);
        }
      }
    }
  }
};

/// p in the Bernstein basis of [lo, hi], the interval of the given depth of
/// halvings of [-1, 1].
template <int N>
Bernstein<N> bernsteinOnDyadic(const Polynomial<N>& p, double lo, double hi, int depth) {
  using Maps = DyadicBernsteinMaps<N>;
  if (depth >= Maps::kDepths) return toBernstein<N>(p, lo, hi);
  static const Maps maps;
  // lo = -1 + k 2^(1 - depth) exactly: halvings of [-1, 1] are exact in binary.
  const int k = static_cast<int>((lo + 1.0) * (1 << depth) / 2.0);
  const auto& map = maps.maps[(1 << depth) - 1 + k];
  Bernstein<N> b{};
  for (int j = 0; j <= N; ++j) {
    for (int i = 0; i <= N; ++i) b[i] += p[j] * map[j][i];
  }
  return b;
}

template <typename Coefficients>
int signChanges(const Coefficients& b) {
  // Without zeros (almost always), branch-free: adjacent signs that differ.
  bool any_zero = false;
  int adjacent_changes = 0;
  for (std::size_t i = 0; i < b.size(); ++i) any_zero |= b[i] == 0.0;
  for (std::size_t i = 0; i + 1 < b.size(); ++i) adjacent_changes += (b[i] < 0) != (b[i + 1] < 0);
  if (!any_zero) return adjacent_changes;
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
/// 2^-24 wide in t, within 6e-8 of the root(s), where a function stationary
/// at the root is off by ~4e-15 of its curvature (the callers polish their
/// best candidate anyway).
constexpr int kMaxSubdivisions = 24;

/// Bernstein coefficients within this many times the size of the terms a
/// polynomial is computed from (the caller's `noise` scale) of zero may be
/// rounding: ~5e4 ulps, far above the rounding the sampling, the Fourier
/// transform and the change of basis leave (~1e3 ulps of the chart polynomial,
/// which is up to 16 times f), far below any coefficient a clear sign carries.
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
/// - one sign change between its ends, both clear of the noise: one root,
///   bracketed and polished;
/// - otherwise, when the coefficients of p' (n (b_{i+1} - b_i)) change sign at
///   most once: p has at most one extremum there, found by Newton within its
///   bracket and taken as a candidate (it marks a double root, or two roots
///   rounding may merge), and p is monotone on either side of it, so each side
///   holds a root exactly when p changes sign over it.
/// Undecided intervals are halved, down to kMaxSubdivisions (then the midpoint
/// is the candidate), within a budget of kMaxIntervals.
/// Only intervals [lo, hi] for which may_hold(lo, hi) is true are examined
/// (false: no wanted root lies there, whatever the coefficients say), and
/// those wider than may_hold.split_wider_than are halved before they are
/// decided, so that the test sees intervals small enough to rule out.
template <int N, typename IntervalTest>
int rootsOnChart(const Polynomial<N>& p, double noise, double* out,
                 const IntervalTest& may_hold) {
  Polynomial<N> dp{}, ddp{};
  for (int j = 0; j < N; ++j) dp[j] = (j + 1) * p[j + 1];
  for (int j = 0; j + 1 < N; ++j) ddp[j] = (j + 1) * dp[j + 1];
  int count = 0;
  const auto add = [&](double t) {
    if (count < kMaxChartCandidates) out[count++] = t;
  };
  // The root of p in [lo, hi] if p changes sign over it (values given). Only
  // signs above the noise count: an end within it is a candidate of its own
  // (added with its interval), and on a monotone piece no other root can hide
  // beside it; a bracket from a rounding-level sign would find that end's
  // rounding instead of the root.
  const auto rootIfSignChange = [&](double lo, double hi, double p_lo, double p_hi) {
    if (std::abs(p_lo) > noise && std::abs(p_hi) > noise && (p_lo < 0) != (p_hi < 0)) {
      add(rootInBracket(p.data(), dp.data(), N, lo, hi, p_lo));
    }
  };
  struct Interval {
    Bernstein<N> b;
    double lo, hi;
    int depth;
    bool has_b;  ///< false: split for the arc test only, b not formed yet
  };
  std::array<Interval, kMaxSubdivisions + 2> stack;
  int size = 0, examined = 0;
  // de Casteljau at s = 1/2: the left half's coefficients are the first
  // entries of each level, the right half's the last.
  const auto halve = [&](const Interval& interval, double mid) {
    Interval left{{}, interval.lo, mid, interval.depth + 1, true};
    Interval right{{}, mid, interval.hi, interval.depth + 1, true};
    Bernstein<N> level = interval.b;
    for (int r = 0; r <= N; ++r) {
      left.b[r] = level[0];
      right.b[N - r] = level[N - r];
      for (int i = 0; i < N - r; ++i) level[i] = 0.5 * (level[i] + level[i + 1]);
    }
    stack[size++] = right;
    stack[size++] = left;
  };
  // Intervals wider than may_hold.split_wider_than are split before they are
  // decided, so that the test sees intervals small enough to rule out; their
  // halves get their coefficients only if they pass it.
  stack[size++] = {{}, -1.0, 1.0, 0, false};
  while (size > 0) {
    // In place: the slot is reused only by the halves pushed last, which
    // read it before they are written (halve copies b and the ends first).
    Interval& interval = stack[--size];
    const double lo = interval.lo, hi = interval.hi, mid = 0.5 * (lo + hi);
    const int depth = interval.depth;
    if (++examined > kMaxIntervals) {
      add(mid);
      continue;
    }
    if (!may_hold(lo, hi)) continue;
    if (hi - lo > may_hold.split_wider_than && depth < kMaxSubdivisions &&
        size + 2 <= int(stack.size())) {
      stack[size++] = {{}, mid, hi, depth + 1, false};
      stack[size++] = {{}, lo, mid, depth + 1, false};
      continue;
    }
    if (!interval.has_b) interval.b = bernsteinOnDyadic<N>(p, lo, hi, depth);
    const Bernstein<N>& b = interval.b;
    const int changes = signChanges(b);
    if (changes == 0) {
      double smallest = std::abs(b[0]);
      for (const double x : b) smallest = std::min(smallest, std::abs(x));
      if (smallest > noise) continue;  // |p| > noise on the interval: no root
    }
    // An end within the noise of zero may be a root that does not change sign
    // (a double root where a halving fell, as on the symmetry axis of a
    // symmetric pair): a candidate, whatever the interior holds.
    if (std::abs(b[0]) <= noise) add(interval.lo);
    if (std::abs(b[N]) <= noise) add(interval.hi);
    if (changes == 1 && std::abs(b[0]) > noise && std::abs(b[N]) > noise) {
      // The ends differ in sign, each clearly.
      rootIfSignChange(interval.lo, interval.hi, b[0], b[N]);
      continue;
    }
    std::array<double, N> derivative;  // p' in the Bernstein basis, up to a factor
    for (int i = 0; i < N; ++i) derivative[i] = b[i + 1] - b[i];
    const int derivative_changes = signChanges(derivative);
    if (derivative_changes == 0) {  // p monotone: a root iff it changes sign
      rootIfSignChange(interval.lo, interval.hi, b[0], b[N]);
      continue;
    }
    // The extremum's bracket needs the derivative's signs at both ends clear
    // of the noise too: next to a double root at an end, p' is at rounding
    // level there, and a bracket from its sign finds that end again.
    if (derivative_changes == 1 && std::abs(derivative[0]) > noise &&
        std::abs(derivative[N - 1]) > noise) {
      const double extremum = rootInBracket(dp.data(), ddp.data(), N - 1, interval.lo,
                                            interval.hi, derivative[0]);
      add(extremum);
      const double p_extremum = evaluate(p.data(), N, extremum);
      rootIfSignChange(interval.lo, extremum, b[0], p_extremum);
      rootIfSignChange(extremum, interval.hi, p_extremum, b[N]);
      continue;
    }
    if (interval.depth >= kMaxSubdivisions || size + 2 > int(stack.size())) {
      add(mid);
      continue;
    }
    halve(interval, mid);
  }
  return count;
}

/// A test of arcs of the circle: `may_hold(cos, sin, radius)` false when no
/// wanted root lies within `radius` (radians) of the angle (cos, sin); arcs
/// wider than `split_wider_than` (radians) are halved for it before they are
/// decided.
struct AnyArc {
  bool operator()(double, double, double) const { return true; }
  static constexpr double split_wider_than = 2 * kPi;
};

/// forEachRootAngle below, visiting only the roots on arcs `may_hold` keeps.
template <int Degree = kTrigDegree, typename Visit, typename ArcTest>
void forEachRootAngle(const TrigPolynomial& f, double noise, Visit&& visit,
                      const ArcTest& may_hold) {
  static_assert(Degree >= 1 && Degree <= kTrigDegree, "a trigonometric degree of 1..4");
  for (const bool shifted : {false, true}) {
    std::array<double, kMaxChartCandidates> ts;
    const double sign = shifted ? -1.0 : 1.0;
    // The chart interval [lo, hi] of t as an arc: theta = 2 atan t moves by at
    // most 2 |dt|, so the arc lies within hi - lo of theta(mid).
    struct ChartTest {
      const ArcTest& arcs;
      double sign;
      double split_wider_than;
      bool operator()(double lo, double hi) const {
        const double mid = 0.5 * (lo + hi), denominator = 1.0 + mid * mid;
        return arcs(sign * (1.0 - mid * mid) / denominator, sign * 2.0 * mid / denominator,
                    hi - lo);
      }
    };
    const ChartTest chart_test{may_hold, sign, 0.5 * ArcTest::split_wider_than};
    // A chart none of whose quarters may hold a root is skipped before its
    // polynomial is formed.
    bool any_quarter = false;
    for (int quarter = 0; quarter < 4 && !any_quarter; ++quarter) {
      any_quarter = chart_test(-1.0 + 0.5 * quarter, -0.5 + 0.5 * quarter);
    }
    if (!any_quarter) continue;
    const int num =
        rootsOnChart<2 * Degree>(onChart<Degree>(f, shifted), noise, ts.data(), chart_test);
    for (int i = 0; i < num; ++i) {
      const double t = ts[i], denominator = 1.0 + t * t;
      visit(sign * (1.0 - t * t) / denominator, sign * 2.0 * t / denominator);
    }
  }
}

/// Calls visit(cos theta, sin theta) for every real root theta of f on the
/// circle and every candidate for a double root (see rootsOnChart), given the
/// rounding level `noise` of f's values (|f| within it may be 0). f's
/// coefficients above `Degree` are taken as 0.
template <int Degree = kTrigDegree, typename Visit>
void forEachRootAngle(const TrigPolynomial& f, double noise, Visit&& visit) {
  forEachRootAngle<Degree>(f, noise, std::forward<Visit>(visit), AnyArc());
}

}  // namespace trig_roots
}  // namespace internal
}  // namespace fcl_disk
