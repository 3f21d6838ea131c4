// An independent, long-double reference for the penetration depth of two disks,
// for tests. Header-only; Eigen and the standard library only (no fcl, no
// fcl_disk code), so a bug in the production solver cannot leak into the values
// it is judged against.
//
// Notation: disk i has centre c_i, in-plane axes u_i, v_i (the first two columns
// of its rotation) and radius r_i; the disk is {c_i + a u_i + b v_i : a^2 + b^2 <=
// r_i^2}. Its support function is h_i(w) = c_i.w + r_i |P_i w| with
// |P_i w| = sqrt((u_i.w)^2 + (v_i.w)^2) (the rotation is used as given, so the
// set is exactly the image of the local disk under the stored pose). With M =
// K1 - K2 (the Minkowski difference),
//   F(w) = h_1(w) + h_2(-w) = (c1 - c2).w + r1 |P1 w| + r2 |P2 w| = h_M(w)
// is M's support function. Translating disk 2 by t w (|w| = 1) separates the
// disks iff t w is outside M, i.e. iff t > rho_M(w), M's radial function; since
// rho_M <= h_M, t > F(w) is sufficient but NOT necessary (two coincident disks
// separate under any tiny tilted translation, while F = 2 r cos(tilt) there).
// The minima coincide: for 0 in M, min rho_M = min h_M = dist(0, boundary of M),
// attained at the same directions (the ball of that radius touches the boundary
// where the supporting plane's normal is w). So
//   min over unit w of F = PD (>= 0) when the disks share a point,
//                        = -distance (< 0) when they are apart,
// and minus that minimum is the signed distance in both cases. F is smooth on the
// sphere except at the four kinks w = +-n1, +-n2 (n_i = u_i x v_i / |u_i x v_i|).
//
// METHOD (a plain global search; the production solver enumerates the roots of a
// trigonometric polynomial, this does not):
//   1. Candidates: the four kinks, exactly.
//   2. Scan: F (in double) on a Fibonacci sphere of kPenetrationSamples
//      directions; the best samples from distinct neighbourhoods (pairwise more
//      than kPenetrationStartSeparation sample spacings apart) become starts.
//   3. Starts near the kinks: at each kink, the descent direction of the cone
//      model F(k + t) ~ F(k) + g.t + r_i |t| (g: tangential gradient of the
//      smooth part) at offsets 1e-1..1e-9, and the kink itself.
//   4. Local refinement in long double of every start, in tangent coordinates
//      x of w = normalize(w0 + x1 e1 + x2 e2): a Newton step on the analytic
//      gradient and Hessian (tried first where F is smooth and the Hessian is
//      positive definite, with backtracking), then a compass search over eight
//      directions plus steepest descent with a step that doubles on success and
//      halves on failure, down to kPenetrationFinalStep radians. Only strict
//      decreases are accepted, so every reported value is F at a real unit w,
//      i.e. an upper bound on the minimum; at a kink the compass search and the
//      kink starts cover the cone, which the Newton step cannot see.
//   5. The smallest refined value is the reference PD; the distinct refined
//      minima are kept (value, direction) so tests can detect ties.
// ACCURACY: F is evaluated in long double (eps 1.08e-19) from c1 - c2 computed
// in long double, so the value carries ~1e-18 * scale of rounding; at a smooth
// minimum the direction is known to ~sqrt(1e-18) (F is flat there), at a kink
// to long-double rounding. Validated (test_disk_penetration.cpp,
// ReferencePenetration.* and *.ReferenceIsConsistent/*):
//   - hand-derived closed forms (coplanar 0; perpendicular through the centres 1,
//     a four-way tie; small disk through a face 0.05 along +z; coaxial-centred
//     min(r1, r2) sin(theta); symmetric chain link 1 on two arcs): to 1e-16;
//   - separated pairs, where -min F is the distance: against reference_distance.h
//     on the same long-double frames, max 1.8e-19 * scale (176 pairs);
//   - constructed PDs (coplanar, coaxial-centred, face dips): within the
//     rounding of the poses (max 1.0e-16 * scale);
//   - a 10x denser scan with 4x the starts never lower by more than 3e-20 * scale;
//   - translating along its minimiser by PD_ref -+ 1e-9 * scale intersects /
//     separates by the library's exact distance.
// Cost: ~0.8 ms per pair (20000 double evaluations of the scan, ~25 double
// refinements, a few long-double polishes).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <vector>

namespace fcl_disk_penetration_reference {

using Real = long double;
using Vector3R = Eigen::Matrix<Real, 3, 1>;

/// Fibonacci-sphere samples of the scan: spacing sqrt(4 pi / N) = 0.025 rad.
constexpr int kPenetrationSamples = 20000;
/// Refined starts taken from the scan.
constexpr int kPenetrationStarts = 16;
/// Starts from the scan are at least this many sample spacings apart.
constexpr double kPenetrationStartSeparation = 4.0;
/// The compass search stops below this step (radians): ~long-double eps, where
/// w + x e no longer changes w.
constexpr Real kPenetrationFinalStep = 1e-19L;
/// Two refined minima closer than this (radians) are the same minimum.
constexpr Real kPenetrationSameMinimum = 1e-6L;

/// A disk in long double: centre, in-plane axes u, v as stored (not
/// re-orthonormalised), unit normal n = u x v / |u x v|, radius.
struct PenDisk {
  Vector3R centre{Vector3R::Zero()};
  Vector3R u{Vector3R::UnitX()};
  Vector3R v{Vector3R::UnitY()};
  Vector3R n{Vector3R::UnitZ()};
  Real radius{1};
};

template <typename S>
PenDisk makePenDisk(const Eigen::Transform<S, 3, Eigen::Isometry>& X, S radius) {
  PenDisk d;
  d.centre = X.translation().template cast<Real>();
  d.u = X.linear().col(0).template cast<Real>();
  d.v = X.linear().col(1).template cast<Real>();
  const Vector3R n = d.u.cross(d.v);
  d.n = n / n.norm();
  d.radius = Real(radius);
  return d;
}

/// F and its pieces for one ordered pair (disk 1, disk 2), relative to c1, in
/// scalar type T (long double for values; double for the cheap first stage).
template <typename T>
struct PenProblemT {
  using Vec = Eigen::Matrix<T, 3, 1>;
  Vec d;  ///< c1 - c2
  Vec u1, v1, n1, u2, v2, n2;
  T r1, r2;
  T scale;  ///< r1 + r2 + |c1 - c2|

  PenProblemT(const PenDisk& a, const PenDisk& b)
      : d((a.centre - b.centre).template cast<T>()),
        u1(a.u.template cast<T>()),
        v1(a.v.template cast<T>()),
        n1(a.n.template cast<T>()),
        u2(b.u.template cast<T>()),
        v2(b.v.template cast<T>()),
        n2(b.n.template cast<T>()),
        r1(T(a.radius)),
        r2(T(b.radius)),
        scale(T(a.radius + b.radius + (a.centre - b.centre).norm())) {}

  static T inPlane(const Vec& u, const Vec& v, const Vec& w) {
    const T a = u.dot(w), b = v.dot(w);
    return std::sqrt(a * a + b * b);
  }
  /// F at a unit vector w.
  T value(const Vec& w) const {
    return d.dot(w) + r1 * inPlane(u1, v1, w) + r2 * inPlane(u2, v2, w);
  }
  /// F at normalize(w).
  T valueAt(const Vec& w) const { return value(w / w.norm()); }
};
using PenProblem = PenProblemT<Real>;

/// One local minimum of F on the sphere.
struct PenMinimum {
  Vector3R w;
  Real value;
};

struct PenReference {
  Real pd{0};                      ///< min F over the unit sphere (-distance if apart)
  Vector3R w{Vector3R::UnitZ()};   ///< a minimiser
  Vector3R p1{Vector3R::Zero()};   ///< support point of disk 1 along w (info)
  Vector3R p2{Vector3R::Zero()};   ///< support point of disk 2 along -w (info)
  Real scale{1};                   ///< r1 + r2 + |c1 - c2|
  std::vector<PenMinimum> minima;  ///< distinct refined minima, best first

  /// Whether another minimiser at least `min_angle` radians from w has a value
  /// within `value_tolerance` of pd (the minimiser is then not unique to that
  /// tolerance).
  bool hasRival(Real value_tolerance, Real min_angle) const {
    for (const PenMinimum& m : minima) {
      if (m.value > pd + value_tolerance) continue;
      if (angleBetween(m.w, w) >= min_angle) return true;
    }
    return false;
  }

  static Real angleBetween(const Vector3R& a, const Vector3R& b) {
    return std::atan2(a.cross(b).norm(), a.dot(b));
  }
};

namespace penetration_detail {

template <typename T>
T norm2(T a, T b) {
  return std::sqrt(a * a + b * b);
}

/// An orthonormal basis (e1, e2) of the plane perpendicular to unit w.
template <typename T>
void tangentBasis(const Eigen::Matrix<T, 3, 1>& w, Eigen::Matrix<T, 3, 1>* e1,
                  Eigen::Matrix<T, 3, 1>* e2) {
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::fabs(w[i]) < std::fabs(w[k])) k = i;
  Eigen::Matrix<T, 3, 1> axis = Eigen::Matrix<T, 3, 1>::Zero();
  axis[k] = 1;
  *e1 = (axis - axis.dot(w) * w).normalized();
  *e2 = w.cross(*e1);
}

/// Fibonacci sphere with n points (cached per n; tests are single-threaded).
inline const std::vector<Eigen::Vector3d>& fibonacciSphere(int n) {
  static std::map<int, std::vector<Eigen::Vector3d>> cache;
  auto it = cache.find(n);
  if (it != cache.end()) return it->second;
  std::vector<Eigen::Vector3d> points(n);
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < n; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / n;
    const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden * k;
    points[k] = Eigen::Vector3d(rho * std::cos(phi), rho * std::sin(phi), z);
  }
  return cache.emplace(n, std::move(points)).first->second;
}

/// Gradient g and Hessian H of f(x) = F(normalize(w + x1 e1 + x2 e2)) at x = 0,
/// where F is smooth (both |P_i w| > 0). F = G(y)/|y| with G positively
/// homogeneous: grad f = E^T grad G, Hess f = E^T (Hess G - F I) E. For
/// G_i = r |P y|: grad = r m (m = P y / |P y|, in 3-D), Hess = r / |P y| (P - m m^T).
template <typename T>
bool smoothDerivatives(const PenProblemT<T>& p, const Eigen::Matrix<T, 3, 1>& w,
                       const Eigen::Matrix<T, 3, 1>& e1, const Eigen::Matrix<T, 3, 1>& e2, T f,
                       T g[2], T H[2][2]) {
  using Vec = Eigen::Matrix<T, 3, 1>;
  Vec grad = p.d;
  Eigen::Matrix<T, 3, 3> hess = Eigen::Matrix<T, 3, 3>::Zero();
  const Vec* us[2] = {&p.u1, &p.u2};
  const Vec* vs[2] = {&p.v1, &p.v2};
  const T rs[2] = {p.r1, p.r2};
  for (int i = 0; i < 2; ++i) {
    const T a = us[i]->dot(w), b = vs[i]->dot(w);
    const T rho = norm2(a, b);
    if (!(rho > T(1e-30))) return false;
    const Vec m = (a * *us[i] + b * *vs[i]) / rho;
    grad += rs[i] * m;
    hess += (rs[i] / rho) *
            (*us[i] * us[i]->transpose() + *vs[i] * vs[i]->transpose() - m * m.transpose());
  }
  const Vec* es[2] = {&e1, &e2};
  for (int i = 0; i < 2; ++i) {
    g[i] = es[i]->dot(grad);
    for (int j = 0; j < 2; ++j) H[i][j] = es[i]->dot(hess * *es[j]) - (i == j ? f : T(0));
  }
  return true;
}

/// Tangential gradient of F's smooth part at kink k = +-n_i (disk = i - 1; the
/// term of disk i removed): F(k + t) ~ F(k) + g.t + r_i |t| for small tangent t.
template <typename T>
Eigen::Matrix<T, 3, 1> kinkSmoothGradient(const PenProblemT<T>& p, const Eigen::Matrix<T, 3, 1>& k,
                                          int disk) {
  Eigen::Matrix<T, 3, 1> grad = p.d;
  const Eigen::Matrix<T, 3, 1>& u = disk == 0 ? p.u2 : p.u1;
  const Eigen::Matrix<T, 3, 1>& v = disk == 0 ? p.v2 : p.v1;
  const T r = disk == 0 ? p.r2 : p.r1;
  const T a = u.dot(k), b = v.dot(k);
  const T rho = norm2(a, b);
  if (rho > 0) grad += r * (a * u + b * v) / rho;
  return grad - grad.dot(k) * k;
}

template <typename T>
struct MinimumT {
  Eigen::Matrix<T, 3, 1> w;
  T value;
};

/// Local minimisation from w0 (see the file comment, step 4), down to compass
/// steps of final_step radians.
template <typename T>
MinimumT<T> refine(const PenProblemT<T>& p, const Eigen::Matrix<T, 3, 1>& w0, T initial_step,
                   T final_step) {
  using Vec = Eigen::Matrix<T, 3, 1>;
  Vec w = w0.normalized();
  T f = p.value(w);
  T step = initial_step;
  constexpr T kMaxStep = T(0.5);
  constexpr int kMaxIterations = 2000;
  const Vec kinks[4] = {p.n1, -p.n1, p.n2, -p.n2};
  auto moved = [&w](const Vec& e1, const Vec& e2, T x1, T x2) {
    return Vec((w + x1 * e1 + x2 * e2).normalized());
  };
  for (int iter = 0; iter < kMaxIterations && step >= final_step; ++iter) {
    // Near a kink, try the kink itself: the compass search would crawl into the
    // cone at a linear rate. At a kink, its cone model decides local optimality.
    int at_kink = -1;
    for (int k = 0; k < 4; ++k) {
      if (w == kinks[k]) {
        at_kink = k;
      } else if ((w - kinks[k]).norm() <= 8 * step) {
        const T fk = p.value(kinks[k]);
        if (fk < f) {
          w = kinks[k];
          f = fk;
          at_kink = k;
        }
      }
    }
    Vec kink_descent = Vec::Zero();
    if (at_kink >= 0) {
      const Vec g = kinkSmoothGradient(p, kinks[at_kink], at_kink / 2);
      const T slope = at_kink < 2 ? p.r1 : p.r2;
      if (g.norm() < slope) break;  // the cone F(k) + g.t + r |t| is a strict minimum
      kink_descent = -g / g.norm();
    }
    Vec e1, e2;
    tangentBasis(w, &e1, &e2);
    T g[2], H[2][2];
    const bool smooth = at_kink < 0 && smoothDerivatives(p, w, e1, e2, f, g, H);
    bool improved = false;
    if (smooth) {
      const T det = H[0][0] * H[1][1] - H[0][1] * H[1][0];
      if (H[0][0] > 0 && det > 0) {
        T x1 = -(H[1][1] * g[0] - H[0][1] * g[1]) / det;
        T x2 = -(-H[1][0] * g[0] + H[0][0] * g[1]) / det;
        for (int halving = 0; halving < 8 && !improved; ++halving) {
          const T length = norm2(x1, x2);
          if (!(length >= final_step)) break;  // converged: leave it to the compass
          const Vec candidate = moved(e1, e2, x1, x2);
          const T fc = p.value(candidate);
          if (fc < f) {
            w = candidate;
            f = fc;
            improved = true;
            // Newton is converging: the compass only needs steps of its size.
            step = std::max(std::min(step, 2 * length), final_step);
          }
          x1 /= 2;
          x2 /= 2;
        }
      }
    }
    if (improved) continue;
    // Compass search: 8 fixed directions and steepest descent; take the best.
    T best_f = f;
    Vec best_w = w;
    auto try_direction = [&](T c, T s) {
      const Vec candidate = moved(e1, e2, step * c, step * s);
      const T fc = p.value(candidate);
      if (fc < best_f) {
        best_f = fc;
        best_w = candidate;
      }
    };
    static const T kDiagonal = std::sqrt(T(0.5));
    const T directions[8][2] = {
        {1, 0},  {kDiagonal, kDiagonal},   {0, 1},  {-kDiagonal, kDiagonal},
        {-1, 0}, {-kDiagonal, -kDiagonal}, {0, -1}, {kDiagonal, -kDiagonal}};
    for (const auto& direction : directions) try_direction(direction[0], direction[1]);
    if (smooth) {
      const T gn = norm2(g[0], g[1]);
      if (gn > 0) try_direction(-g[0] / gn, -g[1] / gn);
    }
    if (at_kink >= 0) try_direction(kink_descent.dot(e1), kink_descent.dot(e2));
    if (best_f < f) {
      w = best_w;
      f = best_f;
      step = std::min(2 * step, kMaxStep);
    } else {
      step /= 2;
    }
  }
  return {w, f};
}

}  // namespace penetration_detail

/// Options of the search (defaults as documented above; tests of the reference
/// itself use denser settings).
struct PenOptions {
  int samples = kPenetrationSamples;
  int starts = kPenetrationStarts;
};

/// The reference minimum of F over the unit sphere for disks a (1) and b (2).
/// Two stages: every start is refined in double down to kDoubleStageStep, then
/// the distinct double-stage minima within kPolishWindow * scale of the best
/// (and the four kinks) are polished in long double.
inline PenReference referencePenetration(const PenDisk& a, const PenDisk& b,
                                         const PenOptions& options = {}) {
  using namespace penetration_detail;
  constexpr double kDoubleStageStep = 1e-9;
  constexpr double kPolishStartStep = 1e-7;
  constexpr double kPolishWindow = 1e-6;
  const PenProblem p(a, b);
  const PenProblemT<double> pd(a, b);
  std::vector<MinimumT<double>> coarse;

  // 1. Kinks and 3. starts around them (double stage).
  const Eigen::Vector3d kinks[4] = {pd.n1, -pd.n1, pd.n2, -pd.n2};
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d& kink = kinks[k];
    coarse.push_back(refine(pd, kink, 1e-2, kDoubleStageStep));
    const Eigen::Vector3d g = kinkSmoothGradient(pd, kink, k / 2);
    const double gn = g.norm();
    const double r = k < 2 ? pd.r1 : pd.r2;
    if (gn > r * (1 - 1e-9)) {  // the cone model descends along -g
      for (double offset : {1e-1, 1e-3, 1e-6, 1e-9})
        coarse.push_back(
            refine(pd, Eigen::Vector3d(kink - offset * g / gn), offset, kDoubleStageStep));
    }
  }

  // 2. Scan, then refine the best samples from distinct neighbourhoods.
  const std::vector<Eigen::Vector3d>& sphere = fibonacciSphere(options.samples);
  std::vector<double> values(sphere.size());
  for (std::size_t k = 0; k < sphere.size(); ++k) values[k] = pd.value(sphere[k]);
  std::vector<int> order(sphere.size());
  std::iota(order.begin(), order.end(), 0);
  const std::size_t pool = std::min<std::size_t>(order.size(), 128 * options.starts);
  std::partial_sort(order.begin(), order.begin() + pool, order.end(),
                    [&values](int x, int y) { return values[x] < values[y]; });
  const double spacing = std::sqrt(4 * M_PI / options.samples);
  const double min_cos = std::cos(kPenetrationStartSeparation * spacing);
  std::vector<int> starts;
  for (std::size_t i = 0; i < pool && int(starts.size()) < options.starts; ++i) {
    bool distinct = true;
    for (int s : starts) distinct &= sphere[order[i]].dot(sphere[s]) < min_cos;
    if (distinct) starts.push_back(order[i]);
  }
  for (int s : starts) coarse.push_back(refine(pd, sphere[s], spacing, kDoubleStageStep));

  // 4. Polish in long double: the kinks exactly, and the coarse minima near the best.
  std::sort(coarse.begin(), coarse.end(),
            [](const MinimumT<double>& x, const MinimumT<double>& y) { return x.value < y.value; });
  std::vector<PenMinimum> found;
  for (const Vector3R& kink : {p.n1, Vector3R(-p.n1), p.n2, Vector3R(-p.n2)})
    found.push_back({kink, p.value(kink)});
  std::vector<Eigen::Vector3d> polished_from;
  for (const MinimumT<double>& m : coarse) {
    bool distinct = true;
    for (const Eigen::Vector3d& q : polished_from)
      distinct &= PenReference::angleBetween(m.w.cast<Real>(), q.cast<Real>()) >= 1e-7L;
    if (!distinct) continue;
    polished_from.push_back(m.w);
    if (m.value <= coarse.front().value + kPolishWindow * pd.scale) {
      const MinimumT<Real> fine = refine<Real>(p, Vector3R(m.w.cast<Real>()),
                                               Real(kPolishStartStep), kPenetrationFinalStep);
      found.push_back({fine.w, fine.value});
    } else {
      found.push_back({m.w.cast<Real>(), p.value(m.w.cast<Real>().normalized())});
    }
  }

  // 5. Distinct minima, best first.
  std::sort(found.begin(), found.end(),
            [](const PenMinimum& x, const PenMinimum& y) { return x.value < y.value; });
  PenReference result;
  for (const PenMinimum& m : found) {
    bool distinct = true;
    for (const PenMinimum& kept : result.minima)
      distinct &= PenReference::angleBetween(m.w, kept.w) >= kPenetrationSameMinimum;
    if (distinct) result.minima.push_back(m);
  }
  result.pd = result.minima.front().value;
  result.w = result.minima.front().w;
  result.scale = p.scale;
  // Witness points (information only): supports along w and -w; on a kink the
  // face point that makes p1 - p2 = pd w.
  const Vector3R& w = result.w;
  const Real rho1 = PenProblem::inPlane(a.u, a.v, w), rho2 = PenProblem::inPlane(b.u, b.v, w);
  const Vector3R m1 =
      rho1 > 0 ? Vector3R((a.u.dot(w) * a.u + a.v.dot(w) * a.v) / rho1) : Vector3R::Zero();
  const Vector3R m2 =
      rho2 > 0 ? Vector3R((b.u.dot(w) * b.u + b.v.dot(w) * b.v) / rho2) : Vector3R::Zero();
  result.p1 = a.centre + a.radius * m1;
  result.p2 = b.centre - b.radius * m2;
  if (!(rho1 > 1e-15L) && rho2 > 1e-15L) result.p1 = result.p2 + result.pd * w;
  if (!(rho2 > 1e-15L) && rho1 > 1e-15L) result.p2 = result.p1 - result.pd * w;
  return result;
}

template <typename S>
PenReference referencePenetration(S r1, const Eigen::Transform<S, 3, Eigen::Isometry>& X_W1, S r2,
                                  const Eigen::Transform<S, 3, Eigen::Isometry>& X_W2,
                                  const PenOptions& options = {}) {
  return referencePenetration(makePenDisk(X_W1, r1), makePenDisk(X_W2, r2), options);
}

/// F of the pair at a (not necessarily unit) direction, in long double: for
/// judging a direction some solver returned.
inline Real referenceF(const PenDisk& a, const PenDisk& b, const Vector3R& w) {
  return PenProblem(a, b).valueAt(w);
}

/// The largest angle (radians) from the minimiser w at which F still stays at
/// or below `level`, over 16 tangent directions: the angular radius of the
/// sublevel set {F <= level} around w (for unique minimisers: how far two
/// directions whose values are both below `level` can be apart, halved).
inline Real sublevelRadius(const PenDisk& a, const PenDisk& b, const Vector3R& w, Real level) {
  using namespace penetration_detail;
  const PenProblem p(a, b);
  Vector3R e1, e2;
  tangentBasis<Real>(w, &e1, &e2);
  Real radius = 0;
  for (int k = 0; k < 16; ++k) {
    const Real angle = Real(k) * Real(M_PI) / 8;
    const Vector3R t = std::cos(angle) * e1 + std::sin(angle) * e2;
    auto at = [&](Real phi) { return p.value(std::cos(phi) * w + std::sin(phi) * t); };
    Real inside = 0, outside = -1;
    for (Real phi = 1e-18L; phi < Real(M_PI); phi *= 2) {
      if (at(phi) > level) {
        outside = phi;
        break;
      }
      inside = phi;
    }
    if (outside < 0) return Real(M_PI);  // the whole half-circle is below level
    for (int i = 0; i < 64; ++i) {
      const Real mid = (inside + outside) / 2;
      if (!(inside < mid && mid < outside)) break;
      (at(mid) > level ? outside : inside) = mid;
    }
    radius = std::max(radius, outside);
  }
  return radius;
}

/// Distance from a point to a disk (closed form, long double), using the
/// disk's axes as stored.
inline Real pointToDisk(const Vector3R& x, const PenDisk& disk) {
  const Vector3R rel = x - disk.centre;
  const Real a = disk.u.dot(rel), b = disk.v.dot(rel), z = disk.n.dot(rel);
  const Real outside = std::max(Real(0), penetration_detail::norm2(a, b) - disk.radius);
  return penetration_detail::norm2(z, outside);
}

}  // namespace fcl_disk_penetration_reference
