// Disk - fcl::Halfspace {y : n.y <= d} and fcl::Plane {y : n.y = d}, closed
// form: the disk's heights over the boundary plane span h0 +- r |P n| (h0 the
// centre's height, P n the plane normal's component in the disk's plane).
// Computed in the frame with the shape's origin and the world's axes
// (diskAtShapeOrigin): one product turns the boundary's normal into it, where
// the shape's frame would take three to turn the disk and two to turn the
// answer back. docs/disk_shape_distance.md, section 4.
#include "../disk_shape_pair.h"

namespace fcl_disk {
namespace internal {
namespace {

/// The boundary plane seen from the disk (diskAtShapeOrigin's frame): unit
/// normal n, the disk centre's height h0 over the plane, and P n.
struct BoundaryOfDisk {
  Vec3 n;
  double h0;
  Vec3 in_plane_normal;  ///< P n = (u.n) u + (v.n) v.
  double in_plane;       ///< |P n|: the disk's half-span of heights is r * in_plane.

  /// The disk point lowest along n: c - r P n / |P n|, or the centre when the
  /// disk is parallel to the plane (every point ties).
  Vec3 lowestPoint(const DiskInShape& disk) const {
    if (!(in_plane > 0.0)) return disk.c;
    return disk.c - (disk.r / in_plane) * in_plane_normal;
  }
};

/// A normal whose squared length lies within [this, 1 / this] (every normal
/// FCL's constructors leave: they normalise it) is normalised by one reciprocal
/// square root, its square and reciprocal staying normal doubles; others, down
/// to subnormal components, are first scaled by their largest component.
constexpr double kPlainNormalSquaredLength = 1e-200;

/// n, d of the shape; valid if finite, n non-zero (any magnitude: FCL's own
/// constructor normalises it, and so does boundaryOfDisk).
template <typename S>
bool isValidBoundary(const fcl::Vector3<S>& n, S d) {
  return n.allFinite() && (n.array() != S(0)).any() && std::abs(d) <= kMaxDiskLength<S>;
}

/// n_S, d: the shape's (shape frame); X_WS its pose; `disk` from diskAtShapeOrigin.
/// Always inlined, as diskAtShapeOrigin and closedForm below: the pair takes a
/// few hundred instructions, and calls would pass their structs through memory.
template <typename S>
[[gnu::always_inline]] inline BoundaryOfDisk boundaryOfDisk(const fcl::Vector3<S>& n_S, S d,
                                                            const fcl::Transform3<S>& X_WS,
                                                            const DiskInShape& disk) {
  const Vec3 n_raw = n_S.template cast<double>();
  const double squared_length = n_raw.squaredNorm();
  Vec3 n_unit;
  double offset;  // d / |n|: the plane's distance from the shape's origin
  if (squared_length >= kPlainNormalSquaredLength &&
      squared_length <= 1.0 / kPlainNormalSquaredLength) {
    const double inverse_length = 1.0 / std::sqrt(squared_length);
    n_unit = inverse_length * n_raw;
    offset = double(d) * inverse_length;
  } else {
    // Scaled by its largest component first: a normal of tiny (even subnormal)
    // components still normalises to a unit vector.
    const double largest = n_raw.cwiseAbs().maxCoeff();
    const Vec3 n_scaled = n_raw / largest;
    const double scaled_length = n_scaled.norm();
    n_unit = n_scaled / scaled_length;
    offset = double(d) / (largest * scaled_length);
  }
  const Vec3 n = X_WS.linear().template cast<double>() * n_unit;
  const Vec2 planar = disk.inPlane(n);
  return BoundaryOfDisk{n, n.dot(disk.c) - offset, planar.x() * disk.u + planar.y() * disk.v,
                        planar.norm()};
}

/// scale = r + |h0| (the shape's "origin" is the foot of the disk centre).
double boundaryScale(const DiskInShape& disk, const BoundaryOfDisk& boundary) {
  return disk.r + std::abs(boundary.h0);
}

/// The result for points p, q (diskAtShapeOrigin's frame) at `distance`, which
/// the closed form proves: the certificate at w = -+n equals it.
template <typename S>
[[gnu::always_inline]] inline DiskShapeDistanceResult<S> closedForm(
    const fcl::Transform3<S>& X_WS, const Vec3& p, const Vec3& q, double distance) {
  DiskShapeSolution solution;
  solution.p = p;
  solution.q = q;
  solution.distance = solution.lower_bound = distance;
  return toWorldFromShapeOrigin(X_WS, solution);
}

}  // namespace

template <typename S>
struct DiskShapePair<fcl::Halfspace<S>> {
  static DiskShapeDistanceResult<S> distance(S radius, const fcl::Transform3<S>& X_WD,
                                             const fcl::Halfspace<S>& halfspace,
                                             const fcl::Transform3<S>& X_WS) {
    if (!isValidDiskAndShapePose(radius, X_WD, X_WS) || !isValidBoundary(halfspace.n, halfspace.d)) {
      return nanDiskShapeResult<S>();
    }
    const DiskInShape disk = diskAtShapeOrigin(radius, X_WD, X_WS);
    const BoundaryOfDisk boundary = boundaryOfDisk(halfspace.n, halfspace.d, X_WS, disk);
    // The lowest disk point p is at height h0 - r |P n|: apart iff that is > 0.
    const Vec3 p = boundary.lowestPoint(disk);
    const double height = boundary.h0 - disk.r * boundary.in_plane;
    if (height <= 0.0) return closedForm<S>(X_WS, p, p, 0.0);  // p lies in the halfspace
    return closedForm<S>(X_WS, p, p - height * boundary.n, height);
  }

  /// Contact: pos the lowest disk point; normal -n, depth r |P n| - h0: moving
  /// the halfspace by that along -n separates it, and no shorter move does
  /// (the exact penetration depth).
  static bool intersect(S radius, const fcl::Transform3<S>& X_WD,
                        const fcl::Halfspace<S>& halfspace, const fcl::Transform3<S>& X_WS,
                        DiskContact<S>* contact) {
    if (!isValidDiskAndShapePose(radius, X_WD, X_WS) || !isValidBoundary(halfspace.n, halfspace.d)) {
      return false;
    }
    const DiskInShape disk = diskAtShapeOrigin(radius, X_WD, X_WS);
    const BoundaryOfDisk boundary = boundaryOfDisk(halfspace.n, halfspace.d, X_WS, disk);
    const double height = boundary.h0 - disk.r * boundary.in_plane;
    if (height > kShapeTouchingTolerance * boundaryScale(disk, boundary)) return false;
    if (contact) {
      contact->pos = fromShapeOrigin(X_WS, boundary.lowestPoint(disk)).template cast<S>();
      contact->normal = (-boundary.n).template cast<S>();
      contact->penetration_depth = S(std::max(-height, 0.0));
    }
    return true;
  }
};

template <typename S>
struct DiskShapePair<fcl::Plane<S>> {
  /// The nearest pair, or a common point: the point of the disk on the plane
  /// nearest its centre (the foot of the chord), the centre itself when parallel.
  static void solve(const DiskInShape& disk, const BoundaryOfDisk& boundary, Vec3* p, Vec3* q,
                    double* distance) {
    const double clearance = std::abs(boundary.h0) - disk.r * boundary.in_plane;
    if (clearance <= 0.0) {
      const double foot =
          boundary.in_plane > 0.0 ? boundary.h0 / (boundary.in_plane * boundary.in_plane) : 0.0;
      *p = *q = disk.c - foot * boundary.in_plane_normal;
      *distance = 0.0;
      return;
    }
    // The rim point towards the plane, and its foot on the plane.
    const double side = boundary.h0 > 0.0 ? 1.0 : -1.0;
    const Vec3 towards = boundary.in_plane > 0.0
                             ? Vec3(disk.c - side * (disk.r / boundary.in_plane) *
                                                 boundary.in_plane_normal)
                             : disk.c;
    *p = towards;
    *q = towards - side * clearance * boundary.n;
    *distance = clearance;
  }

  static DiskShapeDistanceResult<S> distance(S radius, const fcl::Transform3<S>& X_WD,
                                             const fcl::Plane<S>& plane,
                                             const fcl::Transform3<S>& X_WS) {
    if (!isValidDiskAndShapePose(radius, X_WD, X_WS) || !isValidBoundary(plane.n, plane.d)) {
      return nanDiskShapeResult<S>();
    }
    const DiskInShape disk = diskAtShapeOrigin(radius, X_WD, X_WS);
    Vec3 p, q;
    double distance;
    solve(disk, boundaryOfDisk(plane.n, plane.d, X_WS, disk), &p, &q, &distance);
    return closedForm<S>(X_WS, p, q, distance);
  }

  /// Contact: pos the common point; the plane moved along +n past the disk's
  /// highest point or along -n past its lowest, whichever is shorter.
  static bool intersect(S radius, const fcl::Transform3<S>& X_WD, const fcl::Plane<S>& plane,
                        const fcl::Transform3<S>& X_WS, DiskContact<S>* contact) {
    if (!isValidDiskAndShapePose(radius, X_WD, X_WS) || !isValidBoundary(plane.n, plane.d)) {
      return false;
    }
    const DiskInShape disk = diskAtShapeOrigin(radius, X_WD, X_WS);
    const BoundaryOfDisk boundary = boundaryOfDisk(plane.n, plane.d, X_WS, disk);
    Vec3 p, q;
    double distance;
    solve(disk, boundary, &p, &q, &distance);
    if (distance > kShapeTouchingTolerance * boundaryScale(disk, boundary)) return false;
    if (contact) {
      const double above = boundary.h0 + disk.r * boundary.in_plane;  // move by this along +n
      const double below = disk.r * boundary.in_plane - boundary.h0;  // or this along -n
      const bool up = above <= below;
      contact->pos = fromShapeOrigin(X_WS, p).template cast<S>();
      contact->normal = ((up ? 1.0 : -1.0) * boundary.n).template cast<S>();
      contact->penetration_depth = S(std::max(up ? above : below, 0.0));
    }
    return true;
  }
};

}  // namespace internal
}  // namespace fcl_disk

FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::Halfspace)
FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::Plane)
