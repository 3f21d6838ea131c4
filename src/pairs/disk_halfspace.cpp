// Disk - fcl::Halfspace {x : n.x <= d} and fcl::Plane {x : n.x = d}, closed
// form: the disk's heights over the boundary plane span h0 +- r |n_xy| (h0 the
// centre's height, n_xy the plane normal's component in the disk's plane).
// docs/disk_shape_distance.md, section 4.
#include "../disk_shape_pair.h"

namespace fcl_disk {
namespace internal {
namespace {

/// The boundary plane in D: unit normal n and the disk centre's height h0 over it.
struct BoundaryInDisk {
  Vec3 n;
  double h0;
  double in_plane;  ///< |n_xy|: the disk's half-span of heights is r * in_plane.

  /// The disk point nearest along -n (lowest): -r n_xy / |n_xy|, or the centre
  /// when the disk is parallel to the plane (every point ties).
  Vec3 lowestPoint(double r) const {
    if (!(in_plane > 0.0)) return Vec3::Zero();
    return Vec3(-r * n.x() / in_plane, -r * n.y() / in_plane, 0.0);
  }
};

/// n, d of the shape, in its frame; valid if finite, n non-zero.
template <typename S>
bool isValidBoundary(const fcl::Vector3<S>& n, S d) {
  return n.allFinite() && n.squaredNorm() > S(0) && std::abs(d) <= kMaxDiskLength<S>;
}

template <typename S>
BoundaryInDisk boundaryInDisk(const fcl::Vector3<S>& n_S, S d, const fcl::Transform3<S>& X_WD,
                              const fcl::Transform3<S>& X_WS) {
  const PoseInDisk pose = PoseInDisk::of(X_WD, X_WS);
  const Vec3 n_local = n_S.template cast<double>();
  const double length = n_local.norm();
  const Vec3 n = pose.R * (n_local / length);
  // Boundary in D: {n.x = d / |n| + n.c}; the centre (origin) has height -that.
  const double h0 = -(double(d) / length + n.dot(pose.c));
  return BoundaryInDisk{n, h0, std::sqrt(n.x() * n.x() + n.y() * n.y())};
}

/// scale = r + |h0| (the shape's "origin" is the foot of the disk centre).
double boundaryScale(double r, const BoundaryInDisk& boundary) {
  return r + std::abs(boundary.h0);
}

template <typename S>
DiskShapeDistanceResult<S> fromDisk(const fcl::Transform3<S>& X_WD, const Vec3& p, const Vec3& q,
                                    double distance) {
  DiskShapeSolution solution;
  solution.p = p;
  solution.q = q;
  solution.distance = distance;
  solution.lower_bound = distance;  // the certificate at w = -n or +n is the closed form itself
  solution.intersecting = distance == 0.0;
  return toWorld(X_WD, solution);
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
    const BoundaryInDisk boundary = boundaryInDisk(halfspace.n, halfspace.d, X_WD, X_WS);
    const double r = double(radius);
    // The lowest disk point p is at height h0 - r |n_xy|: apart iff that is > 0.
    const Vec3 p = boundary.lowestPoint(r);
    const double height = boundary.h0 - r * boundary.in_plane;
    if (height <= 0.0) return fromDisk<S>(X_WD, p, p, 0.0);  // p lies in the halfspace
    return fromDisk<S>(X_WD, p, p - height * boundary.n, height);
  }

  /// Contact: pos the lowest disk point; normal -n, depth r |n_xy| - h0: moving
  /// the halfspace by that along -n separates it, and no shorter move does
  /// (the exact penetration depth).
  static bool intersect(S radius, const fcl::Transform3<S>& X_WD,
                        const fcl::Halfspace<S>& halfspace, const fcl::Transform3<S>& X_WS,
                        DiskContact<S>* contact) {
    if (!isValidDiskAndShapePose(radius, X_WD, X_WS) || !isValidBoundary(halfspace.n, halfspace.d)) {
      return false;
    }
    const BoundaryInDisk boundary = boundaryInDisk(halfspace.n, halfspace.d, X_WD, X_WS);
    const double r = double(radius);
    const double height = boundary.h0 - r * boundary.in_plane;
    if (height > kShapeTouchingTolerance * boundaryScale(r, boundary)) return false;
    if (contact) {
      const Mat3 R_WD = X_WD.linear().template cast<double>();
      contact->pos = (X_WD.translation().template cast<double>() + R_WD * boundary.lowestPoint(r))
                         .template cast<S>();
      contact->normal = (-(R_WD * boundary.n)).template cast<S>();
      contact->penetration_depth = S(std::max(-height, 0.0));
    }
    return true;
  }
};

template <typename S>
struct DiskShapePair<fcl::Plane<S>> {
  /// The nearest pair, or a common point: the point of the disk on the plane
  /// nearest its centre (on the chord's foot), the centre itself when parallel.
  static void solve(double r, const BoundaryInDisk& boundary, Vec3* p, Vec3* q, double* distance) {
    const double clearance = std::abs(boundary.h0) - r * boundary.in_plane;
    if (clearance <= 0.0) {
      const double foot = boundary.in_plane > 0.0 ? boundary.h0 / (boundary.in_plane * boundary.in_plane) : 0.0;
      *p = *q = Vec3(-foot * boundary.n.x(), -foot * boundary.n.y(), 0.0);
      *distance = 0.0;
      return;
    }
    // The rim point towards the plane, and its foot on the plane.
    const Vec3 lowest = boundary.lowestPoint(r);
    *p = boundary.h0 > 0.0 ? lowest : Vec3(-lowest);
    const double side = boundary.h0 > 0.0 ? 1.0 : -1.0;
    *q = *p - side * clearance * boundary.n;
    *distance = clearance;
  }

  static DiskShapeDistanceResult<S> distance(S radius, const fcl::Transform3<S>& X_WD,
                                             const fcl::Plane<S>& plane,
                                             const fcl::Transform3<S>& X_WS) {
    if (!isValidDiskAndShapePose(radius, X_WD, X_WS) || !isValidBoundary(plane.n, plane.d)) {
      return nanDiskShapeResult<S>();
    }
    Vec3 p, q;
    double distance;
    solve(double(radius), boundaryInDisk(plane.n, plane.d, X_WD, X_WS), &p, &q, &distance);
    return fromDisk<S>(X_WD, p, q, distance);
  }

  /// Contact: pos the common point; the plane moved along +n past the disk's
  /// highest point or along -n past its lowest, whichever is shorter.
  static bool intersect(S radius, const fcl::Transform3<S>& X_WD, const fcl::Plane<S>& plane,
                        const fcl::Transform3<S>& X_WS, DiskContact<S>* contact) {
    if (!isValidDiskAndShapePose(radius, X_WD, X_WS) || !isValidBoundary(plane.n, plane.d)) {
      return false;
    }
    const BoundaryInDisk boundary = boundaryInDisk(plane.n, plane.d, X_WD, X_WS);
    const double r = double(radius);
    Vec3 p, q;
    double distance;
    solve(r, boundary, &p, &q, &distance);
    if (distance > kShapeTouchingTolerance * boundaryScale(r, boundary)) return false;
    if (contact) {
      const Mat3 R_WD = X_WD.linear().template cast<double>();
      const double above = boundary.h0 + r * boundary.in_plane;   // move by this along +n
      const double below = r * boundary.in_plane - boundary.h0;   // or this along -n
      const bool up = above <= below;
      contact->pos = (X_WD.translation().template cast<double>() + R_WD * p).template cast<S>();
      contact->normal = ((up ? 1.0 : -1.0) * (R_WD * boundary.n)).template cast<S>();
      contact->penetration_depth = S(std::max(up ? above : below, 0.0));
    }
    return true;
  }
};

}  // namespace internal
}  // namespace fcl_disk

FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::Halfspace)
FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::Plane)
