// Internal: the contact a collision traversal adds for a leaf (a triangle, a
// cell) that meets the disk, as FCL's shape-mesh and shape-octree traversals
// add it (src/mesh_collision.h, src/octree_collision.h).
#pragma once

#include <fcl/narrowphase/collision_request.h>
#include <fcl/narrowphase/collision_result.h>

#include <algorithm>
#include <cstdint>

#include "disk_shape_solver.h"

namespace fcl_disk {
namespace internal {

/// Runs the leaf's intersection test `meets(FrameContact*)` (the contact asked
/// for only with enable_contact) and, if the leaf meets the disk and there is
/// room, adds FCL's contact: o1 the environment, o2 the disk, b1 `leaf_id`, b2
/// NONE; with enable_contact, pos the test's point plus `leaf_origin` (the
/// leaf's frame's origin in the environment's), the normal the test's
/// separation direction negated, depth >= 0. Returns whether the request is
/// satisfied after a meeting leaf, false for one that does not meet the disk.
template <typename S, typename Meets>
bool addLeafContact(Meets&& meets, const Vec3& leaf_origin,
                    const fcl::CollisionGeometry<S>& environment,
                    const fcl::CollisionGeometry<S>& disk, std::intptr_t leaf_id,
                    const fcl::CollisionRequest<S>& request, fcl::CollisionResult<S>& result) {
  using Contact = fcl::Contact<S>;
  FrameContact contact;
  if (!meets(request.enable_contact ? &contact : nullptr)) return false;
  if (result.numContacts() < request.num_max_contacts) {
    if (!request.enable_contact) {
      result.addContact(Contact(&environment, &disk, leaf_id, Contact::NONE));
    } else {
      result.addContact(Contact(&environment, &disk, leaf_id, Contact::NONE,
                                (leaf_origin + contact.pos).template cast<S>(),
                                (-contact.separation.direction).template cast<S>(),
                                S(std::max(contact.separation.depth, 0.0))));
    }
  }
  return request.isSatisfied(result);
}

}  // namespace internal
}  // namespace fcl_disk
