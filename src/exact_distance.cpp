// Exact disk-disk distance. Derivation: docs/exact_distance.md; the names below
// (c, R, m, s, psi, g, H, lambda/mu, the certificate g(w)) are the document's.
#include "fcl_disk/exact_distance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "pair_in_frame1.h"

namespace fcl_disk {
namespace {

using internal::PairInFrame1;
using internal::Vec2;
using internal::Mat3;
using internal::Vec3;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kTwoPi = 6.283185307179586;

/// Newton stops when the certified gap |q - p| - g is below this many scene
/// sizes: 45 ulps, comfortably under the 1e-12 promise and above the
/// rounding noise (a few ulps) of evaluating both bounds.
constexpr double kGapTolerance = 1e-14;

/// Newton also stops when psi decreases by less than kStagnation * scale^2 in a
/// step (no progress at all: flat, near-degenerate optima; a larger threshold
/// would stop the slow but real progress on near-parallel rims a few 1e-10
/// apart), or when a rim step is below kStepAtRounding * scale.
constexpr double kStagnation = 4 * kEps * kEps;
constexpr double kStepAtRounding = 4 * kEps;

/// A rim step predicted to decrease psi = d^2 / 2 by less than d *
/// kPsiRounding * eps * scale cannot be seen to (psi's rounding is about d
/// times the eps * scale rounding of the points), so once the certificate is
/// due the iteration reports instead of taking it. A quarter of that rounding:
/// a step stopped too early leaves the certificate open and costs the
/// fallback searches; one taken too many costs one step.
constexpr double kPsiRounding = 0.25;

/// Relative Tikhonov term tau = kModelRegularisation * trace(H) of the
/// disk-constrained model: negligible against any real curvature, it only pins
/// the step along psi's flat directions.
constexpr double kModelRegularisation = 1e-10;

/// A point within this relative distance of disk 1's rim counts as on it.
constexpr double kOnRimTolerance = 4 * kEps;

/// The rim Newton step is tried while the gradient points inwards by less than
/// this fraction of its length (rounding noise on a nearly tangential gradient).
constexpr double kInwardGradientTolerance = 1e-3;

/// Largest angle one rim Newton step may turn, and the halvings tried when a
/// rim step does not decrease psi before falling back to the model step.
constexpr double kMaxRimStep = 1.5707963267948966;  // pi / 2
constexpr int kMaxRimHalvings = 8;

/// The certificate is evaluated once a rim Newton step is below this many
/// scene sizes (then the gap is at most about its square), or off the rim.
constexpr double kCertifyStep = 1e-6;

/// The rim iteration's start uses disk 2's geometry over plane 1 only for
/// planes at least this far (sine of the angle, ~6 degrees) from parallel: the
/// start point divides by s. Fewer iterations for any value in 0.01-0.3 on
/// every family of test/disk_families.h (docs/exact_distance.md, section 4).
constexpr double kTiltedStart = 0.1;

/// The fallbacks (solveInFrame1: local rim search, the iteration on disk 2's
/// rim, global rim search, each only while the gap is still open) run when
/// Newton ends with a certified gap above kFallbackGap * scale (well above the
/// certificate's own rounding, so only genuinely unconverged pairs pay for
/// them). The global search: kRimSamples samples, the kRimCandidates lowest
/// local minima refined, each by at most kMaxRimSearchIterations golden-section
/// steps (enough to shrink a bracket of two samples to the resolution of theta).
constexpr double kFallbackGap = 1e-12;
constexpr int kRimSamples = 256;
constexpr int kRimCandidates = 4;
constexpr int kMaxRimSearchIterations = 80;

/// Before the global rim search, the local minimum of psi along disk 1's rim
/// next to Newton's answer is bracketed (steps from kFirstBracketStep radians,
/// growing by kBracketGrowth up to a half turn) and refined like a sampled
/// minimum. Newton crawls where psi along the rim is a rounded V: nearly
/// coplanar rims crossing in projection, where psi's curvature jumps by ~1/tilt^2
/// within an angle ~d / r (docs/exact_distance.md, section 4); the first step is
/// far below any such width that double resolves.
constexpr double kFirstBracketStep = 1e-9;
constexpr double kBracketGrowth = 4.0;

/// A lens corner (the crossing for parallel planes, off by O(s^2 r2)
/// otherwise) starts the candidate's Newton iteration, which takes at most
/// kMaxCornerIterations steps. It is not refined first (a Newton step on
/// rho(theta) - r2 towards the exact crossing): that proves a few more corners
/// but costs every corner attempt a step, more than the fallbacks it spares
/// (docs/exact_distance.md, section 4).
constexpr int kMaxCornerIterations = 8;

/// The direction of q - x is known to about 2 eps scale / d (both points carry
/// rounding of eps scale): a lens-corner answer's points count as proven when
/// the certificate along q - x closes up to (r1 + r2) kSeparationRounding eps
/// scale / d, the term exact_distance.h documents for small distances.
constexpr double kSeparationRounding = 8.0;

/// The certificate tries t1 x t2 only when it is at least this long (the
/// tangents' sine, for points on the rims): its squares then stay normal, and
/// its direction is still good to eps / kMinTangentCross.
constexpr double kMinTangentCross = 1e-8;

/// Iterations are capped: median 3-4 on rim-rim pairs; the ~1% that reach the
/// cap are flat, near-degenerate optima, handed to the rim search when their
/// certificate is still open (docs/exact_distance.md, section 4).
constexpr int kMaxNewtonIterations = 16;

/// (cos, sin) of the rim step by the angle dtheta, as the rational (Cayley)
/// rotation ((1 - h^2), 2h) / (1 + h^2) with h = dtheta / 2: the rotation by
/// 2 atan(dtheta / 2), unit to rounding, which agrees with the rotation by
/// dtheta to third order (so Newton stays quadratic) at the cost of one
/// division: no trigonometry, no square root.
Vec2 cayleyRotation(double dtheta) {
  const double h = 0.5 * dtheta;
  const double inverse = 1.0 / (1.0 + h * h);
  return Vec2((1.0 - h * h) * inverse, 2.0 * h * inverse);
}

/// Exact line search along a Newton step (regula falsi on psi'): at most
/// kMaxLineSearchSteps evaluations, stopping when psi' has fallen below
/// kLineSearchFlatness of its initial slope or the bracket is
/// kLineSearchResolution of the step (beyond that psi's rounding dominates).
constexpr int kMaxLineSearchSteps = 60;
constexpr double kLineSearchFlatness = 1e-6;
constexpr double kLineSearchResolution = 1e-15;

/// The multiplier mu of the disk-constrained model step is found to this
/// relative accuracy (the step then lands on the rim to rounding) within
/// kMaxSecularIterations secant/bisection steps.
constexpr double kSecularTolerance = 1e-15;
constexpr int kMaxSecularIterations = 32;

/// A face-case point whose projection falls outside the other disk's rim by at
/// most this many scene sizes is clamped onto the rim. The clamped pair is at
/// most that much longer than the face height, which certifies a lower bound
/// (section 2 of the document), so the answer stays 10x inside the 1e-12
/// promise; without the slack, optima at the face/rim boundary (rim resting on
/// rim) would go to the rim-rim iteration, whose problem is degenerate there.
constexpr double kFaceSlack = internal::kTouchingTolerance;

/// Disk 2's face counts as parallel to plane 1 for disk 1's face case when its
/// heights over plane 1, c_z +- r2 s, differ from c_z by at most this many
/// scene sizes: then the height c_z over any point of the projections'
/// overlap is the distance to within that, certified by the face height
/// |c_z| - r2 s to within that, and the tie-break of exactly parallel planes
/// (the middle of the overlap along the line of centres) applies. Poses
/// parallel in exact arithmetic but rounded apart (a disk and a copy of it
/// turned about its normal, in one common frame) have s ~ 1e-16 and would
/// otherwise take the lowest rim point along the rounding's direction, which
/// lies over disk 1 or not by chance, and go to the rim iteration when not.
constexpr double kParallelHeightSpread = 0.5 * kGapTolerance;

/// faceOfDisk2MayHold decides in frame 1 what faceOfDisk1 decides on the
/// swapped pair, whose axes are the transpose of R: the two differ by a few
/// eps * scale of rounding, so it passes every pair within this many scene
/// sizes (about 450 eps) beyond faceOfDisk1's own limit.
constexpr double kFaceTestMargin = 1e-13;

struct Solution {
  Vec3 p;  // on disk 1, frame 1
  Vec3 q;  // on disk 2, frame 1
  double distance;
  DiskPairFeature feature;
  int iterations = 0;
  double lower_bound = 0.0;  // the certificate (section 2 of the document)
};

/// The point of the coplanar/parallel overlap of the projections of the disks,
/// along the line of centres (tie-break for face-face optima). Disk 2's centre
/// projects to (c_x, c_y); returns the in-plane point, or nullopt if the
/// projections are apart.
std::optional<Vec2> overlapOfProjections(const PairInFrame1& pair) {
  const double D = std::sqrt(pair.c.x() * pair.c.x() + pair.c.y() * pair.c.y());
  const auto t = internal::coplanarOverlapMidpoint(D, pair.r1, pair.r2);
  if (!t) return std::nullopt;
  return pair.pointOnCentreLine(*t);
}

/// Face case of disk 1: p inside disk 1's face, q the point of disk 2 nearest
/// plane 1. Valid (hence optimal, by the KKT conditions) iff disk 2 lies strictly
/// on one side of plane 1 and q projects into disk 1.
std::optional<Solution> faceOfDisk1(const PairInFrame1& pair, double scale) {
  const double cz = pair.c.z();
  const double lowest_height = pair.disk2ClearanceOfPlane1();
  if (!(lowest_height > 0.0)) return std::nullopt;
  const double side = cz > 0.0 ? 1.0 : -1.0;
  Vec3 q;
  if (pair.r2 * pair.s > kParallelHeightSpread * scale) {
    q = pair.rimPointTowardsPlane1();
    q.z() = side * lowest_height;  // exact height, free of the rotation's rounding
  } else {
    const auto overlap = overlapOfProjections(pair);
    if (!overlap) return std::nullopt;
    q = Vec3(overlap->x(), overlap->y(), cz);
  }
  Vec3 p(q.x(), q.y(), 0.0);
  const double radial = std::sqrt(p.x() * p.x() + p.y() * p.y());
  if (radial > pair.r1) {
    if (radial > pair.r1 + kFaceSlack * scale) return std::nullopt;
    p.head<2>() *= pair.r1 / radial;
  }
  return Solution{p, q, (q - p).norm(), DiskPairFeature::face1_rim2};
}

/// Whether disk 2's face case (faceOfDisk1 of pair.swapped()) may hold, from
/// frame 1 without building the swapped pair: disk 1's rim point extreme
/// towards plane 2, x = -side r1 m2 / |m2| (m2 = (R(0,2), R(1,2)), the
/// in-plane part of n2; side the sign of c1's height over plane 2), projects
/// into disk 2 to kFaceSlack + kFaceTestMargin scene sizes. In disk 2's plane
/// coordinates that foot is y0 + R_xy^T x (y0 = c1's, R_xy the top-left 2x2
/// block of R); compared scaled by |m2| and squared, so one square root and
/// no division. Requires disk1ClearanceOfPlane2() > 0; parallel planes
/// (m2 = 0) pass.
bool faceOfDisk2MayHold(const PairInFrame1& pair, double scale) {
  const Mat3& R = pair.R;
  const Vec2 m2(R(0, 2), R(1, 2));
  const double m2_length = std::sqrt(m2.squaredNorm());
  const double side_r1 = pair.c1_in_frame2.z() > 0.0 ? pair.r1 : -pair.r1;
  // |m2| times the foot: |m2| y0 - side r1 R_xy^T m2.
  const Vec2 scaled_foot(
      m2_length * pair.c1_in_frame2.x() - side_r1 * (R(0, 0) * m2.x() + R(1, 0) * m2.y()),
      m2_length * pair.c1_in_frame2.y() - side_r1 * (R(0, 1) * m2.x() + R(1, 1) * m2.y()));
  const double reach = (pair.r2 + (kFaceSlack + kFaceTestMargin) * scale) * m2_length;
  return !(scaled_foot.squaredNorm() > reach * reach);
}

/// The certificate g(w) = w.c - r1|P1 w| - r2|P2 w|: a lower bound of the
/// distance for unit w, positively homogeneous (callers divide by |w|).
double lowerBound(const PairInFrame1& pair, const Vec3& w) {
  return w.dot(pair.c) - pair.r1 * pair.inPlane1(w) - pair.r2 * pair.inPlane2(w);
}

/// The certificate at the face normals +-n1, +-n2, where g has its kinks: there
/// g is only Lipschitz, so near-face optima are certified better by the normal
/// itself than by a slightly misdirected separation direction. Constant per pair.
double faceLowerBound(const PairInFrame1& pair) {
  return std::max({0.0, pair.disk2ClearanceOfPlane1(), pair.disk1ClearanceOfPlane2()});
}

/// psi(s) = |x - proj_K2(x)|^2 / 2 for x = (s, 0) on plane 1
/// (docs/exact_distance.md, section 4). proj_K2(x) is found in two dimensions:
/// x's coordinates y in disk 2's plane are affine in s, and the projection is y
/// itself (over disk 2's face) or y pulled onto the circle of radius r2 (over
/// its rim). psi and its gradient are then taken from
/// the points themselves, q - x in frame 1, so that they stay consistent with
/// the certificate's q - x when R is orthonormal only to rounding (a float pose
/// widened to double); the Hessian, which only shapes the steps, comes from the
/// two-dimensional pieces on demand.
struct PointToDisk2 {
  Vec2 y;              ///< x - c in disk 2's plane coordinates: R^T (x - c), first two.
  double inverse_rho;  ///< 1 / |y| over disk 2's rim, 0 over its face.
  Vec3 q;              ///< proj_K2(x), frame 1.
  double psi;          ///< |x - q|^2 / 2.
  Vec2 gradient;       ///< (x - q)_xy.

  /// psi's Hessian a I + b v v^T: m2 m2^T over the face (m2 the in-plane part
  /// of n2), I - (r2/rho) t t^T over the rim (t = n2 x e, e = y / rho, the
  /// Hessian of dist^2/2 to a circle outside its disk).
  Eigen::Matrix2d hessian(const PairInFrame1& pair) const {
    const Mat3& R = pair.R;
    if (inverse_rho == 0.0) {
      const Vec2 m2(R(0, 2), R(1, 2));
      return m2 * m2.transpose();
    }
    const Vec2 e = inverse_rho * y;
    const Vec2 t(R(0, 1) * e.x() - R(0, 0) * e.y(), R(1, 1) * e.x() - R(1, 0) * e.y());
    return Eigen::Matrix2d::Identity() - (pair.r2 * inverse_rho) * t * t.transpose();
  }
};

/// What evaluate measures x's distance to: disk 2 (psi), or disk 2's rim
/// circle (phi: psi's rim branch continued over disk 2's face, where it
/// exceeds psi; smooth wherever x is off disk 2's axis, so the lens-corner
/// candidates iterate on it).
enum class DistanceTo { disk2, rim2 };

template <DistanceTo kTarget = DistanceTo::disk2>
PointToDisk2 evaluate(const PairInFrame1& pair, const Vec2& s) {
  const Mat3& R = pair.R;
  PointToDisk2 out;
  // R^T (x - c) = R^T x + c1_in_frame2, with x = (s, 0).
  out.y = Vec2(R(0, 0) * s.x() + R(1, 0) * s.y() + pair.c1_in_frame2.x(),
               R(0, 1) * s.x() + R(1, 1) * s.y() + pair.c1_in_frame2.y());
  const double rho_squared = out.y.squaredNorm();
  Vec2 nearest = out.y;  // proj_K2(x) in disk 2's plane coordinates
  out.inverse_rho = 0.0;
  if (!(kTarget == DistanceTo::disk2 && rho_squared <= pair.r2 * pair.r2)) {
    // 1/rho as sqrt(rho^2) * (1/rho^2): the square root and the division
    // run side by side instead of one after the other.
    out.inverse_rho = std::sqrt(rho_squared) * (1.0 / rho_squared);
    nearest = (pair.r2 * out.inverse_rho) * out.y;
  }
  out.q = pair.pointOfDisk2(nearest);
  const Vec3 residual = Vec3(s.x(), s.y(), 0.0) - out.q;
  out.psi = 0.5 * residual.squaredNorm();
  out.gradient = residual.head<2>();
  return out;
}

/// psi's derivatives along disk 1's rim at x = r1 (radial, 0), in the angle
/// theta: psi' = r1 sigma and psi'' = r1 (r1 curvature + outward), with
/// sigma = g.t and outward = -g.radial (g the gradient, t = perp(radial)) and
/// curvature = t^T H t, the last from x's coordinates in disk 2's frame.
struct AlongRim {
  double sigma;
  double outward;
  double curvature;
};

AlongRim alongRim(const PairInFrame1& pair, const PointToDisk2& at, const Vec2& radial) {
  const Mat3& R = pair.R;
  const Vec2 tangent(-radial.y(), radial.x());
  // R^T t (in-plane part, and height over plane 2).
  const Vec2 t2(R(0, 0) * tangent.x() + R(1, 0) * tangent.y(),
                R(0, 1) * tangent.x() + R(1, 1) * tangent.y());
  const double t_height = R(0, 2) * tangent.x() + R(1, 2) * tangent.y();
  const double sigma = at.gradient.dot(tangent), outward = -at.gradient.dot(radial);
  if (at.inverse_rho == 0.0) return {sigma, outward, t_height * t_height};  // H = m2 m2^T
  // Over the rim: t^T H t = 1 - (r2 / rho) (T.t)^2 with T = perp(y) / rho disk
  // 2's rim tangent (|R^T t| = 1).
  const double across = at.y.x() * t2.y() - at.y.y() * t2.x();  // perp(y).t2, up to sign
  const double inverse_rho_cubed = at.inverse_rho * at.inverse_rho * at.inverse_rho;
  return {sigma, outward, 1.0 - pair.r2 * inverse_rho_cubed * across * across};
}

/// The certificate at x (frame 1, on plane 1) and q on disk 2: the best of g
/// at the face normals, along q - x, and along t1 x t2, the tangents of the
/// circles about c1 through x and about c2 through q (t1 = n1 x x,
/// t2 = n2 x (q - c); either sign: g(-w) differs from g(w) only in the sign of
/// w.c). At a rim-rim optimum the separation lies in both rims' normal planes,
/// so t1 x t2 is its direction, computed without the cancellation of q - x: for
/// distances d near rounding, q - x knows its direction only to eps scale / d,
/// t1 x t2 to eps / sin(t1, t2) (docs/exact_distance.md, section 2).
///
/// Newton's stopping test uses separationCertificate alone: a gap closed by
/// t1 x t2 says the distance is right, not that x and q are (near a face case
/// the optimum is flat, and a distance 2e-14 too long can come with points
/// whose separation is 1e-6 rad off the optimal direction); closing it along
/// q - x proves the points too.
double separationCertificate(const PairInFrame1& pair, const Vec3& x, const Vec3& q,
                             double face_lower_bound) {
  // g is positively homogeneous, g(w / |w|) = g(w) / |w|: one division.
  const Vec3 separation = q - x;
  const double distance = separation.norm();
  return distance > 0.0 ? std::max(face_lower_bound, lowerBound(pair, separation) / distance)
                        : face_lower_bound;
}

/// The certificate along t1 x t2 alone (see certificate()), or 0 when the
/// tangents are too close to parallel for it.
double tangentCrossCertificate(const PairInFrame1& pair, const Vec3& x, const Vec3& q) {
  // Scaled by the radii, so that w's squares stay in double's range at every
  // length scale (|w| <= 1); oriented towards disk 2 (w.c >= 0).
  const Vec3 t1(-x.y() / pair.r1, x.x() / pair.r1, 0.0);
  Vec3 w = t1.cross(pair.R.col(2).cross((q - pair.c) / pair.r2));
  if (w.dot(pair.c) < 0.0) w = -w;
  const double length = w.norm();
  return length > kMinTangentCross ? lowerBound(pair, w) / length : 0.0;
}

/// The certificate along q - x with its component along rim 1's tangent t1 at
/// x dropped (0 if nothing is left). At a rim-rim optimum the separation lies
/// in disk 1's normal cone at x, spanned by x's radial direction and n1, so
/// that component is rounding. It matters where t1 x t2 fails: rims side by
/// side in nearly parallel planes, whose tangents at the optimum are nearly
/// parallel. There q - x knows its direction within the planes only to about
/// delta = eps scale / d, which costs the certificate about (r1 + r2) delta^2
/// / 2; after the projection the rounding left turns the direction within the
/// normal plane, which costs only d delta^2 / 2 (docs/exact_distance.md,
/// section 2).
double rimNormalPlaneCertificate(const PairInFrame1& pair, const Vec3& x, const Vec3& q) {
  const Vec3 t1(-x.y() / pair.r1, x.x() / pair.r1, 0.0);
  const Vec3 separation = q - x;
  const Vec3 w = separation - separation.dot(t1) * t1;
  const double length = w.norm();
  return length > 0.0 ? lowerBound(pair, w) / length : 0.0;
}

/// The certificate at x and q, `distance` = |q - x| apart, given the one along
/// q - x (`along_separation`): with t1 x t2, then q - x normal to t1, each
/// tried only while the gap to `distance` is above kGapTolerance * scale
/// (the usual case needs neither; crossing tangents need no third).
double withRimDirections(const PairInFrame1& pair, const Vec3& x, const Vec3& q, double distance,
                         double along_separation, double scale) {
  const double tolerance = kGapTolerance * scale;
  if (distance - along_separation <= tolerance) return along_separation;
  const double lower = std::max(along_separation, tangentCrossCertificate(pair, x, q));
  if (distance - lower <= tolerance) return lower;
  return std::max(lower, rimNormalPlaneCertificate(pair, x, q));
}

/// What the rounding of the direction of q - x, for points `distance` apart,
/// can cost the certificate along it: the points carry eps * scale of rounding,
/// so the direction is known to about 2 eps scale / distance, and g is
/// Lipschitz with constant r1 + r2 at its kinks (kSeparationRounding).
double separationRounding(const PairInFrame1& pair, double scale, double distance) {
  return distance > 0.0 ? (pair.r1 + pair.r2) * kSeparationRounding * kEps * scale / distance
                        : 0.0;
}

/// The best of the certificates along q - x, t1 x t2 and q - x normal to t1.
double certificate(const PairInFrame1& pair, const Vec3& x, const Vec3& q,
                   double face_lower_bound) {
  return withRimDirections(pair, x, q, (q - x).norm(),
                           separationCertificate(pair, x, q, face_lower_bound), pair.scale());
}

/// Exact line search along `step` from s: psi is convex along the segment, so
/// psi'(alpha) = gradient(s + alpha step).step is monotone. Returns alpha *
/// step for the minimiser over alpha in (0, 1]: the full step when psi'(1) <= 0,
/// else regula falsi (Illinois) on psi', which finds e.g. the point where the
/// step crosses from disk 2's face region into its rim region, a kink of psi''
/// that a one-piece quadratic model cannot see. *at_end receives psi there.
Vec2 exactLineSearch(const PairInFrame1& pair, const Vec2& s, const Vec2& step, double slope,
                     PointToDisk2* at_end) {
  PointToDisk2 next = evaluate(pair, s + step);
  double derivative_hi = next.gradient.dot(step);
  double alpha = 1.0;
  if (derivative_hi > 0.0) {
    double lo = 0.0, hi = 1.0, derivative_lo = slope;
    PointToDisk2 at_lo = evaluate(pair, s);
    int last_side = 0;  // +1: last point had psi' > 0, -1: psi' <= 0
    for (int k = 0; k < kMaxLineSearchSteps; ++k) {
      alpha = (lo * derivative_hi - hi * derivative_lo) / (derivative_hi - derivative_lo);
      if (!(alpha > lo && alpha < hi)) alpha = 0.5 * (lo + hi);
      next = evaluate(pair, s + alpha * step);
      const double derivative = next.gradient.dot(step);
      if (derivative > 0.0) {
        hi = alpha, derivative_hi = derivative;
        if (last_side == 1) derivative_lo *= 0.5;  // Illinois: no stuck endpoint
        last_side = 1;
      } else {
        lo = alpha, derivative_lo = derivative, at_lo = next;
        if (last_side == -1) derivative_hi *= 0.5;
        last_side = -1;
        if (derivative >= kLineSearchFlatness * slope) break;  // psi' ~ 0: done
      }
      if (hi - lo <= kLineSearchResolution * hi) break;
    }
    if (next.psi > at_lo.psi) alpha = lo, next = at_lo;
  }
  *at_end = next;
  return alpha * step;
}

/// Step delta minimising the regularised model g.delta + delta'(H + tau I)delta/2
/// subject to |s + delta| <= r1, for H symmetric positive semidefinite (2x2).
/// Written in delta (not in the point s + delta) so that small steps are not
/// computed as differences of O(r1) numbers. tau > 0 makes the model strictly
/// convex: along directions where psi is flat (its Hessian is rank one where x
/// projects into disk 2's face) the step stays near s instead of wandering.
/// delta(mu) = -(H + (tau + mu) I)^-1 (g + mu s) for the multiplier mu >= 0 of
/// the disk; |s + delta(mu)| decreases in mu, so mu is found by safeguarded
/// secant steps on f(mu) = |s + delta(mu)|^2 - r1^2 (computed as
/// 2 s.delta + |delta|^2 + |s|^2 - r1^2, again free of cancellation).
Vec2 stepOnDisk(const Eigen::Matrix2d& H, const Vec2& g, const Vec2& s, double r1) {
  const double tau = kModelRegularisation * H.trace() + std::numeric_limits<double>::min();
  auto step_for = [&](double mu) -> Vec2 {
    const double a = H(0, 0) + tau + mu, b = H(0, 1), d = H(1, 1) + tau + mu;
    const Vec2 rhs = g + mu * s;
    return Vec2(-(d * rhs.x() - b * rhs.y()), -(a * rhs.y() - b * rhs.x())) / (a * d - b * b);
  };
  const double slack = s.squaredNorm() - r1 * r1;  // <= 0 for a feasible s
  auto excess = [&](const Vec2& delta) { return 2.0 * s.dot(delta) + delta.squaredNorm() + slack; };
  Vec2 delta = step_for(0.0);
  double f_lo = excess(delta);
  if (f_lo <= 0.0) return delta;  // the Newton step stays in the disk
  // Bracket: at mu_hi = |g + mu s|/r1-ish the step cannot leave the disk.
  double mu_lo = 0.0, mu_hi = (g.norm() + tau * s.norm()) / r1 + r1 * 0.0;
  mu_hi = std::max(mu_hi, tau);
  Vec2 delta_hi = step_for(mu_hi);
  double f_hi = excess(delta_hi);
  for (int grow = 0; f_hi > 0.0 && grow < kMaxSecularIterations; ++grow) {
    mu_lo = mu_hi, f_lo = f_hi;
    mu_hi *= 4.0;
    delta_hi = step_for(mu_hi);
    f_hi = excess(delta_hi);
  }
  Vec2 best = delta_hi;  // feasible end of the bracket
  int last_side = 0;      // Illinois: halve a stale endpoint's value
  for (int iteration = 0; iteration < kMaxSecularIterations; ++iteration) {
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
      if (f >= -kSecularTolerance * r1 * r1) break;
    }
    if (mu_hi - mu_lo <= kSecularTolerance * mu_hi) break;
  }
  return best;
}

/// The direction of v, or (1, 0) for v = 0. It starts the rim iteration's
/// chain, so 1 / |v| is sqrt(|v|^2) * (1 / |v|^2), a square root and a division
/// side by side, where |v|^2 is normal; otherwise (|v| subnormal, where 1 / |v|
/// overflows, or beyond 1e154) v is divided per component by |v|.
Vec2 directionOf(const Vec2& v) {
  const double length_squared = v.squaredNorm();
  if (std::isnormal(length_squared)) {
    return std::sqrt(length_squared) * (1.0 / length_squared) * v;
  }
  const double length = v.norm();
  return length > 0.0 ? Vec2(v.x() / length, v.y() / length) : Vec2(1.0, 0.0);
}

/// s times the projection onto plane 1 of disk 2's rim point extreme towards
/// plane 1 (PairInFrame1::rimPointTowardsPlane1), which needs no division by s:
/// s c_xy - sign(c_z) r2 (R_xy m), with R_xy the top-left 2x2 block of R.
Vec2 scaledFootOfDisk2(const PairInFrame1& pair) {
  const Mat3& R = pair.R;
  const double side_r2 = pair.c.z() > 0.0 ? pair.r2 : -pair.r2;
  return Vec2(pair.s * pair.c.x() - side_r2 * (R(0, 0) * pair.m.x() + R(0, 1) * pair.m.y()),
              pair.s * pair.c.y() - side_r2 * (R(1, 0) * pair.m.x() + R(1, 1) * pair.m.y()));
}

/// |m|^2 times the projection onto plane 1 of the point of disk 2's chord on
/// plane 1 nearest c1 (ChordOnPlane1 with its parameter clamped), for s > 0
/// and disk 2 crossing plane 1, with no square root or division before it
/// unless the chord's end is the point: with M = |m|^2, E = m_a u + m_b v and
/// Q = -m_b u + m_a v (u, v disk 2's axes), the chord is c - c_z E / M + tau
/// Q / s, its point nearest c1 at tau = -c.Q / s (E.Q = 0), so M times that
/// point is M c - c_z E - (c.Q) Q; past the half-length sqrt(r2^2 - c_z^2 / M)
/// the chord's end, M c - c_z E - sign(c.Q) sqrt(r2^2 M - c_z^2) Q.
Vec2 scaledChordPointNearestC1(const PairInFrame1& pair) {
  const Mat3& R = pair.R;
  const Vec2& m = pair.m;
  const double M = m.squaredNorm();
  const Vec3 E = m.x() * R.col(0) + m.y() * R.col(1);
  const Vec3 Q = -m.y() * R.col(0) + m.x() * R.col(1);
  const double c_along = pair.c.dot(Q);
  const double half_squared_M = pair.r2 * pair.r2 * M - pair.c.z() * pair.c.z();
  const double tau_M = c_along * c_along <= half_squared_M
                           ? c_along
                           : std::copysign(std::sqrt(std::max(0.0, half_squared_M)), c_along);
  return Vec2(M * pair.c.x() - pair.c.z() * E.x() - tau_M * Q.x(),
              M * pair.c.y() - pair.c.z() * E.y() - tau_M * Q.y());
}

/// Where the rim iteration starts (only its speed depends on it; measured in
/// docs/exact_distance.md, section 4): disk 1's rim point towards where disk 2
/// comes nearest plane 1, projected: the point of disk 2's chord on plane 1
/// nearest c1 when disk 2 crosses plane 1, else disk 2's rim point extreme
/// towards plane 1. Towards c2's projection instead when disk 1 crosses plane 2
/// but disk 2 does not cross plane 1 (there that start is better), and for
/// planes within kTiltedStart (sine) of parallel, where the point is
/// ill-conditioned (it divides by s).
Vec2 rimStartDirection(const PairInFrame1& pair) {
  const Vec2 towards_c2(pair.c.x(), pair.c.y());
  if (!(pair.s > kTiltedStart)) return directionOf(towards_c2);
  if (pair.disk2ClearanceOfPlane1() <= 0.0) {  // disk 2 crosses plane 1
    return directionOf(scaledChordPointNearestC1(pair));
  }
  if (pair.disk1ClearanceOfPlane2() <= 0.0) return directionOf(towards_c2);
  return directionOf(scaledFootOfDisk2(pair));  // towards rimPointTowardsPlane1()
}

/// rimRim's `converging` test for a rim step of dtheta >= 0 radians with
/// curvature kappa (psi'' = r1 kappa) at a point where psi = d^2 / 2: the
/// step moves the point by at most kCertifyStep * scale, and the decrease of
/// psi it predicts, r1 kappa dtheta^2 / 2, is within what the gap tolerance
/// allows at that distance (d psi = d dd). d's square root is taken only for
/// a step that passes the first test.
bool rimStepConverging(double r1, double dtheta, double kappa, double psi, double scale) {
  return dtheta * r1 <= kCertifyStep * scale &&
         0.5 * r1 * kappa * dtheta * dtheta <= std::sqrt(2.0 * psi) * (kGapTolerance * scale);
}

/// The factors of to_rim = r2 / rho for a point of disk 2's frame at in-plane
/// distance rho, given rho^2 and r2 times a common factor (`scaled_squared`
/// = (f rho)^2, `scaled_r2` = f r2, any f > 0): root = f rho and ratio = f r2
/// / (f rho)^2, a square root and a division side by side, so that to_rim =
/// root * ratio and to_rim^2 = scaled_r2 * ratio. Over disk 2's face (rho <=
/// r2) every factor is 1 (to_rim = 1: the point's nearest is itself).
struct RimFactors {
  bool over_face;
  double root, ratio, scaled_r2;

  RimFactors(double scaled_squared, double scaled_r2_in)
      : over_face(!(scaled_squared > scaled_r2_in * scaled_r2_in)),
        root(over_face ? 1.0 : std::sqrt(scaled_squared)),
        ratio(over_face ? 1.0 : scaled_r2_in / scaled_squared),
        scaled_r2(over_face ? 1.0 : scaled_r2_in) {}
  double toRim() const { return root * ratio; }
  double toRimSquared() const { return scaled_r2 * ratio; }
};

/// Plain Newton along disk 1's rim, the path nearly every rim-rim query
/// takes to its answer, written as one short chain of arithmetic (the
/// iteration is latency-bound): x = r1 radial is carried in disk 2's frame as
/// offset2 = r1 R_xy^T radial and offset_height = r1 m2.radial, so a rotation
/// of radial by (cos, sin) moves y and h by (cos offset2 + r1 sin tangent2,
/// ...), tangent2 = R_xy^T t and tangent_height = m2.t the images of t =
/// perp(radial), which turn with it: no matrix product on the chain, and the
/// turn's division beside the next square root (docs/exact_distance.md,
/// section 4, "The plain path"). The steps are rimRim's (alongRim's sigma and
/// kappa, the Cayley rotation); the certificate is tried once the step Newton's
/// quadratic convergence predicts from the last two, dtheta_k^3 /
/// dtheta_(k-1)^2, would pass rimRim's `converging` test, so a query ends
/// with the evaluation of its last point and no step it would not take.
/// x may lie over disk 2's rim (nearest = (r2 / rho) y) or its face (nearest =
/// y, psi = h^2 / 2), and the gradient may point into disk 1 on the way (the
/// multiplier term of kappa is then dropped, as in rimRim); the optimum is on
/// the rim (section 4), so only a point where the rim steps stall with the
/// gradient pointing inwards needs rimRim's model step. A step beyond
/// kMaxRimStep is clamped to it, and a step that does not decrease psi is
/// halved (as rimRim does both). Returns the certified answer, or nullopt
/// with *radial at the last point reached when the steps stall: such a stall,
/// no positive curvature, or psi not decreasing beyond rounding after the
/// halvings (a certificate that fails earlier only means more steps; one that
/// fails at rounding level is reported with the other certificate directions
/// added, as rimRim reports it). rimRim then goes on from there. *steps
/// receives the number of steps taken.
std::optional<Solution> rimNewton(const PairInFrame1& pair, double scale, double face_lower_bound,
                                  Vec2* radial_io, int* steps) {
  const Mat3& R = pair.R;
  const double r1 = pair.r1, r2 = pair.r2;
  const double inverse_r1 = 1.0 / r1, inverse_r2 = 1.0 / r2;
  const Vec2 y0 = pair.c1_in_frame2.head<2>();
  const double h0 = pair.c1_in_frame2.z();
  const double gap_tolerance = kGapTolerance * scale;
  // The point x = r1 radial in disk 2's frame, y = offset2 + y0 and h =
  // offset_height + h0, with (offset2, offset_height) = r1 (R_xy^T radial,
  // m2.radial).
  Vec2 radial = *radial_io;
  Vec2 offset2(r1 * (R(0, 0) * radial.x() + R(1, 0) * radial.y()),
               r1 * (R(0, 1) * radial.x() + R(1, 1) * radial.y()));
  double offset_height = r1 * (R(0, 2) * radial.x() + R(1, 2) * radial.y());
  // The unit images of t = perp(radial), turned with the point.
  Vec2 tangent2(R(1, 0) * radial.x() - R(0, 0) * radial.y(),
                R(1, 1) * radial.x() - R(0, 1) * radial.y());
  double tangent_height = R(1, 2) * radial.x() - R(0, 2) * radial.y();
  Vec2 y = offset2 + y0;
  double h = offset_height + h0;
  // Over disk 2's rim proj_K2 pulls y onto the circle: nearest = to_rim y with
  // to_rim = r2 / rho (RimFactors); over its face nearest = y (to_rim = 1).
  // The turn below forms the factors from rho^2 and r2 times its denominator.
  const double rho_squared = y.squaredNorm();
  RimFactors rim(rho_squared, r2);
  double to_rim = rim.toRim();
  double psi = 0.5 * ((1.0 - to_rim) * (1.0 - to_rim) * rho_squared + h * h);
  double last_step = 0.0, step_before = 0.0, last_kappa = 0.0;
  const auto converging = [&](double dtheta, double kappa, double psi_at) {
    return rimStepConverging(r1, dtheta, kappa, psi_at, scale);
  };
  // The certificate at the current point, once tried, and the distance |q - x|
  // it is compared with (the points themselves, not psi: for a rotation that
  // is orthonormal only to rounding, say a float pose widened to double, psi's
  // two-dimensional form and |q - x| differ by that rounding), and the points
  // it was tried at, which are the answer's.
  std::optional<double> lower;
  Vec3 x_tried, q_tried;
  double distance_of_points = 0.0;
  // The certificate is separationCertificate's, max(face_lower_bound, g(q -
  // x) / |q - x|); its test is taken times |q - x|, which keeps the division
  // off the test's chain (only the returned bound waits for it).
  const auto certified = [&]() -> bool {
    x_tried = Vec3(r1 * radial.x(), r1 * radial.y(), 0.0);
    q_tried = pair.pointOfDisk2(to_rim * y);
    const Vec3 separation = q_tried - x_tried;
    distance_of_points = separation.norm();
    const double along = lowerBound(pair, separation);
    lower = distance_of_points > 0.0
                ? std::max(face_lower_bound, along / distance_of_points)
                : face_lower_bound;
    return distance_of_points - face_lower_bound <= gap_tolerance ||
           distance_of_points * distance_of_points - along <= gap_tolerance * distance_of_points;
  };
  const auto answer = [&](int steps_taken) {
    return Solution{x_tried, q_tried, distance_of_points, DiskPairFeature::rim_rim,
                    steps_taken + 1, *lower};
  };
  *steps = 0;
  for (int step = 0; step < kMaxNewtonIterations; ++step) {
    lower.reset();
    if (step_before > 0.0) {
      const double ratio = last_step / step_before;
      if (converging(last_step * ratio * ratio, last_kappa, psi)) {
        if (certified()) return answer(step);
      }
    }
    // alongRim over disk 2's rim, with the unit images of t, over r1
    // (sigma_hat = sigma / r1, kappa_hat = kappa / r1: ratios at every length
    // scale, for the turn below), arranged so that the factors of to_rim enter
    // last: with k = 1 - to_rim,
    //   sigma_hat = (k y.t2 + h t_h) / r1 = (y.t2 + h t_h) / r1 - root (ratio y.t2 / r1),
    //   kappa_hat = 1 + max(outward_hat, 0) - to_rim^2 root (ratio (y x t2 / r2)^2),
    //   outward_hat = to_rim out_rate - out_rest (the multiplier lambda),
    // and where outward_hat > 0, 1 + outward_hat = (1 - out_rest) + to_rim out_rate:
    // from the square root to kappa_hat two products and a difference.
    const double y_along = y.dot(tangent2), y_out = y.dot(offset2) * inverse_r1;
    const double h_out = h * offset_height * inverse_r1;
    const double y_along_hat = y_along * inverse_r1;
    const double out_rate = y_out * inverse_r1, out_rest = (y_out + h_out) * inverse_r1;
    const double across_over_r2 = (y.x() * tangent2.y() - y.y() * tangent2.x()) * inverse_r2;
    const double across_squared = across_over_r2 * across_over_r2;
    const double to_rim_squared = rim.toRimSquared();
    const double to_rim_out = rim.root * (rim.ratio * out_rate);
    const double sigma_hat = rim.over_face
                                 ? (h * inverse_r1) * tangent_height
                                 : (y_along_hat + (h * inverse_r1) * tangent_height) -
                                       rim.root * (rim.ratio * y_along_hat);
    const double outward_hat = rim.over_face ? -(h_out * inverse_r1) : to_rim_out - out_rest;
    const double kappa_hat =
        rim.over_face ? tangent_height * tangent_height + std::max(outward_hat, 0.0)
                      : (outward_hat > 0.0 ? (1.0 - out_rest) + to_rim_out : 1.0) -
                            to_rim_squared * (rim.root * (rim.ratio * across_squared));
    const double sigma = r1 * sigma_hat, kappa = r1 * kappa_hat;
    // The Cayley turn by 2 atan(dtheta / 2) over one denominator.
    const double half_sigma_hat = 0.5 * sigma_hat;
    const double denominator = kappa_hat * kappa_hat + half_sigma_hat * half_sigma_hat;
    if (!(kappa_hat > 0.0 && denominator >= std::numeric_limits<double>::min())) break;
    // A step beyond kMaxRimStep (far from the optimum, where psi is nearly
    // flat along the rim) is clamped to it, as rimRim clamps it.
    const bool clamped = !(std::abs(sigma_hat) <= kMaxRimStep * kappa_hat);
    const double dtheta = clamped ? kMaxRimStep : std::abs(sigma_hat) / kappa_hat;
    // Converged along the rim with the gradient pointing inwards: a spurious
    // rim minimum, which rimRim's model step leaves.
    if (outward_hat < 0.0 && converging(dtheta, kappa, psi)) break;
    if (converging(dtheta, kappa, psi)) {
      const double distance = std::sqrt(2.0 * psi);
      if (!lower && certified()) return answer(step);
      // Along q - x the gap is open by no more than the rounding of that
      // direction explains (small distances): the points are proven when the
      // other directions close it.
      if (distance_of_points - *lower <= separationRounding(pair, scale, distance_of_points)) {
        const double best =
            withRimDirections(pair, x_tried, q_tried, distance_of_points, *lower, scale);
        if (distance_of_points - best <= gap_tolerance) {
          lower = best;
          return answer(step);
        }
      }
      // At rounding (rimRim's tests), where rimRim reports the point with the
      // full certificate: along q - x the certificate's rounding grows like
      // scale (eps scale / d)^2 for small distances d, along t1 x t2 it does not.
      if (dtheta * r1 <= kStepAtRounding * scale ||
          0.5 * r1 * std::abs(sigma) * dtheta <= kPsiRounding * kEps * scale * distance) {
        lower = withRimDirections(pair, x_tried, q_tried, distance_of_points, *lower, scale);
        return answer(step);
      }
    }
    // The point turned by the Cayley rotation of the step (step_sigma_hat /
    // kappa_hat: sigma_hat for Newton's step), and psi there. The turn is
    // (cos, sin) = (kappa_hat^2 - step_sigma_hat^2 / 4, -step_sigma_hat
    // kappa_hat) / step_denominator; the next point's disk-2 coordinates are
    // first formed times step_denominator, as
    //   Y = step_denominator y' = kappa_hat (kappa_hat y - r1 step_sigma_hat t2)
    //       + (step_sigma_hat / 2)^2 (y0 - offset2),
    // whose |Y| gives to_rim = r2 / rho = r2 step_denominator / |Y| with no
    // wait for the turn's division: that division and the square root behind
    // to_rim then run side by side, not one after the other, on the
    // iteration's latency chain. Where |Y|^2 or (r2 step_denominator)^2 is not
    // a normal double (a pair at the ends of the range of lengths with a step
    // denominator far from 1), to_rim is taken from y' itself.
    struct Turned {
      double cos, sin;
      Vec2 offset2, tangent2, y;
      double offset_height, tangent_height, h, psi;
      RimFactors rim{0.0, 0.0};
    };
    const auto turnedBy = [&](double step_sigma_hat, double step_denominator) {
      Turned next;
      const double half_step = 0.5 * step_sigma_hat;
      const double half_step_squared = half_step * half_step;
      const double cos_scaled = kappa_hat * kappa_hat - half_step_squared;
      const double sin_scaled = -(step_sigma_hat * kappa_hat);
      const double r1_step = r1 * step_sigma_hat;
      const Vec2 y_scaled = kappa_hat * (kappa_hat * y - r1_step * tangent2) +
                            half_step_squared * (y0 - offset2);
      const double y_scaled_squared = y_scaled.squaredNorm();
      const double r2_scaled = r2 * step_denominator;
      const double inverse = 1.0 / step_denominator;
      next.cos = cos_scaled * inverse;
      next.sin = sin_scaled * inverse;
      const double r1_sin = r1 * next.sin;
      next.offset2 = next.cos * offset2 + r1_sin * tangent2;
      next.offset_height = next.cos * offset_height + r1_sin * tangent_height;
      // t turns with the point: t' = cos t - sin radial.
      next.tangent2 = next.cos * tangent2 - next.sin * (offset2 * inverse_r1);
      next.tangent_height = next.cos * tangent_height - next.sin * (offset_height * inverse_r1);
      next.y = y_scaled * inverse;
      next.h = next.cos * offset_height + (r1_sin * tangent_height + h0);
      const double rho_squared = next.y.squaredNorm();
      next.rim = std::isnormal(y_scaled_squared) && std::isnormal(r2_scaled * r2_scaled)
                     ? RimFactors(y_scaled_squared, r2_scaled)
                     : RimFactors(rho_squared, r2);
      const double next_k = 1.0 - next.rim.toRim();
      next.psi = 0.5 * (next_k * next_k * rho_squared + next.h * next.h);
      return next;
    };
    double step_sigma_hat = sigma_hat;
    Turned next;
    if (clamped) {
      step_sigma_hat = std::copysign(kMaxRimStep * kappa_hat, sigma_hat);
      next = turnedBy(step_sigma_hat,
                      kappa_hat * kappa_hat + 0.25 * step_sigma_hat * step_sigma_hat);
    } else {
      next = turnedBy(sigma_hat, denominator);
    }
    double step_taken = dtheta;
    if (clamped || !(next.psi < psi)) {
      // Newton's step overshoots (psi's curvature along the rim changes
      // within the step, e.g. a small disk 2 passed at about its own size):
      // halved, as rimRim halves it, at most kMaxRimHalvings times.
      for (int halving = 0; halving < kMaxRimHalvings && !(next.psi < psi); ++halving) {
        step_sigma_hat *= 0.5, step_taken *= 0.5;
        next = turnedBy(step_sigma_hat,
                        kappa_hat * kappa_hat + 0.25 * step_sigma_hat * step_sigma_hat);
      }
      step_before = 0.0;  // a damped step predicts nothing of the next one
    } else {
      step_before = last_step;
    }
    if (!(next.psi < psi) || psi - next.psi <= kStagnation * scale * scale) break;
    radial = Vec2(next.cos * radial.x() - next.sin * radial.y(),
                  next.cos * radial.y() + next.sin * radial.x());
    offset2 = next.offset2, offset_height = next.offset_height;
    tangent2 = next.tangent2, tangent_height = next.tangent_height;
    y = next.y, h = next.h, rim = next.rim;
    to_rim = rim.toRim(), psi = next.psi;
    last_step = step_taken;
    last_kappa = kappa;
    *steps = step + 1;
  }
  *radial_io = radial;
  return std::nullopt;
}

/// Rim-rim case: minimise the convex psi(s) = dist(x(s), K2)^2 / 2 over disk 1
/// (|s| <= r1). On the rim with a non-negative multiplier (the usual case) Newton
/// runs along the rim in the angle, with the rim's curvature lambda in the
/// second derivative; elsewhere (inside the disk, or on the rim where moving
/// inwards decreases psi, i.e. at a spurious minimum along the rim) the step
/// minimises psi's quadratic model over the disk, followed by an exact line
/// search. Iterates stay feasible and psi decreases, so by convexity they reach
/// the global minimum. Each iterate is a feasible pair (an upper bound); once
/// the steps are small the duality certificate (a lower bound) is evaluated and
/// the iteration stops when the two agree to kGapTolerance * scale. It starts
/// with rimNewton, the same iteration while its steps are plain Newton steps.
Solution rimRim(const PairInFrame1& pair, double scale, double face_lower_bound) {
  const double r1 = pair.r1;
  // Start on the rim (the optimum is on the rim), at rimStartDirection.
  // `radial` is s's direction while s is on the rim (s == r1 * radial), carried
  // from step to step so that rim iterations need no normalisation.
  Vec2 radial = rimStartDirection(pair);
  int steps = 0;
  if (auto answer = rimNewton(pair, scale, face_lower_bound, &radial, &steps)) return *answer;
  const int first_iteration = steps + 1;
  Vec2 s = r1 * radial;
  bool s_on_rim = true;
  PointToDisk2 at = evaluate(pair, s);
  const double gap_tolerance = kGapTolerance * scale;
  const double certify_below = kCertifyStep * scale;
  const double tiny_psi = 0.5 * gap_tolerance * gap_tolerance;  // distance within tolerance of 0
  Solution current{Vec3::Zero(), Vec3::Zero(), 0.0, DiskPairFeature::rim_rim};
  // `lower`: the certificate at the current iterate, when already evaluated.
  auto finish = [&](int iteration, std::optional<double> lower = std::nullopt) {
    current.p = Vec3(s.x(), s.y(), 0.0);
    current.q = at.q;
    current.distance = (current.q - current.p).norm();
    current.iterations = iteration;
    current.lower_bound =
        lower ? *lower : certificate(pair, current.p, current.q, face_lower_bound);
    return current;
  };
  for (int iteration = first_iteration; iteration <= kMaxNewtonIterations; ++iteration) {
    bool near_rim = s_on_rim;
    if (!s_on_rim) {  // after a model step: |s| > 0, iterates stay near the rim or inside it
      const double radius = s.norm();
      radial = s / radius;
      near_rim = radius >= r1 * (1.0 - kOnRimTolerance);
    }
    const Vec2 tangent(-radial.y(), radial.x());
    // Multiplier of |s| <= r1: lambda = outward / r1 >= 0 iff -gradient points
    // out of the disk; slightly negative within kInwardGradientTolerance * |g|
    // (compared squared, |g|^2 = sigma^2 + outward^2: no square root).
    const AlongRim along = near_rim ? alongRim(pair, at, radial) : AlongRim{};
    const double outward = along.outward;
    const double tolerance_squared = kInwardGradientTolerance * kInwardGradientTolerance;
    const bool on_rim =
        near_rim && (outward >= 0.0 || outward * outward <= tolerance_squared *
                                                                (along.sigma * along.sigma +
                                                                 outward * outward));
    double dtheta = 0.0;
    double predicted_decrease = 0.0;  // of psi, by the rim Newton step
    Vec2 rotation(1.0, 0.0);          // (cos, sin) of the first rim step tried
    if (on_rim) {
      // Newton in the rim angle theta: psi' = r1 sigma, psi'' = r1 kappa with
      // sigma = g.t and kappa = r1 t'Ht + lambda r1 (both lengths), so
      // dtheta = -sigma / kappa.
      const double sigma = along.sigma;
      const double kappa = r1 * along.curvature + std::max(outward, 0.0);
      // The Cayley rotation of h = dtheta / 2 = -sigma / (2 kappa), written over
      // the common denominator 4 kappa^2 + sigma^2: its division is independent
      // of dtheta's, so the two run side by side (squares of lengths stay in
      // double's range over the whole length range).
      const double four_kappa_squared = 4.0 * kappa * kappa;
      const double denominator = four_kappa_squared + sigma * sigma;
      if (kappa > 0.0 && std::abs(sigma) <= kMaxRimStep * kappa &&
          denominator >= std::numeric_limits<double>::min()) {
        dtheta = -sigma / kappa;
        const double inverse = 1.0 / denominator;
        rotation = Vec2((four_kappa_squared - sigma * sigma) * inverse,
                        -4.0 * sigma * kappa * inverse);
      } else {  // step clamped to kMaxRimStep, or no positive curvature
        dtheta = kappa > 0.0 ? -sigma / kappa : -std::copysign(kMaxRimStep, sigma);
        dtheta = std::clamp(dtheta, -kMaxRimStep, kMaxRimStep);
        rotation = cayleyRotation(dtheta);
      }
      predicted_decrease = 0.5 * r1 * std::abs(sigma * dtheta);
    }
    // Certify once the iteration has (nearly) converged: Newton converges
    // quadratically, so the gap closes within a step or two of here. Not while
    // the step is predicted to shorten the distance d by more than the
    // tolerance (d psi = d dd): the gap is at least that, so the certificate
    // would fail. (Not compared squared: that would be a fourth power of
    // lengths, outside double's range at the ends of the length range.)
    const bool converging = std::abs(dtheta) * r1 <= certify_below &&
                            predicted_decrease <= std::sqrt(2.0 * at.psi) * gap_tolerance;
    if (!on_rim || converging || at.psi <= tiny_psi) {
      const Vec3 x(s.x(), s.y(), 0.0);
      const Vec3 q = at.q;
      const double lower = separationCertificate(pair, x, q, face_lower_bound);
      if ((q - x).norm() - lower <= gap_tolerance) return finish(iteration, lower);
      // Converged to rounding: the step no longer moves the point, or the
      // decrease it predicts is below the rounding of psi itself (d times the
      // eps * scale rounding of the points), so no step can be seen to
      // decrease psi. The certificate's own rounding along q - x grows like
      // scale * (eps * scale / d)^2 for small distances d, so it may not
      // reach kGapTolerance; the full certificate (with t1 x t2) is reported.
      const bool step_at_rounding = std::abs(dtheta) * r1 <= kStepAtRounding * scale;
      const bool decrease_at_rounding =
          predicted_decrease <= kPsiRounding * kEps * scale * std::sqrt(2.0 * at.psi);
      if (on_rim && (step_at_rounding || decrease_at_rounding)) return finish(iteration);
    }
    PointToDisk2 next;
    Vec2 s_next;
    Vec2 radial_next;
    bool moved = false;
    if (on_rim) {
      // Rotate by the Cayley rotation of dtheta (cayleyRotation); halve the
      // step while psi does not decrease.
      for (int halving = 0; halving < kMaxRimHalvings && !moved; ++halving, dtheta *= 0.5) {
        if (halving > 0) rotation = cayleyRotation(dtheta);
        radial_next = rotation.x() * radial + rotation.y() * tangent;
        s_next = r1 * radial_next;
        next = evaluate(pair, s_next);
        moved = next.psi < at.psi;
      }
      if (moved) radial = radial_next;
      s_on_rim = moved;
    }
    if (!moved) {
      const Vec2 step = stepOnDisk(at.hessian(pair), at.gradient, s, r1);
      const double slope = at.gradient.dot(step);
      if (!(slope < 0.0)) break;  // stationary to rounding
      s_next = s + exactLineSearch(pair, s, step, slope, &next);
      moved = next.psi < at.psi;
      s_on_rim = false;
    }
    if (!moved) break;  // no representable decrease: rounding floor
    const double decrease = at.psi - next.psi;
    s = s_next;
    at = next;
    // Stagnation: psi no longer decreases beyond rounding (degenerate optima are
    // flat along the rim); the certificate says how well the pair is proven.
    if (decrease <= kStagnation * scale * scale) return finish(iteration);
  }
  return finish(kMaxNewtonIterations);  // the certificate says how well it is proven
}

/// Disk 1's rim point at angle theta (frame 1, in-plane coordinates).
Vec2 rimPoint(const PairInFrame1& pair, double theta) {
  return Vec2(pair.r1 * std::cos(theta), pair.r1 * std::sin(theta));
}

/// Golden-section search for the minimum of psi along disk 1's rim inside the
/// bracket [lo, hi] (radians), on psi's values: near the optimum of nearly
/// parallel disks psi's gradient is below its rounding while its values are
/// still resolved, so a value-based search is the robust choice. Returns the
/// pair found and its certificate.
Solution goldenSectionOnRim(const PairInFrame1& pair, double lo, double hi,
                            double face_lower_bound) {
  constexpr double kInvPhi = 0.6180339887498949;
  double a = hi - kInvPhi * (hi - lo), b = lo + kInvPhi * (hi - lo);
  PointToDisk2 at_a = evaluate(pair, rimPoint(pair, a)), at_b = evaluate(pair, rimPoint(pair, b));
  for (int iteration = 0;
       iteration < kMaxRimSearchIterations && hi - lo > kLineSearchResolution * kTwoPi;
       ++iteration) {
    if (at_a.psi <= at_b.psi) {
      hi = b, b = a, at_b = at_a;
      a = hi - kInvPhi * (hi - lo);
      at_a = evaluate(pair, rimPoint(pair, a));
    } else {
      lo = a, a = b, at_a = at_b;
      b = lo + kInvPhi * (hi - lo);
      at_b = evaluate(pair, rimPoint(pair, b));
    }
  }
  const bool a_wins = at_a.psi <= at_b.psi;
  const Vec2 s = rimPoint(pair, a_wins ? a : b);
  const PointToDisk2& at = a_wins ? at_a : at_b;
  const Vec3 x(s.x(), s.y(), 0.0);
  const Vec3 q = at.q;
  return {x, q, (q - x).norm(), DiskPairFeature::rim_rim, 0,
          certificate(pair, x, q, face_lower_bound)};
}

/// The better of two rim-rim answers: the nearer pair, and the larger of the
/// two certificates (both are lower bounds of the same distance).
Solution nearer(const Solution& kept, const Solution& other) {
  Solution best = other.distance < kept.distance ? other : kept;
  best.iterations = kept.iterations;
  best.lower_bound = std::max(kept.lower_bound, other.lower_bound);
  return best;
}

/// Where disk 1's rim crosses the projection of disk 2's rim onto plane 1: the
/// corners of the lens in which the two projections overlap, as directions
/// from c1 (unit vectors in plane 1). Newton crawls when the optimum sits at
/// such a corner (nearly coplanar rims crossing in projection,
/// docs/exact_distance.md, section 4). These are the crossings of rim 1 with
/// the circle of radius r2 about c's projection (exact for parallel planes,
/// off by O(s^2 r2) otherwise). Returns how many were written (0 or 2).
int lensCorners(const PairInFrame1& pair, std::array<Vec2, 2>* corners) {
  const double D = std::sqrt(pair.c.x() * pair.c.x() + pair.c.y() * pair.c.y());
  if (!(D > 0.0)) return 0;
  // Law of cosines, written without the cancellation of r1^2 + D^2 - r2^2.
  const double cos_half_angle =
      (pair.r1 * pair.r1 + (D - pair.r2) * (D + pair.r2)) / (2.0 * pair.r1 * D);
  if (!(std::abs(cos_half_angle) <= 1.0)) return 0;
  const double sin_half_angle = std::sqrt((1.0 - cos_half_angle) * (1.0 + cos_half_angle));
  const Vec2 towards_c(pair.c.x() / D, pair.c.y() / D);
  const Vec2 across(-towards_c.y(), towards_c.x());
  (*corners)[0] = cos_half_angle * towards_c + sin_half_angle * across;
  (*corners)[1] = cos_half_angle * towards_c - sin_half_angle * across;
  return 2;
}

/// A rim-rim candidate and whether its points, not only its distance, are
/// proven: the certificate (with its rim directions) proves the distance; along the
/// points' own separation q - x it must close as well, up to what the rounding
/// of that direction (kSeparationRounding eps scale / d) costs at g's kinks,
/// where g is Lipschitz with constant r1 + r2. Without the second test a flat
/// optimum could be reported with the right distance and points off the
/// optimal pair (docs/fuzzing.md, regression input 8).
struct CornerAnswer {
  Solution solution;
  bool proven;
};

/// The candidate at rim 1's point in direction `radial`, `at` its evaluation,
/// certified (certificate(), with the separation's certificate computed once).
CornerAnswer certifiedCorner(const PairInFrame1& pair, const Vec2& radial, const PointToDisk2& at,
                             double scale, double face_lower_bound) {
  const Vec3 x(pair.r1 * radial.x(), pair.r1 * radial.y(), 0.0);
  const Vec3& q = at.q;
  const double distance = (q - x).norm();
  const double tolerance = kGapTolerance * scale;
  const double along_separation = separationCertificate(pair, x, q, face_lower_bound);
  const double lower = withRimDirections(pair, x, q, distance, along_separation, scale);
  const bool proven = distance - lower <= tolerance &&
                      distance - along_separation <=
                          tolerance + separationRounding(pair, scale, distance);
  return {Solution{x, q, distance, DiskPairFeature::rim_rim, 0, lower}, proven};
}

/// A rim-rim candidate at a lens corner: Newton along rim 1 from the rim point
/// in direction `radial` on phi, half the squared distance to disk 2's rim
/// circle, which is smooth across the corner (where psi's curvature jumps).
/// Always a feasible pair (a point of each rim). Once a step would lower phi
/// by less than the gap tolerance allows (rimStepConverging), the
/// point is certified without it and returned if proven; else the steps go on
/// to rounding, and the last point is certified.
CornerAnswer rimRimFromCorner(const PairInFrame1& pair, Vec2 radial, PointToDisk2 at,
                              double scale, double face_lower_bound) {
  bool tried_unmoved = false;  // certified at the current point already
  for (int iteration = 0; iteration < kMaxCornerIterations; ++iteration) {
    const Vec2 tangent(-radial.y(), radial.x());
    // As in rimRim: phi' = r1 sigma, phi'' = r1 kappa, here with the rim's
    // curvature term unclamped (phi is minimised along the circle, not the disk).
    const AlongRim along = alongRim(pair, at, radial);
    const double sigma = along.sigma;
    const double kappa = pair.r1 * along.curvature + along.outward;
    if (!(kappa > 0.0)) break;
    const double dtheta = std::clamp(-sigma / kappa, -kMaxRimStep, kMaxRimStep);
    if (!tried_unmoved &&
        rimStepConverging(pair.r1, std::abs(dtheta), kappa, at.psi, scale)) {
      const CornerAnswer here = certifiedCorner(pair, radial, at, scale, face_lower_bound);
      if (here.proven) return here;
      tried_unmoved = true;
    }
    const Vec2 rotation = cayleyRotation(dtheta);
    const Vec2 radial_next = rotation.x() * radial + rotation.y() * tangent;
    const PointToDisk2 next = evaluate<DistanceTo::rim2>(pair, pair.r1 * radial_next);
    if (!(next.psi < at.psi)) break;  // converged to rounding
    radial = radial_next, at = next, tried_unmoved = false;
    if (std::abs(dtheta) * pair.r1 <= kStepAtRounding * scale) break;
  }
  return certifiedCorner(pair, radial, at, scale, face_lower_bound);
}

/// The rim-rim candidates at the lens corners, for rims that cross in
/// projection (nullopt otherwise; the caller tries them for planes within
/// kTiltedStart, sine, of parallel): the first whose points are proven
/// (`proven`), else the nearer of the two.
std::optional<CornerAnswer> rimRimAtLensCorner(const PairInFrame1& pair, double scale,
                                               double face_lower_bound) {
  std::array<Vec2, 2> corners;
  const int count = lensCorners(pair, &corners);
  // The nearer corner first: the optimum is usually there, and a proven
  // corner ends the search, with the other not evaluated.
  // At a corner rim 1's point lies over rim 2 to O(s^2 r2), so its distance
  // to rim 2 is about its height over plane 2, h0 + r1 m2.radial.
  const auto height = [&](const Vec2& radial) {
    return std::abs(pair.c1_in_frame2.z() +
                    pair.r1 * (pair.R(0, 2) * radial.x() + pair.R(1, 2) * radial.y()));
  };
  if (count == 2 && height(corners[1]) < height(corners[0])) std::swap(corners[0], corners[1]);
  std::optional<CornerAnswer> best;
  for (int k = 0; k < count; ++k) {
    const PointToDisk2 at = evaluate<DistanceTo::rim2>(pair, pair.r1 * corners[k]);
    const CornerAnswer found = rimRimFromCorner(pair, corners[k], at, scale, face_lower_bound);
    if (found.proven) return found;
    best = CornerAnswer{best ? nearer(best->solution, found.solution) : found.solution, false};
  }
  return best;
}

/// First fallback for rim-rim pairs Newton leaves uncertified: the local
/// minimum of psi along disk 1's rim next to `start` (Newton's answer, frame 1),
/// bracketed by steps growing from kFirstBracketStep in the direction psi
/// decreases, then refined by goldenSectionOnRim.
Solution localRimSearch(const PairInFrame1& pair, const Vec3& start, double face_lower_bound) {
  constexpr double kHalfTurn = kTwoPi / 2;
  const double theta0 = std::atan2(start.y(), start.x());
  const double psi0 = evaluate(pair, rimPoint(pair, theta0)).psi;
  // Downhill side: the first step that lowers psi (none: theta0 is a minimum
  // to the resolution of the first step, bracketed by +-that step).
  double direction = 0.0;
  double psi_next = psi0;
  for (const double side : {1.0, -1.0}) {
    psi_next = evaluate(pair, rimPoint(pair, theta0 + side * kFirstBracketStep)).psi;
    if (psi_next < psi0) {
      direction = side;
      break;
    }
  }
  if (direction == 0.0) {
    return goldenSectionOnRim(pair, theta0 - kFirstBracketStep, theta0 + kFirstBracketStep,
                              face_lower_bound);
  }
  // Walk downhill with growing steps until psi rises: the last three angles
  // bracket a local minimum.
  double behind = theta0, middle = theta0 + direction * kFirstBracketStep;
  double psi_middle = psi_next;
  double step = kFirstBracketStep;
  for (;;) {
    step = std::min(step * kBracketGrowth, kHalfTurn);
    const double ahead = middle + direction * step;
    const double psi_ahead = evaluate(pair, rimPoint(pair, ahead)).psi;
    if (psi_ahead >= psi_middle || step >= kHalfTurn) {
      return goldenSectionOnRim(pair, std::min(behind, ahead), std::max(behind, ahead),
                                face_lower_bound);
    }
    behind = middle, middle = ahead, psi_middle = psi_ahead;
  }
}

/// Last fallback for the rare rim-rim pairs still uncertified (nearly parallel
/// disks whose psi is flat to rounding over a long valley, or whose rim has
/// several local minima): since p* lies on disk 1's rim, minimise psi along the
/// rim globally. Sample kRimSamples angles, then refine the lowest sampled local
/// minima by golden-section search inside the bracket of their neighbouring
/// samples (the lowest refined one is kept).
Solution rimSearch(const PairInFrame1& pair, double face_lower_bound) {
  constexpr double kStep = kTwoPi / kRimSamples;
  std::array<double, kRimSamples> psi{};
  for (int k = 0; k < kRimSamples; ++k) psi[k] = evaluate(pair, rimPoint(pair, kStep * k)).psi;
  // Local minima of the samples, lowest first.
  std::array<int, kRimSamples> minima{};
  int count = 0;
  for (int k = 0; k < kRimSamples; ++k) {
    const double before = psi[(k + kRimSamples - 1) % kRimSamples];
    const double after = psi[(k + 1) % kRimSamples];
    if (psi[k] <= before && psi[k] <= after) minima[count++] = k;
  }
  std::sort(minima.begin(), minima.begin() + count, [&](int a, int b) { return psi[a] < psi[b]; });
  Solution best{Vec3::Zero(), Vec3::Zero(), std::numeric_limits<double>::infinity(),
                DiskPairFeature::rim_rim};
  for (int m = 0; m < std::min(count, kRimCandidates); ++m) {
    const double centre = kStep * minima[m];
    const Solution refined =
        goldenSectionOnRim(pair, centre - kStep, centre + kStep, face_lower_bound);
    if (refined.distance < best.distance) best = refined;
  }
  return best;
}

/// A solution of pair.swapped() (frame 2, disk 2 first) mapped back to frame 1.
Solution fromDisk2(const PairInFrame1& pair, const Solution& swapped) {
  Solution out = swapped;
  out.p = pair.c + pair.R * swapped.q;
  out.q = pair.c + pair.R * swapped.p;
  return out;
}

/// The rim-rim iteration and its local fallback on disk 2's rim (frame 2).
Solution rimRimFromDisk2(const PairInFrame1& pair, double scale, double face_lower_bound) {
  const PairInFrame1 swapped = pair.swapped();
  Solution answer = rimRim(swapped, scale, face_lower_bound);
  if (answer.distance - answer.lower_bound > kGapTolerance * scale) {
    answer = nearer(answer, localRimSearch(swapped, answer.p, face_lower_bound));
  }
  return answer;
}

/// Newton, then while the certified gap is open: the local minimum along rim 1
/// next to Newton's answer, the same two steps on rim 2 (both points of a
/// rim-rim optimum are on a rim, and where one side crawls the other may not),
/// and the global search along rim 1. Every answer is a feasible pair and
/// every certificate a lower bound: the nearest pair and the largest bound are
/// kept (docs/exact_distance.md, section 4). `candidate`: a pair found before
/// (an unproven lens corner), or nullptr.
Solution rimRimWithFallbacks(const PairInFrame1& pair, double scale, double face_lower_bound,
                             const Solution* candidate) {
  Solution answer = rimRim(pair, scale, face_lower_bound);
  if (candidate) answer = nearer(answer, *candidate);
  const auto gap_above = [&](double tolerance) {
    return answer.distance - answer.lower_bound > tolerance * scale;
  };
  if (gap_above(kGapTolerance)) {
    answer = nearer(answer, localRimSearch(pair, answer.p, face_lower_bound));
  }
  if (gap_above(kFallbackGap)) {
    answer = nearer(answer, fromDisk2(pair, rimRimFromDisk2(pair, scale, face_lower_bound)));
  }
  if (gap_above(kFallbackGap)) answer = nearer(answer, rimSearch(pair, face_lower_bound));
  return answer;
}

Solution solveInFrame1(const PairInFrame1& pair) {
  const double scale = pair.scale();  // finite and normal: the input was validated
  if (const auto common = internal::commonPoint(pair)) {
    return {*common, *common, 0.0, DiskPairFeature::intersecting};
  }
  const double face_lower_bound = faceLowerBound(pair);
  if (auto face1 = faceOfDisk1(pair, scale)) {
    face1->lower_bound = face_lower_bound;
    return *face1;
  }
  // Disk 2's face case needs disk 1 wholly on one side of plane 2 (the first
  // test of faceOfDisk1 seen from disk 2) and the foot of disk 1's point
  // nearest plane 2 inside disk 2, both checked before building that view.
  if (pair.disk1ClearanceOfPlane2() > 0.0 && faceOfDisk2MayHold(pair, scale)) {
    if (auto face2 = faceOfDisk1(pair.swapped(), scale)) {
      Solution answer = fromDisk2(pair, *face2);
      answer.feature = DiskPairFeature::rim1_face2;
      answer.lower_bound = face_lower_bound;
      return answer;
    }
  }
  // The lens corners, for nearly parallel planes whose rims cross in projection.
  if (pair.s < kTiltedStart) {
    if (const auto corner = rimRimAtLensCorner(pair, scale, face_lower_bound)) {
      if (corner->proven) return corner->solution;
      return rimRimWithFallbacks(pair, scale, face_lower_bound, &corner->solution);
    }
  }
  return rimRimWithFallbacks(pair, scale, face_lower_bound, nullptr);
}

}  // namespace

namespace internal {
DiskPairAnswer solveDiskPairInFrame1(const PairInFrame1& pair) {
  const Solution solution = solveInFrame1(pair);
  return {solution.p, solution.q, solution.distance,
          std::min(solution.lower_bound, solution.distance)};
}
}  // namespace internal

template <typename S>
DiskDistanceResult<S> exactDiskDistance(S r1, const fcl::Transform3<S>& X_W1, S r2,
                                        const fcl::Transform3<S>& X_W2) {
  const internal::DiskPairCheck check = internal::checkDiskPair(r1, X_W1, r2, X_W2);
  if (!check.valid) return internal::nanDistanceResult<S>();
  const internal::Mat3 R_W1 = internal::diskRotationInDouble(X_W1, check.orthonormal1);
  const PairInFrame1 pair = PairInFrame1::fromWorld(r1, X_W1, R_W1, r2, X_W2, check);
  const Solution solution = solveInFrame1(pair);

  const Vec3 c1 = X_W1.translation().template cast<double>();
  DiskDistanceResult<S> result;
  result.distance = S(solution.distance);
  result.p_W1 = (c1 + R_W1 * solution.p).template cast<S>();
  result.p_W2 = (c1 + R_W1 * solution.q).template cast<S>();
  result.lower_bound = S(std::min(solution.lower_bound, solution.distance));
  result.feature = solution.feature;
  result.iterations = solution.iterations;
  return result;
}

template DiskDistanceResult<float> exactDiskDistance(float, const fcl::Transform3<float>&, float,
                                                     const fcl::Transform3<float>&);
template DiskDistanceResult<double> exactDiskDistance(double, const fcl::Transform3<double>&,
                                                      double, const fcl::Transform3<double>&);

}  // namespace fcl_disk
