// Disk - fcl::Cylinder (a real, solid one): the side wall as the capsule pair
// and the caps as disk-disk pairs where their certificates close
// (CylinderTraits::closedForm), else the generic solver with the cylinder's
// projection (clamp the height, clamp the radial distance) and support
// (docs/disk_shape_distance.md, section 4); the contact's directions make its
// depth the exact penetration depth (docs/penetration_depth.md, section 7).
#include "../disk_shape_pair.h"
#include "feature_candidates.h"
#include "../leaf_solvers.h"
#include "flat_end_pair.h"

#include <vector>

namespace fcl_disk {
namespace internal {
namespace {

/// The solid cylinder {x^2 + y^2 <= radius^2, |z| <= half_length}, in its frame.
struct CylinderTarget {
  double radius;
  double half_length;

  Projection project(const Vec3& y) const {
    const double z = std::clamp(y.z(), -half_length, half_length);
    const double rho = std::sqrt(y.x() * y.x() + y.y() * y.y());
    // psi's Hessian in the cylinder frame: z z^T beyond an end cap; in the
    // plane, 0 inside the radius, else that of a circle's disk,
    // e e^T + (1 - radius / rho) t t^T (e radial, t tangent).
    FactoredHessian hessian = FactoredHessian::diagonalOf(Vec3(0.0, 0.0, z != y.z() ? 1.0 : 0.0));
    Vec3 q_S(y.x(), y.y(), z);
    if (rho > radius) {
      const double shrink = radius / rho;
      q_S.x() *= shrink, q_S.y() *= shrink;
      const Vec3 e(y.x() / rho, y.y() / rho, 0.0);
      hessian.add(1.0, e).add(1.0 - shrink, Vec3(-e.y(), e.x(), 0.0));
    }
    return Projection{q_S, hessian};
  }

  Vec3 support(const Vec3& w_S) const {
    const double planar = std::sqrt(w_S.x() * w_S.x() + w_S.y() * w_S.y());
    // Ties: w along the axis takes the rim point on +x; w in the plane the + cap.
    const Vec3 rim = planar > 0.0 ? Vec3(radius * w_S.x() / planar, radius * w_S.y() / planar, 0.0)
                                  : Vec3(radius, 0.0, 0.0);
    return rim + Vec3(0.0, 0.0, w_S.z() < 0.0 ? -half_length : half_length);
  }

  /// min over the cylinder of w.y: -radius |w_xy| - half_length |w_z|.
  double leastAlong(const Vec3& w_S) const {
    return -radius * std::sqrt(w_S.x() * w_S.x() + w_S.y() * w_S.y()) -
           half_length * std::abs(w_S.z());
  }

  /// The caps: candidates where a nearly parallel disk's rim crosses a cap's rim.
  std::array<FlatEnd, 2> flatEnds() const {
    return {FlatEnd{-half_length, radius}, FlatEnd{half_length, radius}};
  }
};

/// Where the disk crosses the plane z = side * h of a cap (docs/disk_shape_distance.md,
/// section 4): the chord's point m nearest the cylinder's axis, and whether m is
/// the point nearest the axis of the disk's part on the near side (side * z <= h).
/// That part's nearest point to the axis is where dist(., cylinder) is least
/// over it while it stays between the caps' planes and off the cylinder (there
/// dist = rho - radius); dist is convex, so that least point is the whole disk's
/// when it is off the plane (the side wall holds the nearest point), and the
/// whole disk's nearest point lies at or beyond the plane when it is m (the cap
/// does). The test is m's KKT condition: rho (convex) does not decrease from m
/// into the near part, along the disk's steepest descent in side * z for a
/// chord-interior m, along the rim for a chord end.
struct CapPlaneChord {
  bool crosses = false;       ///< the disk meets the plane along a chord
  /// m scaled by tilt_squared = 1 - n_z^2 > 0 (crosses only): the tests on m
  /// are homogeneous, so they need no division (it would sit on the query's
  /// latency chain; nearestAxis() divides where m itself is needed).
  Vec3 scaled_nearest_axis;
  double tilt_squared = 0.0;
  bool least_at_chord = false;  ///< m is the near part's point nearest the axis

  /// Whether |m_xy| <= radius.
  bool nearestAxisWithin(double radius) const {
    const double scaled_radius = radius * tilt_squared;
    return scaled_nearest_axis.x() * scaled_nearest_axis.x() +
               scaled_nearest_axis.y() * scaled_nearest_axis.y() <=
           scaled_radius * scaled_radius;
  }
  Vec3 nearestAxis() const { return scaled_nearest_axis / tilt_squared; }
};

CapPlaneChord capPlaneChord(const DiskInShape& disk, double side, double h) {
  CapPlaneChord chord;
  // Z = e_z - n n_z spans the disk's steepest ascent in z (Z.z = |Z|^2 = 1 - n_z^2);
  // the plane meets the disk's plane along c + k Z + tau w, w = n x e_z horizontal,
  // k = rise / tilt_squared. Scaled by tilt_squared (|w|^2 = |Z|^2 = tilt_squared):
  // m' = tilt_squared c + rise Z + tau' w with tau' = clamp(-c.w, +-half_span'),
  // half_span' = sqrt(r^2 tilt_squared - rise^2) (|tau| |w| <= sqrt(r^2 - k^2 |Z|^2));
  // c.w is c's offset along the chord from its midpoint (Z.w = 0).
  const Vec3& n = disk.n;
  const double tilt_squared = n.x() * n.x() + n.y() * n.y();
  const double rise = side * h - disk.c.z();
  const double span_squared = disk.r * disk.r * tilt_squared - rise * rise;
  if (!(span_squared > 0.0)) return chord;
  chord.crosses = true;
  chord.tilt_squared = tilt_squared;
  const Vec3 Z(-n.x() * n.z(), -n.y() * n.z(), tilt_squared);
  const Vec3 w(n.y(), -n.x(), 0.0);
  const double half_span = std::sqrt(span_squared);
  const double tau_free = -(disk.c.x() * w.x() + disk.c.y() * w.y());
  const double tau = std::clamp(tau_free, -half_span, half_span);
  chord.scaled_nearest_axis = tilt_squared * disk.c + rise * Z + tau * w;
  // Into the near part: down the steepest descent, or along the rim at a chord end.
  Vec3 inwards = -side * Z;
  if (tau != tau_free) {
    inwards = n.cross(chord.scaled_nearest_axis - tilt_squared * disk.c);
    if (side * inwards.z() > 0.0) inwards = -inwards;
  }
  const Vec3& m = chord.scaled_nearest_axis;
  chord.least_at_chord = m.x() * inwards.x() + m.y() * inwards.y() >= 0.0;
  return chord;
}

template <typename S>
struct CylinderTraits {
  static bool valid(const fcl::Cylinder<S>& cylinder) {
    return areValidShapeLengths({double(cylinder.radius), double(cylinder.lz)});
  }
  static double boundingRadius(const fcl::Cylinder<S>& cylinder) {
    return Vec2(double(cylinder.radius), 0.5 * double(cylinder.lz)).norm();
  }
  static double inflation(const fcl::Cylinder<S>&) { return 0.0; }
  static CylinderTarget target(const fcl::Cylinder<S>& cylinder) {
    return CylinderTarget{double(cylinder.radius), 0.5 * double(cylinder.lz)};
  }
  /// Two exact cases, each a simpler pair (docs/disk_shape_distance.md,
  /// section 4):
  /// - the side wall: the cylinder lies in the capsule of its radius about
  ///   its axis, and the two share every point with |z| <= half_length. So
  ///   where the capsule's nearest point (solveDiskCapsule) has |z| <=
  ///   half_length, it is on the cylinder, and the capsule's answer and
  ///   certificate are the cylinder's;
  /// - a cap (diskAgainstFlatEnd): where the disk-disk pair of the disk and
  ///   a cap is the cylinder's, the certificate along it closes; for a disk
  ///   wholly beyond a cap's plane the pair's own (diskBeyondFlatEnd).
  /// Which to try first is read off where the disk crosses the caps' planes
  /// (capPlaneChord): a chord point within the radius is a common point; a cap
  /// goes first when the disk lies wholly beyond its plane or its chord holds
  /// the near part's point nearest the axis, else the side wall, then the cap
  /// beyond which the capsule's point lies. What neither settles (an optimum
  /// at a cap's rim seen from the side, where the certificate along one pair
  /// can stay open) goes to the generic solver. `disk`'s axes are orthonormal
  /// (solvedDiskInShape).
  static LeafToDisk closedForm(const DiskInShape& disk, const fcl::Cylinder<S>& cylinder,
                               double scale) {
    const CylinderTarget cylinder_target = target(cylinder);
    const double h = cylinder_target.half_length, radius = cylinder_target.radius;
    const auto against_cap = [&](double side) {
      return diskAgainstFlatEnd(disk, cylinder_target, FlatEnd{side * h, radius}, scale);
    };
    const double centre_side = disk.c.z() < 0.0 ? -1.0 : 1.0;
    double cap_first = 0.0;  // the side of the cap tried first, 0 for the wall
    bool beyond_cap = false;  // the disk lies wholly beyond that cap's plane
    for (const double side : {centre_side, -centre_side}) {
      const CapPlaneChord chord = capPlaneChord(disk, side, h);
      if (chord.crosses) {
        if (chord.nearestAxisWithin(radius)) {
          const Vec3 m = chord.nearestAxis();
          const Vec3 on_cap(m.x(), m.y(), side * h);
          return certifiedOrBound(0.0, 0.0, on_cap, on_cap, scale);
        }
        if (chord.least_at_chord) cap_first = side;
      } else if (side * disk.c.z() > h) {
        cap_first = side;
        beyond_cap = true;
      }
      if (cap_first != 0.0) break;
    }
    if (cap_first != 0.0) {
      const LeafToDisk cap = beyond_cap
                                 ? diskBeyondFlatEnd(disk, FlatEnd{cap_first * h, radius}, scale)
                                 : against_cap(cap_first);
      if (cap.exact) return cap;
    }
    const DiskShapeSolution wall = solveDiskCapsule(disk, radius, h);
    if (std::abs(wall.q.z()) <= h) return exactLeafOf(wall);
    const double wall_side = wall.q.z() < 0.0 ? -1.0 : 1.0;
    if (wall_side != cap_first) return against_cap(wall_side);
    return LeafToDisk{};
  }

  /// The directions among which the shortest separating translation lies
  /// (shortestSeparation adds the disk's normals and both signs), so the contact's
  /// depth is the exact penetration depth. The cylinder's support, h(-w) =
  /// radius |P_z w| + half_length |w_z| - ..., is kinked at w = +-z (its caps'
  /// normals) and on the circle w . z = 0 (its two caps tie). Away from both, one
  /// cap is the support and F is the disk-disk F of the disk against that cap:
  /// its candidates (docs/penetration_depth.md, section 2). On the circle F =
  /// h_disk(w) + radius, stationary where the disk's support is normal to the
  /// axis (section 7).
  template <typename Search>
  static void contactDirections(const CylinderTarget& target, const DiskInShape& disk,
                                Search* directions) {
    directions->push_back(Vec3::UnitZ());
    addEdgeLineCandidates(disk, Vec3::Zero(), Vec3::UnitZ(), directions, target.radius);
    for (const FlatEnd& end : target.flatEnds()) addFlatEndCandidates(disk, end, directions);
  }
};

}  // namespace

template <typename S>
struct DiskShapePair<fcl::Cylinder<S>>
    : GenericDiskShapePair<S, fcl::Cylinder<S>, CylinderTraits<S>> {};

}  // namespace internal
}  // namespace fcl_disk

FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::Cylinder)
