// DiskNarrowPhase: the narrowphase solver that FCL's mesh and octree collision
// traversals call at their leaves, answering with fcl_disk's exact solvers when
// the shape is a Disk. The hook runs those traversals only for requests with
// enable_cost, so that cost sources are FCL's; distance, and collision without
// cost, are fcl_disk's own traversals (src/mesh_distance.h,
// src/octree_distance.h, src/mesh_collision.h, src/octree_collision.h).
//
// FCL's traversal templates (BVHShapeCollider, OcTreeShapeCollide, ...;
// fcl/narrowphase/detail/) take the narrowphase solver as a template parameter
// and only call the members below on it. Instantiated with Shape = Disk<S> and
// this solver, they keep FCL's traversal, pruning, result and contact
// conventions (b1/b2 = triangle or cell id, world-frame points) while every
// leaf test is exact:
//   a triangle  diskShapeIntersect with fcl::TriangleP (src/pairs/disk_triangle.cpp);
//   an octree cell (FCL passes it as a Box and its pose) with fcl::Box
//               (src/pairs/disk_box.cpp).
// Bounding volumes of the disk in those traversals: include/fcl_disk/disk_bv.h.
//
// Conventions, as FCL's GJK solvers: points in the world frame; a collision
// normal is a unit vector from the first shape towards the second (FCL negates
// it where the mesh or octree is o1). Stateless, so one instance serves every
// thread.
#pragma once

#include <algorithm>
#include <vector>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/triangle_p.h>
#include <fcl/narrowphase/contact_point.h>

#include "fcl_disk/disk.h"
#include "fcl_disk/disk_shape_distance.h"

namespace fcl_disk {
namespace internal {

template <typename S_>
class DiskNarrowPhase {
 public:
  using S = S_;
  using Vector3 = fcl::Vector3<S>;
  using Transform3 = fcl::Transform3<S>;

  /// FCL's GJK warm start (ShapeShapeCollide calls these): the exact solvers
  /// run no GJK, so there is no guess to keep; the one reported is FCL's
  /// default, CollisionRequest's cached_gjk_guess (1, 0, 0).
  void enableCachedGuess(bool) const {}
  void setCachedGuess(const Vector3&) const {}
  Vector3 getCachedGuess() const { return Vector3::UnitX(); }

  /// Whether the disk meets the triangle (a, b, c) given in the world frame; if
  /// so and `contact_point` is given, FCL's single contact.
  bool shapeTriangleIntersect(const Disk<S>& disk, const Transform3& X_WD, const Vector3& a,
                              const Vector3& b, const Vector3& c, Vector3* contact_point,
                              S* penetration_depth, Vector3* normal) const {
    return shapeTriangleIntersect(disk, X_WD, a, b, c, Transform3::Identity(), contact_point,
                                  penetration_depth, normal);
  }

  /// As above, the triangle given in a frame M with pose X_WM.
  bool shapeTriangleIntersect(const Disk<S>& disk, const Transform3& X_WD, const Vector3& a,
                              const Vector3& b, const Vector3& c, const Transform3& X_WM,
                              Vector3* contact_point, S* penetration_depth,
                              Vector3* normal) const {
    DiskContact<S> contact;
    const bool wanted = contact_point != nullptr;
    if (!diskShapeIntersect(disk.radius, X_WD, fcl::TriangleP<S>(a, b, c), X_WM,
                            wanted ? &contact : nullptr)) {
      return false;
    }
    if (wanted) {
      *contact_point = contact.pos;
      if (penetration_depth) *penetration_depth = contact.penetration_depth;
      if (normal) *normal = contact.normal;
    }
    return true;
  }

  /// Whether the box meets the disk; if so and `contacts` is given, one contact
  /// whose normal points from the box towards the disk.
  bool shapeIntersect(const fcl::Box<S>& box, const Transform3& X_WB, const Disk<S>& disk,
                      const Transform3& X_WD,
                      std::vector<fcl::ContactPoint<S>>* contacts) const {
    DiskContact<S> contact;
    if (!diskShapeIntersect(disk.radius, X_WD, box, X_WB, contacts ? &contact : nullptr)) {
      return false;
    }
    if (contacts) {
      contacts->emplace_back(-contact.normal, contact.pos, contact.penetration_depth);
    }
    return true;
  }
};

}  // namespace internal
}  // namespace fcl_disk
