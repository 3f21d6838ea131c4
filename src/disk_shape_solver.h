// Internal: the generic certified solver for a disk against a convex set X, given
// X's projection and support in X's own frame. Derivation and notation:
// docs/disk_shape_distance.md (psi, g, H, the certificate g(w), inflation rho).
//
// Frame S: X's own frame; the disk has centre c, in-plane axes u, v and normal n
// there (DiskInShape), and is {x(s) = c + s_x u + s_y v : |s| <= r}, s in R^2.
// Everything is in double. Working in X's frame keeps X's projection and
// support free of rotations (a box clamps, a support picks a vertex).
//
// A Target (the convex set X, in its frame) provides
//   Projection project(const Vec3& y) const;  // q = proj_X(y), and psi's Hessian
//   Vec3 support(const Vec3& w) const;        // a point of X maximising w.y
// and may provide, where it is cheaper than the support point (no division):
//   double leastAlong(const Vec3& w) const;   // min over X of w.y = -h_X(-w)
// and the solver works on X inflated by `rho` >= 0 (a sphere is a point
// inflated, a capsule a segment): dist(x, X + B_rho) = max(dist(x, X) - rho, 0).
// Where the iteration leaves the certificate open, the solver tries candidates
// at the kinks of psi that make it crawl, from the Target's flat features, if
// it provides them (docs/disk_shape_distance.md, section 3, "Flat features"):
//   std::array<FlatEnd, N> flatEnds() const;  // circular ends (cylinder, cone)
//   template <typename Visit> void forEachFace(Visit&& visit) const;
//     // polygonal faces (box, triangle, convex):
//     // visit(unit outward normal, vertex count, vertex(i) -> Vec3)
// A Target whose projection and support describe sets that may lie apart (a
// Convex whose faces are planar only to rounding) says by how much:
//   double supportMismatch() const;  // a length >= 0; 0 when not provided
// The certificate compares the two sets, so it closes at that much more gap,
// and the answer is exact to it (docs/disk_shape_distance.md, section 4).
// Such a Target also bounds how far a point it projects onto itself (a common
// point) lies from the set of its support, which the penetration depth reads:
//   double supportSetDistanceAbove(const Vec3& x) const;  // >= dist(x, that set)
// A Target whose frame origin is not its middle (a triangle, a Convex) says
// where that is, for the intersection test's early exit (apartTowardsCentre):
//   Vec3 centre() const;  // a point of X; the origin when not provided
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>

#include "fcl_disk/disk_shape_distance.h"
#include "pair_in_frame1.h"

namespace fcl_disk {
namespace internal {

using Mat2 = Eigen::Matrix2d;

/// The Hessian of psi_3(x) = dist(x, X)^2 / 2, I - D proj_X(x) (symmetric,
/// 0 <= H <= I; 0 inside X), kept factored in X's frame as
/// H = diag(diagonal) + sum_k b_k v_k v_k^T with at most two rank-one terms:
/// for FCL's shapes the diagonal holds the shape's axes (a box's clamped axes, a
/// capsule's I - z z^T) and the terms a feature's normal or tangents, so
/// nothing 3x3 is ever multiplied out. The solver needs only H's 2x2 block over
/// the disk's plane, w^T H w and H w.
struct FactoredHessian {
  static constexpr int kMaxTerms = 2;
  Vec3 diagonal{Vec3::Zero()};
  int count{0};
  // Only the first `count` entries are meaningful (left uninitialised: a
  // projection is evaluated several times per query).
  std::array<double, kMaxTerms> weight;
  std::array<Vec3, kMaxTerms> direction;

  static FactoredHessian diagonalOf(const Vec3& d) {
    FactoredHessian H;
    H.diagonal = d;
    return H;
  }
  static FactoredHessian identity() { return diagonalOf(Vec3::Ones()); }
  FactoredHessian& add(double b, const Vec3& v) {
    weight[count] = b;
    direction[count] = v;
    ++count;
    return *this;
  }
  /// w^T H w.
  double quadratic(const Vec3& w) const {
    double value = diagonal.dot(w.cwiseProduct(w));
    for (int k = 0; k < count; ++k) {
      const double along = direction[k].dot(w);
      value += weight[k] * along * along;
    }
    return value;
  }
  Vec3 times(const Vec3& w) const {
    Vec3 product = diagonal.cwiseProduct(w);
    for (int k = 0; k < count; ++k) product += (weight[k] * direction[k].dot(w)) * direction[k];
    return product;
  }
};

/// proj_X(x) and psi's Hessian there. Where proj_X is not differentiable
/// (region boundaries) either side's Hessian will do: the solver's line search
/// and certificate do not rely on it, only its speed does.
struct Projection {
  Vec3 q;
  FactoredHessian hessian;
};

/// The disk in X's frame: centre c, orthonormal in-plane axes u, v, normal n,
/// radius r.
struct DiskInShape {
  Vec3 c, u, v, n;
  double r;

  Vec3 point(const Vec2& s) const { return c + s.x() * u + s.y() * v; }
  /// (u.w, v.w): w's in-plane coordinates.
  Vec2 inPlane(const Vec3& w) const { return Vec2(u.dot(w), v.dot(w)); }
  /// h_K(w) = max over the disk of w.k = w.c + r |P w|.
  double support(const Vec3& w) const { return w.dot(c) + r * inPlane(w).norm(); }
  /// The disk point least along w: c - r P w / |P w| (P w = (u.w) u + (v.w) v),
  /// the centre when w is normal to the disk (every point ties).
  Vec3 lowestAlong(const Vec3& w) const { return lowestAlongPlanar(inPlane(w)); }
  /// lowestAlong(side * e_j), reading u.e_j, v.e_j off the axes (the faces of
  /// an axis-aligned box).
  Vec3 lowestAlongAxis(int j, double side) const {
    return lowestAlongPlanar(Vec2(side * u[j], side * v[j]));
  }
  /// The disk point nearest y: y's foot on the disk's plane, clamped to the rim.
  Vec2 nearest(const Vec3& y) const { return clampedToRim(inPlane(y - c)); }
  /// The in-plane point s, clamped to the rim.
  Vec2 clampedToRim(const Vec2& s) const {
    const double length_squared = s.squaredNorm();
    if (!(length_squared > r * r)) return s;
    const double to_rim = lengthOverNorm(r, length_squared);
    return Vec2(s.x() * to_rim, s.y() * to_rim);
  }
  /// The disk point least along a direction whose in-plane coordinates are
  /// `planar`: c - r planar / |planar|, or c for planar = 0.
  Vec3 lowestAlongPlanar(const Vec2& planar) const {
    const double length_squared = planar.squaredNorm();
    if (!(length_squared > 0.0)) return c;
    const double to_rim = lengthOverNorm(r, length_squared);
    return point(Vec2(-to_rim * planar.x(), -to_rim * planar.y()));
  }
  /// length / |s| from |s|^2 > 0, as sqrt(|s|^2) * (length / |s|^2) where that
  /// is finite and |s|^2 normal: the square root and the division run side by
  /// side, so the chains of the closed forms that clamp or turn a point to the
  /// rim wait for one of them, not for both in turn. Else length / |s|.
  static double lengthOverNorm(double length, double norm_squared) {
    const double side_by_side = std::sqrt(norm_squared) * (length / norm_squared);
    if (std::isnormal(norm_squared) && std::isfinite(side_by_side)) return side_by_side;
    return length / std::sqrt(norm_squared);
  }
  /// Whether u, v are orthonormal to within kOrthonormalInDouble (|u.u - 1|,
  /// |v.v - 1|, |u.v|): so in double; poses in float (~1e-7) are not.
  bool hasOrthonormalAxes() const {
    return std::abs(u.squaredNorm() - 1.0) <= kOrthonormalInDouble &&
           std::abs(v.squaredNorm() - 1.0) <= kOrthonormalInDouble &&
           std::abs(u.dot(v)) <= kOrthonormalInDouble;
  }
  /// The disk with centre c, radius r, plane span(u, v) and normal n / |n|, in
  /// orthonormal axes. Axes within kTaylorInverseSqrtRange of orthonormal (a
  /// float pose orthonormal to float's rounding gives ~1e-7) are made
  /// orthonormal symmetrically (Loewdin):
  /// [u' v'] = [u v] G^(-1/2), G = I + E the Gram matrix of u, v, by its
  /// Taylor polynomial I - E/2 + 3E^2/8 (error 5|E|^3/16, under double's
  /// rounding), and n' = u' x v'. The plane, hence the disk, is the same; the
  /// three inner products run side by side, so the axes wait on a short chain
  /// of arithmetic and no square root. Others by Gram-Schmidt (u made
  /// orthogonal to the normal, v = n x u). Always inlined: every float query
  /// of a closed-form pair runs it, and a call passes both disks through memory
  /// (float disk-box and disk-capsule queries take 47 instructions fewer of
  /// ~1,240 and ~1,050: bench/disk_shape_calls SHAPE float under callgrind).
  [[gnu::always_inline]] DiskInShape withOrthonormalAxes() const {
    const double e_u = u.squaredNorm() - 1.0, e_v = v.squaredNorm() - 1.0, e_uv = u.dot(v);
    if (std::max({std::abs(e_u), std::abs(e_v), std::abs(e_uv)}) <= kTaylorInverseSqrtRange) {
      const double m_uu = 1.0 - 0.5 * e_u + 0.375 * (e_u * e_u + e_uv * e_uv);
      const double m_vv = 1.0 - 0.5 * e_v + 0.375 * (e_v * e_v + e_uv * e_uv);
      const double m_uv = e_uv * (0.375 * (e_u + e_v) - 0.5);
      const Vec3 unit_u = m_uu * u + m_uv * v, unit_v = m_uv * u + m_vv * v;
      return DiskInShape{c, unit_u, unit_v, unit_u.cross(unit_v), r};
    }
    const Vec3 unit_n = n * inverseSqrtNearOne(n.squaredNorm());
    const Vec3 in_plane = u - unit_n.dot(u) * unit_n;
    const Vec3 unit_u = in_plane * inverseSqrtNearOne(in_plane.squaredNorm());
    return DiskInShape{c, unit_u, unit_n.cross(unit_u), unit_n, r};
  }
};

/// The disk of radius r and pose X_WD in the frame S of a shape with pose X_WS
/// (double; the offset c_D - c_S is formed first, so a common translation costs
/// only its rounding).
template <typename S>
[[gnu::always_inline]] inline DiskInShape diskInShape(S radius, const fcl::Transform3<S>& X_WD,
                                                      const fcl::Transform3<S>& X_WS) {
  if constexpr (std::is_same_v<S, double>) {
    // R_WS^T in one TransposedProduct for the centre and both axes, read
    // straight from the poses' column-major 4x4 matrices.
    using Matrix = std::decay_t<decltype(X_WD.matrix())>;
    static_assert(Matrix::RowsAtCompileTime == 4 && !Matrix::IsRowMajor,
                  "diskInShape reads column-major 4x4 matrices");
    const double* disk = X_WD.matrix().data();
    const double* shape = X_WS.matrix().data();
    const TransposedProduct<4> to_shape(shape);
    const Vec3 u = to_shape(disk[0], disk[1], disk[2]), v = to_shape(disk[4], disk[5], disk[6]);
    return DiskInShape{
        to_shape(disk[12] - shape[12], disk[13] - shape[13], disk[14] - shape[14]), u, v,
        u.cross(v), radius};
  }
  const Mat3 R_WS = X_WS.linear().template cast<double>();
  const Mat3 R_WD = X_WD.linear().template cast<double>();
  const Vec3 offset =
      X_WD.translation().template cast<double>() - X_WS.translation().template cast<double>();
  const Vec3 u = R_WS.transpose() * R_WD.col(0), v = R_WS.transpose() * R_WD.col(1);
  return DiskInShape{R_WS.transpose() * offset, u, v, u.cross(v), double(radius)};
}

/// diskInShape with orthonormal axes (DiskInShape::withOrthonormalAxes where
/// they are not): for a query that solves many leaves against one disk (a
/// mesh's triangles, an octree's cells), whose closed forms certify only the
/// disk of orthonormal axes (GenericDiskShapePair::solvedDiskInShape).
template <typename S>
DiskInShape orthonormalDiskInShape(S radius, const fcl::Transform3<S>& X_WD,
                                   const fcl::Transform3<S>& X_WS) {
  DiskInShape disk = diskInShape(radius, X_WD, X_WS);
  if (!disk.hasOrthonormalAxes()) disk = disk.withOrthonormalAxes();
  return disk;
}

/// A point of frame S in the world.
template <typename S>
[[gnu::always_inline]] inline Vec3 toWorldPoint(const fcl::Transform3<S>& X_WS, const Vec3& p_S) {
  return X_WS.translation().template cast<double>() + X_WS.linear().template cast<double>() * p_S;
}

/// The disk of radius r and pose X_WD in the frame with the origin of X_WS and
/// the world's axes (frame S translated, not turned), for shapes that need at
/// most their normal turned (a sphere none, a halfspace or a plane its
/// boundary's): it spares turning the disk into frame S (three products) and
/// the answer back (two). Centre c_D - c_S (formed first, as diskInShape's),
/// axes the columns of R_WD, normal u x v. Always inlined: the closed forms
/// that use it take a few hundred instructions, and a call would build the
/// struct in memory only to read it back (with the halfspace's own helpers
/// inlined too, a disk-halfspace query takes 65 instructions fewer of ~490;
/// bench/disk_shape_calls under callgrind).
template <typename S>
[[gnu::always_inline]] inline DiskInShape diskAtShapeOrigin(S radius,
                                                            const fcl::Transform3<S>& X_WD,
                                                            const fcl::Transform3<S>& X_WS) {
  const Mat3 R_WD = X_WD.linear().template cast<double>();
  const Vec3 u = R_WD.col(0), v = R_WD.col(1);
  return DiskInShape{
      X_WD.translation().template cast<double>() - X_WS.translation().template cast<double>(), u, v,
      u.cross(v), double(radius)};
}

/// A point of diskAtShapeOrigin's frame in the world.
template <typename S>
Vec3 fromShapeOrigin(const fcl::Transform3<S>& X_WS, const Vec3& p) {
  return X_WS.translation().template cast<double>() + p;
}

/// What the solver is asked: the distance, or only whether the sets meet (which
/// may stop as soon as either answer is proven).
enum class SolverGoal { distance, intersection };

struct DiskShapeSolution {
  Vec3 p{Vec3::Zero()};   ///< point of the disk, frame S.
  Vec3 q{Vec3::Zero()};   ///< point of X + B_rho, frame S.
  double distance{0};     ///< |q - p|; 0 with p == q when the sets meet.
  double lower_bound{0};  ///< the certificate, <= the true distance.
  int iterations{0};
};

/// The shortest separating translation among candidate directions (frame S).
struct Separation {
  double depth = std::numeric_limits<double>::infinity();
  Vec3 direction;
};

/// The contact of an intersecting pair in the shape's frame S: a common point
/// and the shortest separation found.
struct FrameContact {
  Vec3 pos{Vec3::Zero()};
  Separation separation;
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
/// The rounding of the gradient over the disk, relative to scale: x and q
/// carry a few ulps of scale each.
constexpr double kShapeGradientRounding = 8 * std::numeric_limits<double>::epsilon();
/// The start: this many alternating projections (disk point nearest X's point
/// nearest the disk point), from the disk's point nearest X's frame origin
/// (every primitive's centre). A second projection cost more than the share of
/// a Newton iteration it saved (docs/disk_shape_distance.md, section 3).
constexpr int kStartProjections = 1;
/// The distance goal evaluates the certificate once the step expects to
/// shorten the distance by less than this many gap tolerances: before that the
/// iterate is not optimal to the tolerance and the certificate would only cost
/// its support evaluations. The expectation is Newton's, exact only where psi
/// is smooth: the margin keeps the certificate where a kink ahead makes the
/// model overstate the gain.
constexpr double kShapeCertifyGain = 100.0;
/// The model step's predicted psi below this fraction of psi: the model
/// reaches X (its minimum is 0 up to the step's rounding).
constexpr double kShapeModelReachesX = 1e-8;
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
/// Tikhonov term of the disk-constrained model step, relative to trace(H) + 1
/// (psi's curvatures are at most 1): only pins the step along flat directions.
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
  Vec3 x;                    ///< the disk point, frame S.
  Vec3 q;                    ///< proj_X(x).
  double psi;                ///< |x - q|^2 / 2.
  Vec2 gradient;             ///< psi's gradient over the disk: (u.(x - q), v.(x - q)).
  FactoredHessian hessian3;  ///< X's psi Hessian at x, frame S.
};

template <typename Target>
ShapeIterate evaluateAt(const Target& target, const DiskInShape& disk, const Vec2& s) {
  const Vec3 x = disk.point(s);
  const Projection projection = target.project(x);
  const Vec3 residual = x - projection.q;
  return ShapeIterate{s, x, projection.q, 0.5 * residual.squaredNorm(), disk.inPlane(residual),
                      projection.hessian};
}

/// psi's Hessian over the disk: [u v]^T H3 [u v].
inline Mat2 planarHessian(const FactoredHessian& H, const DiskInShape& disk) {
  Mat2 block = Mat2::Zero();
  for (int i = 0; i < 3; ++i) {
    const Vec2 d(disk.u[i], disk.v[i]);
    block += H.diagonal[i] * d * d.transpose();
  }
  for (int k = 0; k < H.count; ++k) {
    const Vec2 d = disk.inPlane(H.direction[k]);
    block += H.weight[k] * d * d.transpose();
  }
  return block;
}

template <typename Target, typename = void>
struct HasLeastAlong : std::false_type {};
template <typename Target>
struct HasLeastAlong<Target, std::void_t<decltype(std::declval<const Target&>().leastAlong(
                                 std::declval<const Vec3&>()))>> : std::true_type {};

/// min over X of w.y = w.support(-w): the Target's leastAlong where it has one.
template <typename Target>
double leastAlong(const Target& target, const Vec3& w) {
  if constexpr (HasLeastAlong<Target>::value) {
    return target.leastAlong(w);
  } else {
    return w.dot(target.support(-w));
  }
}

/// The certificate g(w) = min_{y in X + B_rho} w.y - max_{k in disk} w.k
///                      = w.support(-w) - rho|w| - h_K(w)
/// for any w (positively homogeneous: divided by |w| here), a lower bound of
/// the distance (docs/disk_shape_distance.md, section 2).
template <typename Target>
double certificateAlong(const Target& target, const DiskInShape& disk, double rho, const Vec3& w) {
  const double length_squared = w.squaredNorm();
  if (!(length_squared > 0.0)) return 0.0;
  return (leastAlong(target, w) - disk.support(w)) / std::sqrt(length_squared) - rho;
}

template <typename Target, typename = void>
struct HasCentre : std::false_type {};
template <typename Target>
struct HasCentre<Target, std::void_t<decltype(std::declval<const Target&>().centre())>>
    : std::true_type {};

/// The Target's centre(), its frame origin if it has none (FCL's primitives
/// are built about their origin).
template <typename Target>
Vec3 centreOf(const Target& target) {
  if constexpr (HasCentre<Target>::value) {
    return target.centre();
  } else {
    return Vec3::Zero();
  }
}

/// Whether the certificate along w = centre - p, p the disk's point nearest
/// the shape's centre (the pair's separating direction, were X a ball about
/// its centre), proves the disk and X + B_rho more than `margin` apart. A
/// closed form and a few square roots: most pairs a broadphase hands to a
/// collision test are apart, and on the report's cases this direction proves
/// 96-98% of the separated ones (docs/disk_shape_distance.md, section 5).
/// w = 0 (the centre on the disk) and NaN prove nothing.
template <typename Target>
bool apartTowardsCentre(const Target& target, const DiskInShape& disk, double rho,
                        double margin) {
  const Vec3 centre = centreOf(target);
  return certificateAlong(target, disk, rho, centre - disk.point(disk.nearest(centre))) > margin;
}

/// How close to closing the separation's certificate must be before the other
/// directions are tried: they only help at the optimum, where what is left of
/// the gap is the rounding of q - x's direction (about (r + R) eps scale / d,
/// kSeparationRoundingFactor eps scale^2 / d with R <= scale), or when it is
/// already within kRefineCertificate * scale. Elsewhere the iterate is simply
/// not optimal yet and the step, not a better certificate, is needed.
constexpr double kRefineCertificate = 1e-8;
constexpr double kSeparationRoundingFactor = 16 * std::numeric_limits<double>::epsilon();

/// The best certificate at the iterate: along the separation q - x and, when
/// that leaves a gap above `gap_tolerance` that rounding may explain (or
/// always, for the iterate that is returned: `returned`), along
/// H3 (q - x), which keeps the components of q - x normal to the feature of X
/// that q lies on (a face's normal, the plane normal to an edge) and drops the
/// rest, which for small distances is rounding (q - x knows its direction only
/// to about eps * scale / d); then at the disk's normals +-n, where g has the
/// disk's kink (face optima).
template <typename Target>
double certificateAt(const Target& target, const DiskInShape& disk, double rho,
                     const ShapeIterate& at, double distance, double gap_tolerance,
                     double scale, bool returned) {
  const Vec3 separation = at.q - at.x;
  double best = certificateAlong(target, disk, rho, separation);
  const double gap = distance - best;
  if (gap <= gap_tolerance) return std::max(best, 0.0);
  const double refine_below =
      kRefineCertificate * scale + kSeparationRoundingFactor * scale * (scale / distance);
  if (!(returned || gap <= refine_below)) return std::max(best, 0.0);
  best = std::max(best, certificateAlong(target, disk, rho, at.hessian3.times(separation)));
  if (distance - best > gap_tolerance) {
    best = std::max({best, certificateAlong(target, disk, rho, disk.n),
                     certificateAlong(target, disk, rho, -disk.n)});
  }
  return std::max(best, 0.0);
}

/// Minimiser over alpha in (0, 1] of psi(s + alpha step), by regula falsi
/// (Illinois) on psi', which is monotone (psi is convex along the line): finds
/// the kinks of psi'' where the step crosses between regions of X's projection.
template <typename Target>
Vec2 shapeLineSearch(const Target& target, const DiskInShape& disk, const ShapeIterate& at,
                     const Vec2& step, double slope, ShapeIterate* at_end) {
  ShapeIterate next = evaluateAt(target, disk, at.s + step);
  double derivative_hi = next.gradient.dot(step);
  double alpha = 1.0;
  if (derivative_hi > 0.0) {
    double lo = 0.0, hi = 1.0, derivative_lo = slope;
    ShapeIterate at_lo = at;
    int last_side = 0;
    for (int k = 0; k < kShapeLineSearchSteps; ++k) {
      alpha = (lo * derivative_hi - hi * derivative_lo) / (derivative_hi - derivative_lo);
      if (!(alpha > lo && alpha < hi)) alpha = 0.5 * (lo + hi);
      next = evaluateAt(target, disk, at.s + alpha * step);
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

/// The unit eigenvector of the symmetric 2x2 H for its larger eigenvalue, in
/// closed form; the eigenvalues are mean +- spread.
inline Vec2 steepEigenvector(const Mat2& H, double* mean, double* spread) {
  *mean = 0.5 * (H(0, 0) + H(1, 1));
  const double half_difference = 0.5 * (H(0, 0) - H(1, 1));
  *spread = std::sqrt(half_difference * half_difference + H(0, 1) * H(0, 1));
  const Vec2 v = half_difference >= 0.0 ? Vec2(half_difference + *spread, H(0, 1))
                                        : Vec2(H(0, 1), *spread - half_difference);
  const double length = v.norm();
  return length > 0.0 ? Vec2(v / length) : Vec2(1.0, 0.0);
}

/// The step delta minimising the model g.delta + delta'(H + tau I)delta / 2
/// subject to |s + delta| <= r, for H symmetric positive semidefinite (2x2).
/// In H's eigenbasis (v_i, lambda_i) the model separates: the Newton step is
/// delta_i = -g_i / (lambda_i + tau); if it leaves the disk, the multiplier
/// mu > 0 of the disk makes s + delta(mu) = z(mu), z_i = -b_i / (lambda_i + tau +
/// mu) with b_i = g_i - (lambda_i + tau) s_i, land on the rim: |z(mu)| = r is
/// solved by Newton on 1/|z(mu)| - 1/r, which is concave and increasing in mu,
/// so Newton from mu = 0 increases monotonically to the root (More and
/// Sorensen's secular equation). The step itself is delta_i = -(g_i + mu s_i)
/// / (lambda_i + tau + mu): no difference of O(r) numbers for small steps.
/// tau > 0 makes the model strictly convex, so along psi's flat directions
/// the step stays near s instead of wandering.
///
/// Before that, the gradient's components along the eigenvectors that are below
/// its rounding (gradient_rounding: g is a difference of coordinates of size
/// scale) are dropped. In exact arithmetic g is orthogonal to H's null space (g
/// is an eigenvector of the 3-D Hessian with eigenvalue 1), so such a component
/// is rounding only, and 1 / tau would turn it into a long step along a flat
/// direction, away from the optimum.
inline Vec2 modelStepOnDisk(const Mat2& H, const Vec2& g_raw, const Vec2& s, double r,
                            double gradient_rounding) {
  // H's eigenpairs: v1 for the larger eigenvalue, v2 = v1 turned.
  double mean, spread;
  const Vec2 v1 = steepEigenvector(H, &mean, &spread);
  const Vec2 v2(-v1.y(), v1.x());
  const double tau = kShapeModelRegularisation * (2.0 * mean + 1.0);
  const double lambda[2] = {mean + spread + tau, std::max(mean - spread, 0.0) + tau};
  const Vec2 g_basis(v1.dot(g_raw), v2.dot(g_raw));
  const double g_i[2] = {std::abs(g_basis.x()) > gradient_rounding ? g_basis.x() : 0.0,
                         std::abs(g_basis.y()) > gradient_rounding ? g_basis.y() : 0.0};
  if (g_i[0] == 0.0 && g_i[1] == 0.0) return Vec2::Zero();
  const double s_i[2] = {v1.dot(s), v2.dot(s)};
  auto step_for = [&](double mu) {
    return -(g_i[0] + mu * s_i[0]) / (lambda[0] + mu) * v1 -
           (g_i[1] + mu * s_i[1]) / (lambda[1] + mu) * v2;
  };
  const Vec2 newton = step_for(0.0);
  // |s + delta|^2 - r^2 as 2 s.delta + |delta|^2 + (|s|^2 - r^2): free of cancellation.
  if (2.0 * s.dot(newton) + newton.squaredNorm() + (s.squaredNorm() - r * r) <= 0.0) return newton;
  const double b[2] = {g_i[0] - lambda[0] * s_i[0], g_i[1] - lambda[1] * s_i[1]};
  double mu = 0.0;
  for (int iteration = 0; iteration < kShapeSecularIterations; ++iteration) {
    const double z0 = b[0] / (lambda[0] + mu), z1 = b[1] / (lambda[1] + mu);
    const double z_squared = z0 * z0 + z1 * z1;
    const double z_length = std::sqrt(z_squared);
    // phi = 1/|z| - 1/r; phi' = (sum z_i^2 / (lambda_i + mu)) / |z|^3.
    const double slope = (z0 * z0 / (lambda[0] + mu) + z1 * z1 / (lambda[1] + mu)) /
                         (z_squared * z_length);
    const double phi = 1.0 / z_length - 1.0 / r;
    const double next = mu - phi / slope;
    if (!(next > mu)) break;  // at the root to rounding
    const bool settled = next - mu <= kShapeSecularTolerance * next;
    mu = next;
    if (settled) break;
  }
  return step_for(mu);
}

/// 2^-k and 2^k for the power of two 2^k <= x < 2^(k+1), read off x's
/// exponent bits (x a positive normal double below 2^1023, as the scene sizes
/// are; for a subnormal x, 2^1023 and 0): scaling by them is exact, and costs
/// no call into libm.
inline std::pair<double, double> powersOfTwoAbout(double x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const std::uint64_t biased = (bits >> 52) & 0x7ff;  // k + 1023
  const std::uint64_t inverse_bits = (2046 - biased) << 52, power_bits = biased << 52;
  double inverse, power;
  std::memcpy(&inverse, &inverse_bits, sizeof inverse);
  std::memcpy(&power, &power_bits, sizeof power);
  return {inverse, power};
}

/// (cos, sin) of a turn by about dtheta: the rational (Cayley) rotation by
/// 2 atan(dtheta / 2), unit to rounding and equal to the turn by dtheta to third
/// order, so rim Newton stays quadratic without trigonometry.
inline Vec2 cayleyTurn(double dtheta) {
  const double h = 0.5 * dtheta;
  const double inverse = 1.0 / (1.0 + h * h);
  return Vec2((1.0 - h * h) * inverse, 2.0 * h * inverse);
}

/// When the iteration ends with its certificate open by more than this many
/// scene sizes, a search along the rim follows (searchAlongRim). Well above the
/// certificate's own rounding, so only unconverged answers pay for it.
constexpr double kShapeFallbackGap = 1e-12;
/// The rim search brackets the minimum with steps from kShapeFirstRimStep
/// radians growing by kShapeRimStepGrowth up to half a turn, then shrinks the
/// bracket by kShapeRimSearchSteps golden-section steps (enough to reach the
/// resolution of the angle from the first step's bracket).
constexpr double kShapeFirstRimStep = 1e-9;
constexpr double kShapeRimStepGrowth = 4.0;
constexpr int kShapeRimSearchSteps = 80;

/// Golden-section search of psi(point(t)) over [lo, hi] (kShapeRimSearchSteps
/// steps); returns the better of `best` and the lowest point seen.
template <typename PointAt>
ShapeIterate goldenSection(PointAt point_at, double lo, double hi, ShapeIterate best) {
  const double ratio = 0.6180339887498949;
  double x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
  ShapeIterate f1 = point_at(x1), f2 = point_at(x2);
  for (int k = 0; k < kShapeRimSearchSteps && hi - lo > 0.0; ++k) {
    if (f1.psi <= f2.psi) {
      if (f1.psi < best.psi) best = f1;
      hi = x2, x2 = x1, f2 = f1;
      x1 = hi - ratio * (hi - lo);
      f1 = point_at(x1);
    } else {
      if (f2.psi < best.psi) best = f2;
      lo = x1, x1 = x2, f1 = f2;
      x2 = lo + ratio * (hi - lo);
      f2 = point_at(x2);
    }
  }
  if (f1.psi < best.psi) best = f1;
  if (f2.psi < best.psi) best = f2;
  return best;
}

/// The local minimum of dist(x(theta), X) along the rim next to the rim iterate
/// `at`, by bracketing and golden-section search on the distance itself. Where
/// the disk's rim and X touch or nearly touch, psi = d^2 / 2 grows like the
/// fourth power of the angle from the optimum and its gradient sinks below
/// rounding before d is within 1e-12 of the scene; d grows quadratically and
/// its values, not its slope, guide this search. Returns the better of `at`
/// and what it finds.
template <typename Target>
ShapeIterate searchAlongRim(const Target& target, const DiskInShape& disk, const ShapeIterate& at) {
  const double theta0 = std::atan2(at.s.y(), at.s.x());
  auto at_angle = [&](double theta) {
    return evaluateAt(target, disk, Vec2(disk.r * std::cos(theta), disk.r * std::sin(theta)));
  };
  ShapeIterate best = at;
  // Bracket: walk from theta0 in the direction psi decreases until it rises.
  double direction = 0.0, step = kShapeFirstRimStep;
  for (const double side : {1.0, -1.0}) {
    const ShapeIterate probe = at_angle(theta0 + side * step);
    if (probe.psi < best.psi) {
      direction = side;
      best = probe;
      break;
    }
  }
  double lo = theta0 - step, hi = theta0 + step;  // psi rises on both sides of theta0
  if (direction != 0.0) {
    double previous = theta0, current = theta0 + direction * step;
    for (step *= kShapeRimStepGrowth; step <= 3.141592653589793; step *= kShapeRimStepGrowth) {
      const ShapeIterate next = at_angle(theta0 + direction * step);
      if (!(next.psi < best.psi)) {
        lo = std::min(previous, theta0 + direction * step);
        hi = std::max(previous, theta0 + direction * step);
        break;
      }
      previous = current, current = theta0 + direction * step, best = next;
    }
  }
  return goldenSection(at_angle, lo, hi, best);
}

/// Rounds of searchInside (each along the flat then the steep direction).
constexpr int kShapeInsideSearchRounds = 3;

/// Golden-section minimum of psi along the chord of the disk through s in the
/// unit direction v; returns the better of `at` and what it finds.
template <typename Target>
ShapeIterate searchAlongChord(const Target& target, const DiskInShape& disk, const ShapeIterate& at,
                              const Vec2& v) {
  // s + t v stays in the disk for t in [-b - root, -b + root], b = s.v.
  const double b = at.s.dot(v);
  const double root = std::sqrt(std::max(0.0, b * b - (at.s.squaredNorm() - disk.r * disk.r)));
  const double lo = -b - root, hi = -b + root;
  auto at_t = [&](double t) { return evaluateAt(target, disk, disk.nearest(disk.point(at.s + t * v))); };
  return goldenSection(at_t, lo, hi, at);
}

/// The interior counterpart of searchAlongRim: where X's curved feature barely
/// meets or misses the disk's face (a cylinder's cap rim dipping through the
/// plane next to the rim), psi is flat to fourth order along the feature and
/// Newton stalls once its gradient is rounding. psi is convex, so searching by
/// values along the chords through the iterate in the directions of psi's
/// Hessian (the flat one first) moves down the valley; a few rounds suffice.
template <typename Target>
ShapeIterate searchInside(const Target& target, const DiskInShape& disk, ShapeIterate at) {
  for (int round = 0; round < kShapeInsideSearchRounds && at.psi > 0.0; ++round) {
    double mean, spread;
    const Vec2 steep = steepEigenvector(planarHessian(at.hessian3, disk), &mean, &spread);
    at = searchAlongChord(target, disk, at, Vec2(-steep.y(), steep.x()));
    at = searchAlongChord(target, disk, at, steep);
  }
  return at;
}

/// The face case, in closed form: when X + B_rho lies wholly on one side of the
/// disk's plane and its point lowest towards the plane, sigma = support(-w) -
/// rho w for w = +-n, has its foot on the plane inside the disk, that foot and
/// sigma are an optimal pair: their distance is sigma's height over the plane,
/// which is also the certificate g(w) (docs/disk_shape_distance.md, section 3).
/// A foot outside the rim by at most `slack` (rounding: the optimum is then on
/// the rim) is clamped onto it, which lengthens the pair by at most `slack`; a
/// height within `slack` of 0 (touching) makes the foot a common point, and so
/// does a foot that lies in X where X crosses the plane. The
/// iteration would find these pairs too, but where X's lowest feature is curved
/// (a cylinder's cap rim, a cone's base rim) psi grows only like the fourth
/// power of the offset from the foot, and its gradient sinks below rounding
/// before the distance is within 1e-12 of the scene.
template <typename Target>
bool faceCase(const Target& target, const DiskInShape& disk, double rho, double slack,
              DiskShapeSolution* solution) {
  for (const double side : {1.0, -1.0}) {
    const Vec3 w = side * disk.n;
    const Vec3 lowest = target.support(-w);
    const double height = w.dot(lowest - disk.c) - rho;
    if (!(height > -slack) && side > 0.0) continue;  // X reaches below: try the other side
    Vec2 foot = disk.inPlane(lowest - disk.c);
    const double foot_radius = foot.norm();
    if (!(foot_radius <= disk.r + slack)) continue;
    if (foot_radius > disk.r) foot *= disk.r / foot_radius;
    solution->p = disk.point(foot);
    solution->iterations = 0;
    if (!(height > -slack)) {
      // X crosses the plane, its lowest point under the disk: the foot is a
      // common point when it lies in X (it does when X dips just below the
      // plane there, where psi is flattest); otherwise the iteration decides.
      const Vec3 q = target.project(solution->p).q;
      if (!((solution->p - q).norm() <= rho + slack)) continue;
      solution->q = solution->p;
      solution->distance = solution->lower_bound = 0.0;
      return true;
    }
    if (height <= 0.0) {  // touching, to rounding: the foot is a common point
      solution->q = solution->p;
      solution->distance = solution->lower_bound = 0.0;
    } else {
      solution->q = lowest - rho * w;
      solution->distance = (solution->q - solution->p).norm();
      solution->lower_bound = height;
    }
    return true;
  }
  return false;
}

/// A flat circular end of X: the disk of `radius` about (0, 0, z) in the plane
/// z = const of X's frame, part of X's boundary.
struct FlatEnd {
  double z;
  double radius;
};

/// The nearest pair of `disk` (orthonormal axes) and the flat end `end`, by
/// the exact disk-disk solver in the end's frame (solveDiskPairInFrame1, the
/// end as disk 1): p on the end, q on the disk, both in X's frame; distance 0
/// with p == q where they meet.
inline DiskPairAnswer diskPairWithFlatEnd(const DiskInShape& disk, const FlatEnd& end) {
  const Vec3 end_centre(0.0, 0.0, end.z);
  Mat3 axes;
  axes << disk.u, disk.v, disk.n;
  DiskPairAnswer pair =
      solveDiskPairInFrame1(PairInFrame1::make(disk.c - end_centre, axes, end.radius, disk.r));
  pair.p += end_centre;
  pair.q += end_centre;
  return pair;
}

/// A flat feature's candidate: the disk point at s evaluated as an iterate
/// (kept when nearer than *at) and certified along the usual directions plus
/// `feature_direction`, the exact separation direction at a rim-against-feature
/// optimum (which q - x knows only to about eps scale / d).
template <typename Target>
void offerCandidate(const Target& target, const DiskInShape& disk, const Vec2& s,
                    const Vec3& feature_direction, double gap_tolerance, double scale,
                    ShapeIterate* at, double* lower) {
  const ShapeIterate candidate = evaluateAt(target, disk, s);
  const double distance = std::sqrt(2.0 * candidate.psi);
  double bound = certificateAt(target, disk, 0.0, candidate, distance, gap_tolerance, scale,
                               /*returned=*/true);
  const Vec3 w = feature_direction.dot(candidate.q - candidate.x) < 0.0 ? Vec3(-feature_direction)
                                                                       : feature_direction;
  bound = std::max(bound, certificateAlong(target, disk, 0.0, w));
  *lower = std::max(*lower, bound);
  if (candidate.psi < at->psi) *at = candidate;
}

template <typename Target, typename = void>
struct HasFlatEnds : std::false_type {};
template <typename Target>
struct HasFlatEnds<Target, std::void_t<decltype(std::declval<const Target&>().flatEnds())>>
    : std::true_type {};

/// Candidates from X's flat ends, for a disk nearly parallel to one whose rim
/// crosses the end's rim in projection: the optimum sits at a corner of the
/// lens where the two overlap, where psi's curvature jumps and the iteration
/// crawls (docs/disk_shape_distance.md, section 3). The exact disk-disk solver
/// finds that corner (docs/exact_distance.md, section 4); its disk point is
/// evaluated as an iterate (kept when nearer) and certified along the usual
/// directions plus the rim-rim one, t_disk x t_end (normal to both rims'
/// tangents: the certificate's exact direction at a rim-rim optimum, which
/// q - x knows only to about eps scale / d). An end point is a point of X, so a
/// candidate is always feasible; its certificate bounds dist(disk, X) itself.
/// Only for rho == 0 (the ends are X's, not X + B_rho's).
template <typename Target>
void tryFlatEnds(const Target& target, const DiskInShape& disk, double gap_tolerance, double scale,
                 ShapeIterate* at, double* lower) {
  for (const FlatEnd& end : target.flatEnds()) {
    const DiskPairAnswer pair = diskPairWithFlatEnd(disk, end);
    if (!std::isfinite(pair.distance)) continue;
    const Vec2 s = disk.nearest(pair.q);
    const Vec3 rim_tangent = disk.n.cross(disk.point(s) - disk.c);
    const Vec3 end_tangent = Vec3::UnitZ().cross(Vec3(pair.p.x(), pair.p.y(), 0.0));
    offerCandidate(target, disk, s, rim_tangent.cross(end_tangent), gap_tolerance, scale, at, lower);
  }
}

/// A visitor type for detecting forEachFace (C++17 has no lambdas in
/// unevaluated contexts).
struct FaceVisitorProbe {
  template <typename Vertex>
  void operator()(const Vec3&, int, const Vertex&) const {}
};
template <typename Target, typename = void>
struct HasFaces : std::false_type {};
template <typename Target>
struct HasFaces<Target, std::void_t<decltype(std::declval<const Target&>().forEachFace(
                            FaceVisitorProbe()))>> : std::true_type {};

/// Faces within this angle (cosine) of parallel to the disk get the polygon
/// candidates: where the rim crosses a face's edge the optimum's curvature
/// jumps by 1 / tilt^2; beyond 0.1 rad (the disk-disk solver's kTiltedStart) the
/// iteration handles the kink in a few steps.
constexpr double kNearlyParallelFaceCosine = 0.995;
/// Newton steps along the rim on the squared distance to an edge's line: the
/// crossing is exact for a disk parallel to the face and off by O(tilt^2 r)
/// otherwise; quadratic convergence needs two or three.
constexpr int kRimLineNewtonSteps = 4;

/// Candidates from X's polygonal faces: a common point where a face's trace on
/// the disk's plane meets the disk; and, for faces nearly parallel to the disk,
/// the rim points above each face edge (where psi along the rim has a kink: over the
/// face it is the height, past the edge the distance to the edge), moved by
/// Newton along the rim to the minimum of the squared distance to the edge's
/// line (smooth across the kink), certified along t_rim x edge; the feet of
/// the face's vertices on the disk (a vertex under the disk's face); and the
/// disk's rim point lowest towards the face (over the face's interior). The
/// polygon analogue of the lens corners (tryFlatEnds).
template <typename Target>
void tryFaces(const Target& target, const DiskInShape& disk, double gap_tolerance, double scale,
              ShapeIterate* at, double* lower) {
  const double r = disk.r;
  target.forEachFace([&](const Vec3& normal, int count, const auto& vertex) {
    // Any face crossing the disk's plane: its trace there is the segment
    // between two edges' crossings; its point nearest the disk's centre, when
    // inside the disk, is a common point. A sliver face (a triangle of nearly
    // zero area) meets the disk only in a thin strip, where psi's regions
    // alternate and the iteration can stop short of it.
    std::array<Vec2, 2> trace;
    int crossings = 0;
    for (int i = 0; i < count && crossings < 2; ++i) {
      const Vec3 a = vertex(i), b = vertex((i + 1) % count);
      const double height_a = disk.n.dot(a - disk.c), height_b = disk.n.dot(b - disk.c);
      if (!((height_a < 0.0 && height_b >= 0.0) || (height_a >= 0.0 && height_b < 0.0))) continue;
      trace[crossings] = disk.inPlane(a + (height_a / (height_a - height_b)) * (b - a) - disk.c);
      if (trace[crossings].squaredNorm() <= r * r) {
        offerCandidate(target, disk, trace[crossings], disk.n, gap_tolerance, scale, at, lower);
      }
      ++crossings;
    }
    if (crossings == 2) {
      const Vec2 along = trace[1] - trace[0];
      const double length_squared = along.squaredNorm();
      const double t =
          length_squared > 0.0 ? std::clamp(-trace[0].dot(along) / length_squared, 0.0, 1.0) : 0.0;
      const Vec2 s = trace[0] + t * along;
      if (s.squaredNorm() <= r * r) {
        offerCandidate(target, disk, s, disk.n, gap_tolerance, scale, at, lower);
      }
    }
    if (!(std::abs(disk.n.dot(normal)) >= kNearlyParallelFaceCosine)) return;
    // The disk's point lowest towards the face (its rim point down the tilt):
    // optimal, certified along the face normal, when its foot is on the face.
    const Vec3 towards_disk = normal.dot(disk.c - vertex(0)) >= 0.0 ? normal : Vec3(-normal);
    const Vec2 downhill = disk.inPlane(towards_disk);
    const double downhill_length = downhill.norm();
    if (downhill_length > 0.0) {
      offerCandidate(target, disk, Vec2(-(r / downhill_length) * downhill), towards_disk,
                     gap_tolerance, scale, at, lower);
    }
    for (int i = 0; i < count; ++i) {
      const Vec3 a = vertex(i);
      offerCandidate(target, disk, disk.nearest(a), disk.n, gap_tolerance, scale, at, lower);
      const Vec3 edge = vertex((i + 1) % count) - a;
      const double length = edge.norm();
      if (!(length > 0.0)) continue;
      const Vec3 e = edge / length;
      // Rim points x(theta) = c + r (cos u + sin v) on the plane through the
      // edge normal to the face: alpha cos + beta sin = -k.
      const Vec3 across = e.cross(normal);
      const double alpha = r * disk.u.dot(across), beta = r * disk.v.dot(across);
      const double k = (disk.c - a).dot(across);
      const double amplitude = std::hypot(alpha, beta);
      if (!(amplitude > 0.0) || !(std::abs(k) <= amplitude)) continue;
      const double cosine = -k / amplitude;
      const double sine = std::sqrt(std::max(0.0, (1.0 - cosine) * (1.0 + cosine)));
      const Vec2 base(alpha / amplitude, beta / amplitude);
      const Vec2 base_perp(-base.y(), base.x());
      for (const double side : {1.0, -1.0}) {
        Vec2 radial = cosine * base + (side * sine) * base_perp;
        const double along = (disk.point(r * radial) - a).dot(e);
        if (!(along >= 0.0 && along <= length)) continue;  // crosses the line, not the edge
        for (int step = 0; step < kRimLineNewtonSteps; ++step) {
          // phi = |y_perp|^2 / 2, y = x - a; x' = r t, x'' = -(x - c).
          const Vec2 tangent(-radial.y(), radial.x());
          const Vec3 x = disk.point(r * radial);
          const Vec3 dx = r * (tangent.x() * disk.u + tangent.y() * disk.v);
          const Vec3 y = x - a;
          const Vec3 y_perp = y - y.dot(e) * e;
          const Vec3 dx_perp = dx - dx.dot(e) * e;
          const double slope = y_perp.dot(dx);
          const double curvature = dx_perp.squaredNorm() - y_perp.dot(x - disk.c);
          if (!(curvature > 0.0)) break;
          const double dtheta = std::clamp(-slope / curvature, -kShapeMaxRimStep, kShapeMaxRimStep);
          const Vec2 turn = cayleyTurn(dtheta);
          radial = turn.x() * radial + turn.y() * tangent;
          if (std::abs(dtheta) * r <= kShapeGradientRounding * scale) break;
        }
        const Vec3 rim_tangent = disk.n.cross(disk.point(r * radial) - disk.c);
        offerCandidate(target, disk, Vec2(r * radial), rim_tangent.cross(e), gap_tolerance, scale,
                       at, lower);
      }
    }
  });
}

template <typename Target, typename = void>
struct HasSupportMismatch : std::false_type {};
template <typename Target>
struct HasSupportMismatch<Target, std::void_t<decltype(std::declval<const Target&>().supportMismatch())>>
    : std::true_type {};

/// The Target's supportMismatch(), 0 if it has none.
template <typename Target>
double supportMismatchOf(const Target& target) {
  if constexpr (HasSupportMismatch<Target>::value) {
    return target.supportMismatch();
  } else {
    return 0.0;
  }
}

/// An upper bound of the distance from x to the set of the Target's support:
/// 0 where its projection and support describe one set (no mismatch), else
/// its supportSetDistanceAbove(x). A point shared by the disk and the
/// projection's set is that far at most from a point of the support's set.
template <typename Target>
double supportSetDistanceAbove(const Target& target, const Vec3& x) {
  if constexpr (HasSupportMismatch<Target>::value) {
    if (target.supportMismatch() > 0.0) return target.supportSetDistanceAbove(x);
  }
  return 0.0;
}

/// Minimises psi(s) = dist(x(s), X)^2 / 2 over the disk |s| <= r by the feasible
/// Newton iteration of docs/disk_shape_distance.md section 3 and certifies the
/// answer; the result is for X inflated by rho (>= 0). `scale` sets every
/// tolerance. Every iterate is a feasible pair, so `distance` is always an upper
/// bound and `lower_bound` a lower bound of the true distance.
template <typename Target>
DiskShapeSolution solveDiskShape(const Target& target, const DiskInShape& disk, double rho,
                                 double scale, SolverGoal goal) {
  const double r = disk.r;
  // Both tolerances widen by the Target's supportMismatch: its projection
  // and support describe sets that far apart, so neither a gap nor a distance
  // below it can be resolved (an overlap would end at distance ~mismatch,
  // open, and go through the fallback searches).
  const double mismatch = supportMismatchOf(target);
  const double gap_tolerance = kShapeGapTolerance * scale + mismatch;
  const double touching = kShapeTouchingTolerance * scale + mismatch;
  DiskShapeSolution face;
  if (faceCase(target, disk, rho, touching, &face)) return face;
  // Start: kStartProjections alternating projections from the disk's point
  // nearest X's frame origin.
  Vec2 start = disk.nearest(Vec3::Zero());
  for (int k = 0; k < kStartProjections; ++k) {
    start = disk.nearest(target.project(disk.point(start)).q);
  }
  ShapeIterate at = evaluateAt(target, disk, start);
  DiskShapeSolution solution;

  // The answer at the current iterate, with its certificate `lower` (for X + B_rho).
  auto finish = [&](int iteration, double lower) {
    // Still open: search by values, along the rim or inside the disk. The
    // intersection goal needs it only while its answer is undecided.
    auto undecided = [&] {
      const double open_distance = std::sqrt(2.0 * at.psi) - rho;
      return goal == SolverGoal::distance
                 ? open_distance - lower > kShapeFallbackGap * scale + mismatch
                 : open_distance > touching && !(lower > touching);
    };
    if constexpr (HasFlatEnds<Target>::value) {
      if (rho == 0.0 && undecided()) tryFlatEnds(target, disk, gap_tolerance, scale, &at, &lower);
    }
    if constexpr (HasFaces<Target>::value) {
      if (rho == 0.0 && undecided()) tryFaces(target, disk, gap_tolerance, scale, &at, &lower);
    }
    if (undecided()) {
      const double psi_before = at.psi;
      at = at.s.norm() >= r * (1.0 - kShapeOnRim) ? searchAlongRim(target, disk, at)
                                                 : searchInside(target, disk, at);
      if (at.psi < psi_before) {
        lower = std::max(lower, certificateAt(target, disk, rho, at, std::sqrt(2.0 * at.psi) - rho,
                                              gap_tolerance, scale, /*returned=*/true));
      }
    }
    const double core_distance = std::sqrt(2.0 * at.psi);
    solution.iterations = iteration;
    solution.p = at.x;
    // x lies in X + B_rho, or within the touching tolerance of it (a pair built
    // touching in one frame touches only to rounding in another): a common point.
    if (core_distance <= rho + touching) {
      solution.q = at.x;
      return solution;
    }
    // The point of X + B_rho nearest x: from q towards x by rho.
    solution.q = at.q + (rho / core_distance) * (at.x - at.q);
    solution.distance = core_distance - rho;
    solution.lower_bound = std::min(lower, solution.distance);
    return solution;
  };
  // `returned`: the iterate will be returned whatever the certificate says, so
  // every direction is worth trying.
  auto certify = [&](double distance, bool returned) {
    return certificateAt(target, disk, rho, at, distance, gap_tolerance, scale, returned);
  };

  const double certify_below = kShapeCertifyGain * gap_tolerance;
  for (int iteration = 1; iteration <= kMaxShapeIterations; ++iteration) {
    const double core_distance = std::sqrt(2.0 * at.psi);
    if (core_distance <= rho) return finish(iteration, 0.0);
    const double distance = core_distance - rho;
    // The certificate at this iterate, and whether it ends the iteration.
    double lower = 0.0;
    bool certified = false;
    auto certificate_closes = [&] {
      lower = certify(distance, /*returned=*/false);
      certified = true;
      if (goal == SolverGoal::intersection && (distance <= touching || lower > touching)) {
        return true;
      }
      return distance - lower <= gap_tolerance;
    };
    // For the intersection goal at every iterate: a positive bound proves the
    // pair apart however far from optimal.
    if (goal == SolverGoal::intersection && certificate_closes()) return finish(iteration, lower);

    // The proposed step: Newton along the rim when the point is on it with a
    // non-negative multiplier, else the disk-constrained model step.
    const Vec2 s = at.s;
    const double radius = s.norm();
    const bool near_rim = radius >= r * (1.0 - kShapeOnRim) && radius > 0.0;
    bool rim_step = false;
    Vec2 radial, tangent;
    double sigma = 0.0, kappa = 0.0;
    if (near_rim) {
      radial = s / radius;
      tangent = Vec2(-radial.y(), radial.x());
      const double outward = -at.gradient.dot(radial);
      rim_step =
          outward >= 0.0 || outward * outward <= kShapeInwardGradient * kShapeInwardGradient *
                                                     at.gradient.squaredNorm();
      if (rim_step) {
        // psi(theta)' = r sigma, psi'' = r kappa (lengths).
        sigma = at.gradient.dot(tangent);
        const Vec3 tangent3 = tangent.x() * disk.u + tangent.y() * disk.v;
        kappa = r * at.hessian3.quadratic(tangent3) + std::max(outward, 0.0);
      }
    }
    // The model step and the decrease of psi its model predicts.
    Vec2 step = Vec2::Zero();
    double model_decrease = 0.0;
    auto model_step = [&] {
      const Mat2 planar_hessian = planarHessian(at.hessian3, disk);
      step = modelStepOnDisk(planar_hessian, at.gradient, s, r, kShapeGradientRounding * scale);
      model_decrease = -(at.gradient.dot(step) + 0.5 * step.dot(planar_hessian * step));
    };
    if (!rim_step) model_step();
    // What the step expects to gain, in distance (psi = d^2 / 2): Newton's
    // decrease of psi, r sigma^2 / (2 kappa) along the rim, the model's
    // otherwise. Once that is little more than the gap tolerance (the gap is at
    // least what is left to gain) the certificate may close.
    const double expected_decrease =
        rim_step ? (kappa > 0.0 ? (0.5 * r * sigma * sigma) / (kappa * core_distance)
                                : std::numeric_limits<double>::infinity())
                 : model_decrease / core_distance;
    if (!certified && expected_decrease <= certify_below && certificate_closes()) {
      return finish(iteration, lower);
    }
    // The rim step: dtheta = -sigma / kappa, at most kShapeMaxRimStep.
    double dtheta = kappa > 0.0 ? -sigma / kappa : -std::copysign(kShapeMaxRimStep, sigma);
    dtheta = std::clamp(dtheta, -kShapeMaxRimStep, kShapeMaxRimStep);

    bool moved = false;
    ShapeIterate next;
    for (int halving = 0; rim_step && halving < kShapeMaxRimHalvings && !moved; ++halving) {
      const Vec2 rotation = cayleyTurn(dtheta);
      next = evaluateAt(target, disk, r * (rotation.x() * radial + rotation.y() * tangent));
      moved = next.psi < at.psi;
      dtheta *= 0.5;
    }
    if (!moved) {
      if (rim_step) model_step();
      const double slope = at.gradient.dot(step);
      if (!(slope < 0.0)) return finish(iteration, certify(distance, true));  // stationary
      // The model reaching psi = 0 means the step ends on X's boundary, where
      // psi is 0 only to rounding: twice the step, when it stays on the disk,
      // is usually inside X, an overlap proven one iteration sooner.
      if (rho == 0.0 && at.psi - model_decrease <= kShapeModelReachesX * at.psi &&
          (s + 2.0 * step).squaredNorm() <= r * r) {
        next = evaluateAt(target, disk, s + 2.0 * step);
        moved = next.psi == 0.0;
      }
      if (!moved) {
        shapeLineSearch(target, disk, at, step, slope, &next);
        moved = next.psi < at.psi;
      }
    }
    if (!moved) return finish(iteration, certify(distance, true));  // no representable decrease
    const double decrease = at.psi - next.psi;
    at = next;
    if (decrease <= kShapeStagnation * scale * scale) {
      return finish(iteration, certify(std::sqrt(2.0 * at.psi) - rho, true));
    }
  }
  return finish(kMaxShapeIterations, certify(std::sqrt(2.0 * at.psi) - rho, true));
}

}  // namespace internal
}  // namespace fcl_disk
