// Exact distance and intersection between a disk and an FCL primitive, certified by
// convex duality. Derivation and notation: docs/disk_shape_distance.md.
#pragma once

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/plane.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>

#include <fcl_disk/disk_intersection.h>
#include <fcl_disk/disk_pair.h>
#include <fcl_disk/disk_penetration.h>

namespace fcl_disk {

/// Distance between a disk and another shape, and a pair of nearest points.
template <typename S>
struct DiskShapeDistanceResult {
  S distance{0};  ///< |p_W_shape - p_W_disk| >= 0; 0 when they intersect.
  fcl::Vector3<S> p_W_disk{fcl::Vector3<S>::Zero()};   ///< point of the disk, world frame.
  fcl::Vector3<S> p_W_shape{fcl::Vector3<S>::Zero()};  ///< point of the shape, world frame.
  /// A certified lower bound on the true distance (the duality certificate,
  /// docs/disk_shape_distance.md section 2): lower_bound <= d_true <= distance up
  /// to rounding, so certifiedGap() is an error bar the caller can check.
  S lower_bound{0};
  int iterations{0};  ///< iterations of the generic solver (0 for closed forms).

  /// distance - lower_bound: how far the returned distance can exceed the true one.
  S certifiedGap() const { return distance - lower_bound; }
};

/// Exact distance between the disk of radius `radius` with pose X_WD and `shape`
/// with pose X_WS, for Shape one of fcl::Sphere, Box, Capsule, Cylinder, Cone,
/// Ellipsoid, Convex, Halfspace, Plane, TriangleP (each pair lives in
/// `src/pairs/disk_<shape>.cpp`).
///
/// Frames: the disk is centred at the origin of its frame D, in D's XY plane,
/// normal +Z; the shape is FCL's, in its frame S (fcl::Cylinder, Cone, Capsule
/// along Z, centred; a Cone's apex at +lz/2; a Halfspace is {x : n.x <= d}, a
/// Plane {x : n.x = d}; a TriangleP is its three vertices, a flat closed
/// triangle). Points are returned in the world frame W. Units: the caller's.
/// All arithmetic is in double, in the disk's frame relative to its centre.
///
/// Scale: scale = radius + R_S + |c_D - c_S|, where R_S is the shape's bounding
/// radius about its frame origin c_S (for Halfspace and Plane, R_S = 0 and c_S
/// is the foot of the disk centre on the boundary plane).
///
/// Guarantee (double): |distance - d_true| <= 1e-12 * scale for Sphere,
/// Halfspace, Plane (closed forms) and for Box, Capsule, Cylinder, Cone,
/// TriangleP, Ellipsoid, Convex (the generic solver, docs section 3): both
/// points lie on their shapes to the same bound, and
/// |p_W_shape - p_W_disk| == distance up to rounding. lower_bound is the
/// certificate; certifiedGap() <= 1e-12 * scale on converged answers and an
/// honest, larger error bar where the iteration stops at its cap. A disk
/// nearly parallel to a cylinder's cap or a cone's base whose rim crosses the
/// end's rim in projection (the optimum at a corner of the lens where they
/// overlap) is answered by the disk-disk solver's lens corners against that end
/// (docs section 3, "Flat ends").
/// Float: inputs are promoted to double and results rounded to float.
///
/// Overlap: distance 0, p_W_disk == p_W_shape == a point of both shapes
/// (unsigned and signed alike; penetration depth is not computed here). Sets
/// closer than 1e-13 * scale count as touching (a pair built touching in one
/// frame touches only to rounding in another): distance 0, the disk's point as
/// the common point, as diskShapeIntersect() decides. Where the iteration
/// stops next to a grazing overlap without proving either answer, the shapes
/// of kExactDiskShapePenetration take the shortest separation over their
/// penetration candidates (the penetration depth, whatever its sign): deeper
/// than 1e-7 * scale, an overlap, distance 0 at the iteration's disk point.
/// Ties (parallel faces, a segment parallel to the disk): the pair the
/// iteration reaches, deterministic for a given input.
///
/// Invalid input: a radius rejected by isValidDiskRadius(), a disk pose rejected
/// by isValidDiskPose(), a shape pose with a NaN or infinite entry or a rotation
/// further than kRotationDefectTolerance from orthonormal, or a shape with NaN,
/// infinite or negative dimensions gives NaN distance, lower_bound and points.
/// Degenerate but valid shapes (a zero-size box or sphere, a zero-length capsule
/// or cylinder, a flat Convex, a zero-area triangle) are answered exactly as the
/// point, segment or polygon they are.
template <typename S, typename Shape>
DiskShapeDistanceResult<S> diskShapeDistance(S radius, const fcl::Transform3<S>& X_WD,
                                             const Shape& shape, const fcl::Transform3<S>& X_WS);

/// Whether the disk and `shape` share a point (closed sets: touching counts), and
/// if so a contact. Frames, shapes and invalid input as diskShapeDistance (invalid
/// input: false). Decision tolerance: closer than 1e-13 * scale counts as touching
/// (for the Ellipsoid, whose iteration can stop next to a grazing contact with
/// the gap open, within its distance's 1e-12 * scale of that).
///
/// Contact convention (FCL's for fcl::Contact, the disk as object 1): `pos` is a
/// point of both shapes (for an overlap the iteration left open and the
/// penetration candidates decided, see diskShapeDistance, the midpoint of its
/// nearest points, within half its residual of each); `normal` is a unit
/// vector from the disk towards the shape, and translating the shape by
/// penetration_depth * normal separates them:
/// the smallest such translation among the disk's normal and the shape's own
/// candidate directions (docs/disk_shape_distance.md section 5). It is an upper
/// bound on the penetration depth, exact for every shape but the Ellipsoid
/// (kExactDiskShapePenetration).
template <typename S, typename Shape>
bool diskShapeIntersect(S radius, const fcl::Transform3<S>& X_WD, const Shape& shape,
                        const fcl::Transform3<S>& X_WS, DiskContact<S>* contact = nullptr);

/// The shapes whose diskShapeIntersect() contact is the exact penetration depth
/// and direction, so that signedDiskShapeDistance() exists for them. Sphere: the
/// shortest way out is straight away from the disk point nearest the centre
/// (depth radius - that distance; along the disk's normal when the centre lies
/// on the disk); Halfspace: along its outward normal reversed; Plane: along
/// +-its normal (docs/disk_shape_distance.md, section 5); Capsule: among the
/// disk's normals, its ends' nearest and farthest rim points, and the rim
/// points where the disk's support is normal to the axis; Cylinder: among the
/// disk-disk candidates against each cap, the axis and those rim points; Cone:
/// the apex's, the base's and the side's (where the disk's support is normal
/// to a generator's plane) candidates; Box,
/// TriangleP and Convex (a polytope whose faces bound the hull of its
/// vertices): among the face normals, the vertices' nearest and farthest rim
/// points, and the rim points where the disk's support is normal to an edge
/// line (docs/penetration_depth.md, section 7).
template <typename Shape>
constexpr bool kExactDiskShapePenetration = false;
/// @cond
template <typename S>
constexpr bool kExactDiskShapePenetration<fcl::Sphere<S>> = true;
template <typename S>
constexpr bool kExactDiskShapePenetration<fcl::Halfspace<S>> = true;
template <typename S>
constexpr bool kExactDiskShapePenetration<fcl::Plane<S>> = true;
template <typename S>
constexpr bool kExactDiskShapePenetration<fcl::Capsule<S>> = true;
template <typename S>
constexpr bool kExactDiskShapePenetration<fcl::Cylinder<S>> = true;
template <typename S>
constexpr bool kExactDiskShapePenetration<fcl::Cone<S>> = true;
template <typename S>
constexpr bool kExactDiskShapePenetration<fcl::Box<S>> = true;
template <typename S>
constexpr bool kExactDiskShapePenetration<fcl::TriangleP<S>> = true;
template <typename S>
constexpr bool kExactDiskShapePenetration<fcl::Convex<S>> = true;
/// @endcond

/// @cond
namespace detail {
/// The signed answer of a disk and a kExactDiskShapePenetration shape that
/// intersect, from their diskShapeIntersect() contact (the disk as object 1):
/// minus the depth, its direction, the disk's support point along it and the
/// shape's point the depth behind it (signedDiskShapeDistance, the hook).
template <typename S>
DiskSignedDistanceResult<S> penetrationFromContact(S radius, const fcl::Transform3<S>& X_WD,
                                                   const DiskContact<S>& contact) {
  DiskSignedDistanceResult<S> result;
  const fcl::Vector3<S>& w = contact.normal;
  // The disk's support point along w: on its rim, unless w is within
  // kAlongNormal rad of its normal, when (up to that angle times the radius)
  // every point ties and the contact point, a point of the disk, is one.
  constexpr S kAlongNormal = S(1e-9);
  const fcl::Matrix3<S> R = X_WD.linear();
  const S a = R.col(0).dot(w), b = R.col(1).dot(w);
  const S in_plane = std::sqrt(a * a + b * b);
  result.p_W1 = in_plane > kAlongNormal ? fcl::Vector3<S>(X_WD.translation() +
                                                     (radius / in_plane) * (a * R.col(0) + b * R.col(1)))
                                   : contact.pos;
  result.signed_distance = -contact.penetration_depth;
  result.direction = w;
  result.p_W2 = result.p_W1 - contact.penetration_depth * w;
  return result;
}
}  // namespace detail
/// @endcond

/// Signed distance between the disk and `shape` (kExactDiskShapePenetration
/// shapes), with the disk as object 1: diskShapeDistance() when apart
/// (direction = (p_W2 - p_W1) / d); minus the exact penetration depth when they
/// share a point, with `direction` the unit vector from the disk towards the
/// shape along which translating the shape by the depth separates them (the
/// gradient of the signed distance with respect to the shape's translation),
/// p_W1 the disk's point deepest along it and p_W2 = p_W1 - depth * direction
/// the shape's point deepest along -direction (FCL's EPA convention).
/// Frames, units, scale and invalid input (NaN result) as diskShapeDistance.
template <typename S, typename Shape>
DiskSignedDistanceResult<S> signedDiskShapeDistance(S radius, const fcl::Transform3<S>& X_WD,
                                                    const Shape& shape,
                                                    const fcl::Transform3<S>& X_WS) {
  static_assert(kExactDiskShapePenetration<Shape>,
                "signedDiskShapeDistance: the penetration depth is exact for Sphere, "
                "Box, Capsule, Cylinder, Cone, Convex, Halfspace, Plane and TriangleP only");
  const S nan = std::numeric_limits<S>::quiet_NaN();
  DiskSignedDistanceResult<S> result;
  const DiskShapeDistanceResult<S> apart = diskShapeDistance(radius, X_WD, shape, X_WS);
  DiskContact<S> contact;
  if (std::isnan(apart.distance)) {
    result.signed_distance = nan;
    result.p_W1.setConstant(nan);
    result.p_W2.setConstant(nan);
    result.direction.setConstant(nan);
    return result;
  }
  if (apart.distance > 0 || !diskShapeIntersect(radius, X_WD, shape, X_WS, &contact)) {
    result.signed_distance = apart.distance;
    result.p_W1 = apart.p_W_disk;
    result.p_W2 = apart.p_W_shape;
    const fcl::Vector3<S> gap = apart.p_W_shape - apart.p_W_disk;
    if (gap.norm() > 0) result.direction = gap.normalized();
    return result;
  }
  return detail::penetrationFromContact(radius, X_WD, contact);
}

}  // namespace fcl_disk
