// Signed distance and exact penetration depth of two disks. Derivation and
// notation (F, Q, rho, L, K, the charts): docs/penetration_depth.md.
#include "fcl_disk/disk_penetration.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <complex>
#include <limits>

#include "fcl_disk/exact_distance.h"
#include "disk_penetration_candidates.h"
#include "pair_in_frame1.h"
#include "trig_roots.h"

namespace fcl_disk {
namespace {

using internal::PairInFrame1;
using internal::Vec2;
using internal::Vec3;
using namespace internal::trig_roots;

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

/// A point the disks share (commonPoint) within kSharedPointOnRims of both
/// rims (scene sizes) is taken as a rim pair of its own
/// (considerSharedRimPoint): where the rims touch with nearly parallel
/// tangents, Q has a near-double root there, known only to ~sqrt(eps), and
/// the pair's directions are PD's to within the shared point's distance from
/// the rims. Wider than needed costs only the pair's few evaluations of F. It
/// is sought only when the rim candidates leave a depth of at most
/// kSharedPointDepth (touching rims have PD 0, and Q's roots miss it by far
/// less than that), so that deeper overlaps do not pay for the common point.
constexpr double kSharedPointOnRims = 1e-6;
constexpr double kSharedPointDepth = 1e-3;

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

/// A rim point of disk 2 within this (scene sizes) of disk 1's axis marks
/// candidates Q places poorly: Q's values there are rho^2 <= 1e-6 of its
/// terms, so its roots there lose 6 digits or more to rounding; the search is
/// then run with the roles exchanged too (penetrationOfValidPair).
constexpr double kNearAxis = 1e-3;

/// Newton's method on F over the sphere (polishBestDirection) takes at most
/// kDirectionPolishIterations steps, each halved at most
/// kDirectionPolishHalvings times until F decreases (a 2^-30 step is below an
/// angle's resolution next to the unit steps a curved valley may need).
constexpr int kDirectionPolishIterations = 8;
constexpr int kDirectionPolishHalvings = 30;

// ---------------------------------------------------------------------------
// The pair in disk 1's frame, lengths in scene sizes.

struct Penetration {
  double depth;  ///< PD, scene sizes.
  Vec3 w;        ///< unit minimiser, frame 1.
  Vec3 p1, p2;   ///< witnesses, frame 1, scene sizes.
  /// The distance to disk 1's axis of the nearest rim point of disk 2 the
  /// search considered (scene sizes; infinite when none).
  double nearest_rim_to_axis = std::numeric_limits<double>::infinity();
};

class PenetrationSearch {
 public:
  /// `sink`, when given, also receives every candidate direction.
  explicit PenetrationSearch(const PairInFrame1& pair,
                             const std::function<void(const Vec3&)>* sink = nullptr)
      : c_(pair.c), u_(pair.R.col(0)), v_(pair.R.col(1)), r1_(pair.r1), r2_(pair.r2),
        sink_(sink) {}

  /// F(w) = -c.w + r1 |P1 w| + r2 |P2 w|: translating disk 2 by t w separates
  /// the disks for every t > F(w). Keeps the smallest, with the rim points
  /// (b of disk 1, a of disk 2) the direction came from, if any.
  void consider(const Vec3& w, const Vec3* b = nullptr, const Vec3* a = nullptr) {
    if (sink_) (*sink_)(w);
    const double value = F(w);
    if (!(value < best_.value)) return;
    best_.value = value;
    best_.w = w;
    best_.from_rims = b != nullptr;
    if (b) best_.b = *b, best_.a = *a;
  }

  double F(const Vec3& w) const {
    const double p1 = std::sqrt(w.x() * w.x() + w.y() * w.y());
    const double in_plane2_u = u_.dot(w), in_plane2_v = v_.dot(w);
    return -c_.dot(w) + r1_ * p1 +
           r2_ * std::sqrt(in_plane2_u * in_plane2_u + in_plane2_v * in_plane2_v);
  }

  /// The smallest F found so far: an upper bound on PD.
  double bestValue() const { return best_.value; }

  /// The candidates of rim angle theta of disk 2 (given as cos, sin): its rim
  /// point a and the rim points b of disk 1 that make (b, a) critical for the
  /// distance between the rims (nearest and farthest to a), each giving the
  /// direction (b - a) / |b - a|.
  void considerRimAngle(double cos_theta, double sin_theta) {
    const Vec3 e2 = cos_theta * u_ + sin_theta * v_;  // outward radial of disk 2 at a
    const Vec3 a = c_ + r2_ * e2;
    const Vec3 t2 = -sin_theta * u_ + cos_theta * v_;
    const double rho = std::sqrt(a.x() * a.x() + a.y() * a.y());
    nearest_rim_to_axis_ = std::min(nearest_rim_to_axis_, rho);
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

  /// A point x of both disks that lies within kSharedPointOnRims of both rims,
  /// taken as a rim angle of its own (considerRimAngle at x's angle on rim 2):
  /// rims touching at x make a critical pair with b = a there whose
  /// directions (t1 x t2, or the sector's edges for parallel tangents) Q's
  /// roots give only to the accuracy of a near-double root when the tangents
  /// are nearly parallel (docs/penetration_depth.md, section 2).
  void considerSharedRimPoint(const Vec3& x) {
    const Vec3 from_c2 = x - c_;
    const double along_u = u_.dot(from_c2), along_v = v_.dot(from_c2);
    const double rho1 = std::sqrt(x.x() * x.x() + x.y() * x.y());
    const double rho2 = std::sqrt(along_u * along_u + along_v * along_v);
    if (std::abs(rho1 - r1_) <= kSharedPointOnRims && std::abs(rho2 - r2_) <= kSharedPointOnRims &&
        rho2 > 0.0) {
      considerRimAngle(along_u / rho2, along_v / rho2);
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

  /// Newton's method on F over the unit sphere from the best direction, when
  /// it came from a rim pair. Next to disk 1's axis the pair equations are
  /// ill-conditioned (the nearest point b of rim 1 to a turns fast with a's
  /// angle) and F is nearly flat along a valley, so the best rim pair can be
  /// far from the minimiser in w while F is smooth there: F's own Newton step
  /// reaches it. Stops at a kink, at a Hessian that is not positive definite,
  /// when no halving of the step lowers F, or at a step below
  /// kPolishConverged; the result is kept only if F is smaller by more than
  /// rounding (kPolishSlack).
  void polishBestDirection() {
    if (!best_.from_rims) return;
    Vec3 w = best_.w;
    double value = best_.value;
    for (int i = 0; i < kDirectionPolishIterations; ++i) {
      const Vec3 P1w(w.x(), w.y(), 0.0);
      const Vec3 P2w = u_.dot(w) * u_ + v_.dot(w) * v_;
      const double length1 = P1w.norm(), length2 = P2w.norm();
      if (!(std::min(length1, length2) > kAlongNormal)) return;  // at a kink: not smooth
      const Vec3 g = -c_ + (r1_ / length1) * P1w + (r2_ / length2) * P2w;
      // r |P w|'s Hessian: (r / |P w|) (P - (P w)(P w)^T / |P w|^2).
      const auto hessian = [&](const Vec3& e, const Vec3& f) {
        const double along1 = e.x() * f.x() + e.y() * f.y();
        const double along2 = u_.dot(e) * u_.dot(f) + v_.dot(e) * v_.dot(f);
        return r1_ / length1 * (along1 - P1w.dot(e) * P1w.dot(f) / (length1 * length1)) +
               r2_ / length2 * (along2 - P2w.dot(e) * P2w.dot(f) / (length2 * length2));
      };
      // A tangent basis (e1, e2) of the sphere at w; on the sphere the Hessian
      // gains -(g.w) I.
      const Vec3 e1 = w.unitOrthogonal(), e2 = w.cross(e1);
      const double g_w = g.dot(w);
      const double h11 = hessian(e1, e1) - g_w, h22 = hessian(e2, e2) - g_w;
      const double h12 = hessian(e1, e2);
      const double det = h11 * h22 - h12 * h12;
      if (!(h11 > 0.0 && det > 0.0)) return;  // not next to a regular minimum
      const double g1 = g.dot(e1), g2 = g.dot(e2);
      double s1 = -(h22 * g1 - h12 * g2) / det, s2 = -(h11 * g2 - h12 * g1) / det;
      // The valley may curve within the Newton step: halved until F decreases.
      bool decreased = false;
      for (int halving = 0; halving < kDirectionPolishHalvings && !decreased; ++halving) {
        const Vec3 next = (w + s1 * e1 + s2 * e2).normalized();
        const double next_value = F(next);
        if (next_value < value) {
          w = next;
          value = next_value;
          decreased = true;
        } else {
          s1 *= 0.5;
          s2 *= 0.5;
        }
      }
      if (!decreased) break;
      if (std::abs(s1) + std::abs(s2) < kPolishConverged) break;
    }
    // A gain at rounding level keeps the rim pair, whose points are exactly on
    // the rims (the support points of a direction known to rounding are not).
    if (value < best_.value - kPolishSlack) consider(w);
  }

  struct Best {
    double value = std::numeric_limits<double>::infinity();
    Vec3 w = Vec3::UnitZ();
    bool from_rims = false;  ///< w came from the rim pair (b, a), not a kink
    Vec3 b = Vec3::Zero(), a = Vec3::Zero();
  };
  const Best& best() const { return best_; }
  double nearestRimToAxis() const { return nearest_rim_to_axis_; }

 private:
  Vec3 c_, u_, v_;
  double r1_, r2_;
  Best best_;
  double nearest_rim_to_axis_ = std::numeric_limits<double>::infinity();
  const std::function<void(const Vec3&)>* sink_;
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
    // Apart by more than the touching tolerance (heights of rounding size, or
    // disks that share no point), the witnesses are the point of disk 1 in the
    // middle of the overlap of the disks' projections on the line of centres
    // (disk 1's rim point towards disk 2 if they do not overlap) and the point
    // of disk 2's plane over it.
    if (const auto common = internal::commonPoint(pair)) {
      out.p1 = out.p2 = *common;
    } else {
      const double D = std::sqrt(pair.c.x() * pair.c.x() + pair.c.y() * pair.c.y());
      const double t =
          internal::coplanarOverlapMidpoint(D, pair.r1, pair.r2).value_or(D - pair.r2);
      const Vec2 xy = pair.pointOnCentreLine(std::clamp(t, -pair.r1, pair.r1));
      out.p1 = Vec3(xy.x(), xy.y(), 0.0);
      const Vec3& n2 = pair.R.col(2);
      out.p2 = out.p1 + (n2.dot(pair.c - out.p1) / n2.z()) * Vec3::UnitZ();
    }
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

/// Arcs of disk 2's rim where a critical rim pair can still beat `bound()`, an
/// upper bound on PD plus a slack (infinite: every arc): at a minimiser off
/// the kinks PD = |b - a| with b the nearest or farthest point of rim 1 to a
/// (section 2), so PD >= dist(a, rim 1), and a(theta) moves at speed r2. An
/// arc whose centre is farther from rim 1 than bound() plus r2 times its
/// radius holds no minimiser. Valid when the minimiser's value is >= 0 (disks
/// that share a point) or within the slack of it (touching).
struct ArcsThatCanBeatBest {
  const PairInFrame1& pair;
  const std::function<double()>& bound;
  /// Arcs wider than this (radians) are halved before their roots are
  /// isolated, so that most of the circle is ruled out as a whole; on the
  /// report's families the arcs that can beat the best are ~10% of it.
  static constexpr double split_wider_than = internal::kPrunedArcWidth;

  bool operator()(double cos_theta, double sin_theta, double radius) const {
    const double limit = bound();
    if (!(limit < std::numeric_limits<double>::infinity())) return true;
    const Vec3 a = pair.c + pair.r2 * (cos_theta * pair.R.col(0) + sin_theta * pair.R.col(1));
    const double off_axis = std::sqrt(a.x() * a.x() + a.y() * a.y()) - pair.r1;
    const double from_rim1 = std::sqrt(off_axis * off_axis + a.z() * a.z());
    return from_rim1 - pair.r2 * radius <= limit;
  }
};

/// The rim-pair candidates of docs/penetration_depth.md section 2: the
/// directions each root of Q gives (or, Q vanishing, kFixedAnglesWhenQVanishes
/// angles), offered to `search`. `bound`: only the roots that can beat it
/// (ArcsThatCanBeatBest); nullptr: every root.
void considerRimCandidates(const PairInFrame1& pair, PenetrationSearch& search,
                           const std::function<double()>* bound) {
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
    return;
  }

  // Candidate angles: the roots of Q, and where it may have a double root.
  const auto visit = [&](double cos_theta, double sin_theta) {
    search.considerRimAngle(cos_theta, sin_theta);
  };
  if (bound) {
    forEachRootAngle(Q, kBernsteinNoise * terms, visit, ArcsThatCanBeatBest{pair, *bound});
  } else {
    forEachRootAngle(Q, kBernsteinNoise * terms, visit);
  }

}

/// For a pair known to share a point, once its rim candidates leave a depth
/// of at most kSharedPointDepth: the common point as a rim angle of its own
/// (considerSharedRimPoint). Where commonPoint finds none (rims touching to
/// rounding with nearly parallel tangents: its chord's ends are square roots
/// of near-zero differences, off by more than its slack), the exact
/// distance's nearest points, midway, when they are within the touching
/// tolerance (fuzz_disk_intersection, regression-touching-rims-nearly-
/// parallel-tangents: depth 2.1e-8 of a scene of 3.4 reported where PD is 0).
void considerSharedPointIfShallow(const PairInFrame1& pair, PenetrationSearch& search) {
  if (!(search.bestValue() <= kSharedPointDepth)) return;
  if (const auto common = internal::commonPoint(pair)) {
    search.considerSharedRimPoint(*common);
    return;
  }
  const internal::DiskPairAnswer nearest = internal::solveDiskPairInFrame1(pair);
  if (nearest.distance <= internal::kTouchingTolerance * pair.scale()) {
    search.considerSharedRimPoint(0.5 * (nearest.p + nearest.q));
  }
}

/// The penetration of a pair in frame 1 whose lengths are in scene sizes.
/// `swapped`: the pair's disk 1 is the caller's disk 2 (the caller negates w),
/// which only changes the order of the kinks so that the tie-break is the
/// caller's +n1 either way. `shares_point`: the disks share a point (to the
/// touching tolerance, as intersectDisks decides), which lets the search prune.
Penetration penetrationInFrame1(const PairInFrame1& pair, bool swapped, bool shares_point) {
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

  // Pruning needs disks that share a point (to the touching tolerance): apart,
  // min F = -d lies at a critical pair no distance to rim 1 bounds.
  const std::function<double()> bound = [&search] {
    const double best = search.bestValue();
    return best > 0.0 ? best + internal::kPrunedCandidateSlack
                      : std::numeric_limits<double>::infinity();
  };
  considerRimCandidates(pair, search, shares_point ? &bound : nullptr);
  if (shares_point) considerSharedPointIfShallow(pair, search);
  search.polishBestRimPair();
  search.polishBestDirection();
  Penetration found = withWitnesses(pair, search.best());
  found.nearest_rim_to_axis = search.nearestRimToAxis();
  return found;
}

}  // namespace

namespace internal {

void forEachDiskPairPenetrationCandidate(const PairInFrame1& unit_pair,
                                         const std::function<void(const Vec3&)>& visit,
                                         const std::function<double()>* bound) {
  PenetrationSearch search(unit_pair, &visit);
  const Vec3 n2 = unit_pair.R.col(0).cross(unit_pair.R.col(1)).normalized();
  for (const Vec3& kink : {Vec3(Vec3::UnitZ()), Vec3(-Vec3::UnitZ()), n2, Vec3(-n2)}) {
    search.consider(kink);
  }
  considerRimCandidates(unit_pair, search, bound);
  if (bound) considerSharedPointIfShallow(unit_pair, search);
  // The polished directions too (consider() passes them on): where F is the
  // caller's, they are its minimiser to rounding.
  search.polishBestRimPair();
  search.polishBestDirection();
  // Rim 2 next to disk 1's axis: the rim pairs there also from rim 1, as
  // penetrationOfValidPair does (its directions mapped back to frame 1).
  if (search.nearestRimToAxis() < kNearAxis) {
    const Mat3& R = unit_pair.R;
    const std::function<void(const Vec3&)> visit_in_frame1 = [&](const Vec3& w) {
      visit(R * w);
    };
    const PairInFrame1 from_disk2 = unit_pair.swapped();
    PenetrationSearch other(from_disk2, &visit_in_frame1);
    considerRimCandidates(from_disk2, other, bound);
    other.polishBestRimPair();
    other.polishBestDirection();
  }
}

}  // namespace internal

namespace {

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

/// The penetration found with one assignment of the roles: `swapped`, the
/// caller's disk 2 is the search's disk 1, whose frame the search runs in.
struct PenetrationWithRoles {
  Penetration found;
  bool swapped;
  double scale;
};

template <typename S>
PenetrationWithRoles penetrationWithRoles(S r1, const fcl::Transform3<S>& X_W1, S r2,
                                          const fcl::Transform3<S>& X_W2, bool swapped,
                                          bool shares_point) {
  const PairInFrame1 pair = swapped ? PairInFrame1::fromWorld(r2, X_W2, r1, X_W1)
                                    : PairInFrame1::fromWorld(r1, X_W1, r2, X_W2);
  const double scale = pair.scale();
  const PairInFrame1 unit_pair =
      PairInFrame1::make(pair.c / scale, pair.R, pair.r1 / scale, pair.r2 / scale);
  return {penetrationInFrame1(unit_pair, swapped, shares_point), swapped, scale};
}

/// diskPenetration of a valid pair; `shares_point` as for penetrationInFrame1.
template <typename S>
DiskSignedDistanceResult<S> penetrationOfValidPair(S r1, const fcl::Transform3<S>& X_W1, S r2,
                                                   const fcl::Transform3<S>& X_W2,
                                                   bool shares_point) {
  // Q parameterises the rim of the pair's disk 2 and measures from disk 1's
  // axis: with the smaller disk as disk 2 its terms are of the size of its
  // features (with a disk 1e-5 the size of the other as disk 2's partner,
  // Q's structure near the small disk would sit 1e-20 below its terms, under
  // the rounding).
  PenetrationWithRoles best = penetrationWithRoles(r1, X_W1, r2, X_W2, r2 > r1, shares_point);
  // Where rim 2 came within kNearAxis of disk 1's axis, Q's roots there are
  // known only to a few digits; the other roles place those pairs from the
  // other rim, and the smaller F of the two is the depth (each is an upper
  // bound on it).
  if (best.found.nearest_rim_to_axis < kNearAxis) {
    const PenetrationWithRoles other =
        penetrationWithRoles(r1, X_W1, r2, X_W2, !best.swapped, shares_point);
    if (other.found.depth < best.found.depth - kPolishSlack) best = other;
  }
  const Penetration& found = best.found;
  const bool swapped = best.swapped;
  const double scale = best.scale;
  const auto& X_WA = swapped ? X_W2 : X_W1;  // the frame the search ran in
  const internal::Mat3 R_WA = internal::diskRotationInDouble(X_WA);
  const Vec3 c_A = X_WA.translation().template cast<double>();
  const Vec3 p_WA = c_A + R_WA * (found.p1 * scale), p_WB = c_A + R_WA * (found.p2 * scale);
  DiskSignedDistanceResult<S> result;
  result.signed_distance = S(-found.depth * scale);
  result.p_W1 = (swapped ? p_WB : p_WA).template cast<S>();
  result.p_W2 = (swapped ? p_WA : p_WB).template cast<S>();
  // Swapped, w moves the caller's disk 1: disk 2 moves along -w.
  const Vec3 w_W = (R_WA * found.w).normalized();
  result.direction = (swapped ? Vec3(-w_W) : w_W).template cast<S>();
  return result;
}

}  // namespace

template <typename S>
DiskSignedDistanceResult<S> diskPenetration(S r1, const fcl::Transform3<S>& X_W1, S r2,
                                            const fcl::Transform3<S>& X_W2) {
  if (!internal::checkDiskPair(r1, X_W1, r2, X_W2).valid) return nanSignedDistance<S>();
  // Decided as intersectDisks decides, so that the hook, which knows that
  // decision already, answers bit for bit the same.
  const bool shares_point =
      internal::commonPoint(PairInFrame1::fromWorld(r1, X_W1, r2, X_W2)).has_value();
  return penetrationOfValidPair(r1, X_W1, r2, X_W2, shares_point);
}

namespace internal {

template <typename S>
DiskSignedDistanceResult<S> penetrationOfIntersecting(S r1, const fcl::Transform3<S>& X_W1, S r2,
                                                      const fcl::Transform3<S>& X_W2) {
  return penetrationOfValidPair(r1, X_W1, r2, X_W2, true);
}

template DiskSignedDistanceResult<float> penetrationOfIntersecting(
    float, const fcl::Transform3<float>&, float, const fcl::Transform3<float>&);
template DiskSignedDistanceResult<double> penetrationOfIntersecting(
    double, const fcl::Transform3<double>&, double, const fcl::Transform3<double>&);

}  // namespace internal

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
