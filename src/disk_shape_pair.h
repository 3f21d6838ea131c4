// Internal: what every disk-shape pair shares. The disk posed in the shape's
// frame, input validation, the world-frame result, the contact, and the driver
// that runs the generic solver (src/disk_shape_solver.h) for a pair given its
// Target. A pair file (src/pairs/disk_<shape>.cpp) specialises DiskShapePair for
// its shape and instantiates it with FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>

#include "disk_penetration_candidates.h"
#include "disk_shape_solver.h"
#include "environment_bounds.h"
#include "fcl_disk/disk_shape_distance.h"

namespace fcl_disk {
namespace internal {

/// Whether every length of a shape is usable: finite, >= 0, within the range of
/// disk lengths (kMaxDiskLength: squares stay finite).
inline bool isValidShapeLength(double length) {
  return length >= 0.0 && length <= double(kMaxDiskLength<double>);
}
inline bool areValidShapeLengths(std::initializer_list<double> lengths) {
  bool valid = true;
  for (const double length : lengths) valid &= isValidShapeLength(length);
  return valid;
}

/// intersect()'s early exit proves a pair apart only beyond this many touching
/// tolerances, so that it never calls apart a pair the full decision calls
/// touching: the closed forms that decide through the disk-disk common point
/// (a cylinder's cap, a cone's base) join disks up to about 2.2 of that pair's
/// tolerances apart, whose scene is at most twice the shape pair's, and the
/// bound's rounding is a few eps * scale against the tolerance's 450.
constexpr double kApartMargin = 8.0;

template <typename S>
DiskShapeDistanceResult<S> nanDiskShapeResult() {
  const S nan = std::numeric_limits<S>::quiet_NaN();
  DiskShapeDistanceResult<S> result;
  result.distance = result.lower_bound = nan;
  result.p_W_disk.setConstant(nan);
  result.p_W_shape.setConstant(nan);
  return result;
}

/// Whether the pair is valid (isValidDiskAndShapePose's rule,
/// include/fcl_disk/disk_pair.h), and whether both rotations are used as given
/// (checkDiskPose with kAsGivenRotationTolerance: in double, within
/// kOrthonormalInDouble; in float never), so that the disk's axes in the
/// shape's frame are orthonormal to double rounding: one pass over both poses
/// (checkTwoPoses).
struct DiskAndShapePoseCheck {
  bool valid;
  bool orthonormal;
};

template <typename S>
[[gnu::always_inline]] inline DiskAndShapePoseCheck checkDiskAndShapePose(
    S radius, const fcl::Transform3<S>& X_WD, const fcl::Transform3<S>& X_WS) {
  const TwoPoseCheck poses = checkTwoPoses(X_WD, X_WS, kAsGivenRotationTolerance<S>);
  return {isValidDiskRadius(radius) && poses.valid, poses.orthonormal_a && poses.orthonormal_b};
}

/// The result of a solution in the shape's frame, or (toWorldFromShapeOrigin)
/// in diskAtShapeOrigin's.
template <typename S, typename ToWorld>
DiskShapeDistanceResult<S> resultInWorld(const DiskShapeSolution& solution, ToWorld to_world) {
  // The points first: the result's default values are then overwritten with
  // no read of the poses in between, so the compiler drops them.
  const fcl::Vector3<S> p_W_disk = to_world(solution.p).template cast<S>();
  const fcl::Vector3<S> p_W_shape = to_world(solution.q).template cast<S>();
  DiskShapeDistanceResult<S> result;
  result.distance = S(solution.distance);
  result.lower_bound = S(std::min(solution.lower_bound, solution.distance));
  result.p_W_disk = p_W_disk;
  result.p_W_shape = p_W_shape;
  result.iterations = solution.iterations;
  return result;
}
template <typename S>
DiskShapeDistanceResult<S> toWorld(const fcl::Transform3<S>& X_WS,
                                   const DiskShapeSolution& solution) {
  return resultInWorld<S>(solution, [&](const Vec3& p) { return toWorldPoint(X_WS, p); });
}
template <typename S>
DiskShapeDistanceResult<S> toWorldFromShapeOrigin(const fcl::Transform3<S>& X_WS,
                                                  const DiskShapeSolution& solution) {
  return resultInWorld<S>(solution, [&](const Vec3& p) { return fromShapeOrigin(X_WS, p); });
}

/// Among the unit candidate directions w (the disk's normals and the shape's
/// own, both signs), the one whose separating translation of the shape,
/// depth(w) = max_disk w.k - min_shape w.y, is smallest (docs section 5). When
/// the candidates hold a minimiser of depth(w) over all w (the
/// kExactDiskShapePenetration shapes), the depth is the penetration depth if
/// the sets meet and minus their distance if not: its sign decides the overlap.
/// Candidates are pushed to it one by one (push_back(w): both signs), the
/// disk's normals first. For a pair known to share a point (to the touching
/// tolerance) a candidate generator may skip the directions that cannot beat
/// pruningBound(), the best depth so far plus `prune_slack` (>= 0; negative:
/// nothing is skipped); docs/penetration_depth.md, section 7.
template <typename DepthAlong>
class SeparationSearch {
 public:
  /// `inflation`: the rho of depth_along (X = core + B_rho), for the bounds.
  SeparationSearch(const DiskInShape& disk, DepthAlong depth_along, double prune_slack,
                   double inflation = 0.0)
      : depth_along_(std::move(depth_along)),
        prune_slack_(prune_slack),
        inflation_(inflation),
        best_{std::numeric_limits<double>::infinity(), disk.n} {
    consider(disk.n);
    consider(-disk.n);
  }

  void push_back(const Vec3& w) {
    consider(w);
    consider(-w);
  }
  /// w alone, for a candidate whose other sign is known not to be one.
  void push_one(const Vec3& w) { consider(w); }
  /// Whether candidates that cannot beat pruningBound() may be skipped.
  bool prunes() const { return prune_slack_ >= 0.0; }
  /// The slack of pruningBound() (>= 0 when prunes()): above the pair's
  /// distance, which is within the touching tolerance when it prunes.
  double pruneSlack() const { return prune_slack_; }
  /// A depth no skipped candidate could reach: infinite until a positive depth
  /// is found (the minimiser of a pair that shares a point has depth >= 0).
  double pruningBound() const {
    return prunes() && best_.depth > 0.0 ? best_.depth + prune_slack_
                                         : std::numeric_limits<double>::infinity();
  }
  const Separation& best() const { return best_; }
  double inflation() const { return inflation_; }

 private:
  void consider(const Vec3& w) {
    const double length = w.norm();
    if (!(length > 0.0)) return;
    const Vec3 unit = w / length;
    const double depth = depth_along_(unit);
    if (depth < best_.depth) best_ = Separation{depth, unit};
  }

  DepthAlong depth_along_;
  double prune_slack_;
  double inflation_;
  Separation best_;
};

/// The shortest separation among the disk's normals and `shape_directions`,
/// nothing skipped.
template <typename Directions, typename DepthAlong>
Separation shortestSeparation(const DiskInShape& disk, const Directions& shape_directions,
                              DepthAlong depth_along) {
  SeparationSearch<DepthAlong> search(disk, depth_along, -1.0);
  for (const Vec3& w : shape_directions) search.push_back(w);
  return search.best();
}

/// The contact of an intersecting pair (frame S in, world out): pos the common
/// point, the shortest separation's depth and direction.
template <typename S>
DiskContact<S> contactInWorld(const fcl::Transform3<S>& X_WS, const Vec3& common_point,
                              const Separation& separation) {
  DiskContact<S> contact;
  contact.pos = toWorldPoint(X_WS, common_point).template cast<S>();
  contact.normal = (X_WS.linear().template cast<double>() * separation.direction).template cast<S>();
  contact.penetration_depth = S(std::max(separation.depth, 0.0));
  return contact;
}
/// contactInWorld from diskAtShapeOrigin's frame.
template <typename S>
DiskContact<S> contactFromShapeOrigin(const fcl::Transform3<S>& X_WS, const Vec3& common_point,
                                      const Separation& separation) {
  DiskContact<S> contact;
  contact.pos = fromShapeOrigin(X_WS, common_point).template cast<S>();
  contact.normal = separation.direction.template cast<S>();
  contact.penetration_depth = S(std::max(separation.depth, 0.0));
  return contact;
}

/// The depth, relative to scale, above which the penetration candidates decide
/// an overlap the distance iteration left open. Their shortest separation is
/// exact up to the accuracy of the candidate directions, which on pairs
/// touching to rounding reaches 3e-12 of the scale (fuzz_disk_shapes:
/// regression-open-overlap-touching-cone) and, for a disk nearly parallel to a
/// cylinder's cap (double roots), 1.6e-9 (regression-open-overlap-parallel-
/// cylinder-cap); below this the iteration's answer stands.
constexpr double kOpenOverlapDepth = 1e-7;

/// Whether a Traits class has a closed form for some configurations:
///   static LeafToDisk closedForm(const DiskInShape&, const Shape&, double scale);
/// (src/environment_bounds.h), tried before the generic solver.
template <typename Traits, typename = void>
constexpr bool kHasClosedForm = false;
template <typename Traits>
constexpr bool kHasClosedForm<Traits, std::void_t<decltype(&Traits::closedForm)>> = true;

/// Whether a Traits class says, per shape, that intersect() asked for no
/// contact decides by its closed form before the early exit:
///   static bool closedFormDecidesFirst(const Shape&);
/// for shapes whose early exit costs more than their closed form (a large
/// Convex's early exit reads its faces, its closed form only its vertices).
template <typename Traits, typename = void>
constexpr bool kHasClosedFormFirst = false;
template <typename Traits>
constexpr bool
    kHasClosedFormFirst<Traits, std::void_t<decltype(&Traits::closedFormDecidesFirst)>> = true;

/// Whether a Traits class checks a meeting its projection found against its
/// support's set (the Targets with a supportMismatch):
///   static std::optional<LeafToDisk> answerOffSupportSet(
///       const DiskInShape&, const Shape&, const Vec3& common, double scale);
/// the pair's answer where the meeting point `common` may lie farther than
/// the mismatch from the support's set, else nullopt (the meeting stands).
template <typename Traits, typename = void>
constexpr bool kHasSupportSetCheck = false;
template <typename Traits>
constexpr bool
    kHasSupportSetCheck<Traits, std::void_t<decltype(&Traits::answerOffSupportSet)>> = true;

/// Each pair specialises this for its shape class (src/pairs/disk_<shape>.cpp)
/// with static distance() and intersect() matching diskShapeDistance /
/// diskShapeIntersect; GenericDiskShapePair implements both for pairs solved by
/// the generic solver.
template <typename Shape>
struct DiskShapePair;

/// distance() and intersect() from the generic solver, for a Traits class with
///   static bool valid(const Shape&);                // dimensions usable
///   static double boundingRadius(const Shape&);     // about the shape's origin
///   static double inflation(const Shape&);          // rho: X = core + B_rho
///   static Target target(const Shape&);             // the core, in the shape frame
///   template <typename Search>
///   static void contactDirections(const Target&, const DiskInShape&, Search*);
///                       // pushes the shape's candidates (shape frame) to the
///                       // search (SeparationSearch), may skip by its bound
template <typename S, typename Shape, typename Traits>
struct GenericDiskShapePair {
  /// `prune_slack`: as SeparationSearch's (negative unless the pair is known
  /// to share a point).
  template <typename Target>
  static Separation shortestSeparation(const Target& target, const DiskInShape& disk, double rho,
                                       double prune_slack) {
    const auto depth_along = [&](const Vec3& w) {
      return disk.support(w) - (leastAlong(target, w) - rho);
    };
    SeparationSearch<decltype(depth_along)> search(disk, depth_along, prune_slack, rho);
    Traits::contactDirections(target, disk, &search);
    return search.best();
  }

  /// Whether the solver left the overlap open (not within touching, not proven
  /// apart: a grazing overlap it stalled next to) and the shape's candidates,
  /// whose shortest separation is the penetration depth, find the sets
  /// overlapping by more than kOpenOverlapDepth * scale; `separation` keeps
  /// what the candidates found, when they were asked.
  template <typename Target>
  static bool overlapLeftOpen(const Target& target, const DiskInShape& disk, double rho,
                              const DiskShapeSolution& solution, double scale,
                              std::optional<Separation>* separation) {
    if constexpr (kExactDiskShapePenetration<Shape>) {
      const double touching = kShapeTouchingTolerance * scale;
      if (!(solution.distance > touching && !(solution.lower_bound > touching))) return false;
      *separation = shortestSeparation(target, disk, rho, /*prune_slack=*/-1.0);
      return (*separation)->depth > kOpenOverlapDepth * scale;
    }
    return false;
  }

  static DiskShapeDistanceResult<S> distance(S radius, const fcl::Transform3<S>& X_WD,
                                             const Shape& shape, const fcl::Transform3<S>& X_WS) {
    const DiskAndShapePoseCheck poses = checkDiskAndShapePose(radius, X_WD, X_WS);
    if (!poses.valid || !Traits::valid(shape)) return nanDiskShapeResult<S>();
    return toWorld(X_WS, solveInShapeFrame(
                             solvedDiskInShape(radius, X_WD, X_WS, poses.orthonormal), shape));
  }

  /// Whether the Traits' closed form (if it has one) certifies itself on
  /// `disk`; its answer in `solution` if so.
  static bool closedFormSolves([[maybe_unused]] const DiskInShape& disk,
                               [[maybe_unused]] const Shape& shape, [[maybe_unused]] double scale,
                               [[maybe_unused]] DiskShapeSolution* solution) {
    if constexpr (kHasClosedForm<Traits>) {
      const LeafToDisk closed = Traits::closedForm(disk, shape, scale);
      if (!closed.exact) return false;
      solution->p = closed.p_disk;
      solution->q = closed.p_leaf;
      solution->distance = closed.distance;
      solution->lower_bound = closed.certified;
      return true;
    }
    return false;
  }

  /// The disk of radius `radius` and pose X_WD in the frame of the shape at
  /// X_WS, as the pair's solvers take it; `orthonormal` is
  /// checkDiskAndShapePose's. For Traits with a closed form its axes are
  /// rebuilt (DiskInShape::withOrthonormalAxes) unless the poses are
  /// orthonormal: the closed forms certify to 1e-13 of the scale only a true
  /// disk, not the ellipse 1e-7 off it that a pose in float gives. The generic
  /// solver is exact on that ellipse ({c + s_x u + s_y v : |s| <= r}, whose
  /// support DiskInShape::support is), within float's rounding of the disk, so
  /// other pairs keep it.
  static DiskInShape solvedDiskInShape(S radius, const fcl::Transform3<S>& X_WD,
                                       const fcl::Transform3<S>& X_WS,
                                       [[maybe_unused]] bool orthonormal) {
    if constexpr (kHasClosedForm<Traits>) {
      if (!orthonormal) return diskInShape(radius, X_WD, X_WS).withOrthonormalAxes();
    }
    return diskInShape(radius, X_WD, X_WS);
  }

  /// distance() in the shape's frame, for a valid pair: the Traits' closed
  /// form where it certifies itself (Traits::closedForm, if it has one and
  /// `try_closed_form`: callers that tried it already pass false), else the
  /// generic solver. `disk` as solvedDiskInShape gives it (the leaves of
  /// meshes and octrees: orthonormalDiskInShape).
  static DiskShapeSolution solveInShapeFrame(const DiskInShape& disk, const Shape& shape,
                                             bool try_closed_form = true) {
    const double scale = disk.r + Traits::boundingRadius(shape) + disk.c.norm();
    DiskShapeSolution solution;
    if (try_closed_form && closedFormSolves(disk, shape, scale, &solution)) return solution;
    const auto target = Traits::target(shape);
    const double rho = Traits::inflation(shape);
    solution = solveDiskShape(target, disk, rho, scale, SolverGoal::distance);
    std::optional<Separation> separation;
    if (overlapLeftOpen(target, disk, rho, solution, scale, &separation)) {
      // Overlap: distance 0 at the solver's point, whose distance to the
      // shape is the solver's residual.
      solution.q = solution.p;
      solution.distance = solution.lower_bound = 0.0;
    } else if (solution.distance == 0.0) {
      // The solver's common point, checked against the support's set.
      if (const auto answer = answerOffSupportSet(disk, shape, solution.p, scale)) {
        solution.p = answer->p_disk;
        solution.q = answer->p_leaf;
        solution.distance = answer->distance;
        solution.lower_bound = answer->certified;
      }
    }
    return solution;
  }

  /// Traits::answerOffSupportSet where the Traits has it (kHasSupportSetCheck).
  static std::optional<LeafToDisk> answerOffSupportSet([[maybe_unused]] const DiskInShape& disk,
                                                       [[maybe_unused]] const Shape& shape,
                                                       [[maybe_unused]] const Vec3& common,
                                                       [[maybe_unused]] double scale) {
    if constexpr (kHasSupportSetCheck<Traits>) {
      return Traits::answerOffSupportSet(disk, shape, common, scale);
    }
    return std::nullopt;
  }

  /// The slack under which the candidates of a pair known to share a point
  /// may be skipped (SeparationSearch): kPrunedCandidateSlack of the scene,
  /// plus how far the pair's common point `common` (a disk point) may lie
  /// from the set the depth reads (supportSetDistanceAbove). Every F(w) is at
  /// least minus the distance of the disk and that set, and so at least
  /// minus that bound; a Convex whose faces are planar only to rounding finds
  /// its common point inside its face planes, up to ~their thickness outside
  /// its vertices' hull.
  template <typename Target>
  static double pruneSlack(const Target& target, const Vec3& common, double scale) {
    return kPrunedCandidateSlack * scale + supportSetDistanceAbove(target, common);
  }

  static bool intersect(S radius, const fcl::Transform3<S>& X_WD, const Shape& shape,
                        const fcl::Transform3<S>& X_WS, DiskContact<S>* contact) {
    const DiskAndShapePoseCheck poses = checkDiskAndShapePose(radius, X_WD, X_WS);
    if (!poses.valid || !Traits::valid(shape)) return false;
    const DiskInShape disk = solvedDiskInShape(radius, X_WD, X_WS, poses.orthonormal);
    if constexpr (kHasClosedFormFirst<Traits>) {
      if (contact == nullptr && Traits::closedFormDecidesFirst(shape)) {
        const double scale = disk.r + Traits::boundingRadius(shape) + disk.c.norm();
        DiskShapeSolution closed;
        if (closedFormSolves(disk, shape, scale, &closed)) {
          return closed.distance <= kShapeTouchingTolerance * scale;
        }
      }
    }
    FrameContact in_shape_frame;
    if (!intersectInShapeFrame(disk, shape, contact ? &in_shape_frame : nullptr)) return false;
    if (contact) *contact = contactInWorld<S>(X_WS, in_shape_frame.pos, in_shape_frame.separation);
    return true;
  }

  /// intersect() in the shape's frame, for a valid pair; `disk` as
  /// solveInShapeFrame's. `try_early_exit`: false for the leaves of meshes and
  /// octrees, which reach here only when their bounding volumes meet the
  /// disk's, so that the early exit would seldom prove them apart.
  static bool intersectInShapeFrame(const DiskInShape& disk, const Shape& shape,
                                    FrameContact* contact, bool try_early_exit = true) {
    const auto target = Traits::target(shape);
    const double rho = Traits::inflation(shape);
    const double scale = disk.r + Traits::boundingRadius(shape) + disk.c.norm();
    const double touching = kShapeTouchingTolerance * scale;
    // Apart by more than kApartMargin touching tolerances (and the Target's
    // supportMismatch): every decision below would say apart too.
    if (try_early_exit && apartTowardsCentre(target, disk, rho,
                                             kApartMargin * touching + supportMismatchOf(target))) {
      return false;
    }
    // The closed form distance() tries first decides here too, so that a pair
    // at distance 0 intersects.
    DiskShapeSolution closed;
    if (closedFormSolves(disk, shape, scale, &closed)) {
      if (!(closed.distance <= touching)) return false;
      if (contact) {
        contact->pos = 0.5 * (closed.p + closed.q);
        contact->separation =
            shortestSeparation(target, disk, rho, pruneSlack(target, closed.p, scale));
      }
      return true;
    }
    DiskShapeSolution solution =
        solveDiskShape(target, disk, rho, scale, SolverGoal::intersection);
    std::optional<Separation> separation;
    if (!(solution.distance <= touching) &&
        !overlapLeftOpen(target, disk, rho, solution, scale, &separation)) {
      return false;
    }
    if (!separation && solution.distance <= touching) {
      // The solver's common point, checked against the support's set as
      // distance() checks it: touching within the mismatch and the tolerance.
      if (const auto answer = answerOffSupportSet(disk, shape, solution.p, scale)) {
        if (!(answer->distance <= touching + supportMismatchOf(target))) return false;
        solution.p = answer->p_disk;
        solution.q = answer->p_leaf;
      }
    }
    if (contact) {
      // pos: the common point, or midway between the solver's nearest points
      // of an overlap it left open. Without a separation from overlapLeftOpen
      // the solver proved a common point, so candidates may be skipped.
      if (!separation) {
        separation = shortestSeparation(target, disk, rho, pruneSlack(target, solution.p, scale));
      }
      contact->pos = 0.5 * (solution.p + solution.q);
      contact->separation = *separation;
    }
    return true;
  }
};

}  // namespace internal

// The one definition of the public entry points: each pair's DiskShapePair.
template <typename S, typename Shape>
DiskShapeDistanceResult<S> diskShapeDistance(S radius, const fcl::Transform3<S>& X_WD,
                                             const Shape& shape, const fcl::Transform3<S>& X_WS) {
  return internal::DiskShapePair<Shape>::distance(radius, X_WD, shape, X_WS);
}

template <typename S, typename Shape>
bool diskShapeIntersect(S radius, const fcl::Transform3<S>& X_WD, const Shape& shape,
                        const fcl::Transform3<S>& X_WS, DiskContact<S>* contact) {
  return internal::DiskShapePair<Shape>::intersect(radius, X_WD, shape, X_WS, contact);
}

}  // namespace fcl_disk

/// Instantiates the public entry points for fcl::ShapeTemplate<float / double>.
#define FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(ShapeTemplate)                                      \
  namespace fcl_disk {                                                                         \
  template DiskShapeDistanceResult<float> diskShapeDistance(                                   \
      float, const fcl::Transform3<float>&, const ShapeTemplate<float>&,                        \
      const fcl::Transform3<float>&);                                                          \
  template DiskShapeDistanceResult<double> diskShapeDistance(                                  \
      double, const fcl::Transform3<double>&, const ShapeTemplate<double>&,                     \
      const fcl::Transform3<double>&);                                                         \
  template bool diskShapeIntersect(float, const fcl::Transform3<float>&,                        \
                                   const ShapeTemplate<float>&, const fcl::Transform3<float>&,  \
                                   DiskContact<float>*);                                       \
  template bool diskShapeIntersect(double, const fcl::Transform3<double>&,                      \
                                   const ShapeTemplate<double>&, const fcl::Transform3<double>&, \
                                   DiskContact<double>*);                                      \
  }
