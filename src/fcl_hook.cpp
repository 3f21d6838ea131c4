// The one place that wires disks into FCL's dispatch. Read top to bottom:
//   1. what a disk-disk entry does (distance, collision);
//   1b. the table of the other shapes a Disk is answered against by fcl_disk,
//      and what such an entry does;
//   1c. the table of meshes and octrees: fcl_disk's distance and collision
//      traversals (FCL's, with fcl_disk's narrowphase solver, for cost sources);
//   2. the wrappers that sit in FCL's GEOM_CYLINDER row and column and forward
//      every pair fcl_disk does not answer to FCL's original function;
//   3. installing them into the tables user code sees, and into the private
//      copies inside libfcl.so (docs/fcl_hook.md explains why both);
//   4. a probe that proves the hook answers plain fcl::distance / fcl::collide;
//   5. FCL's object-level entry points, with a shortcut for pairs of Disks.
#include "fcl_disk/registration.h"

#include <dlfcn.h>
#include <link.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <limits>
#include <type_traits>
#include <typeinfo>
#include <utility>
#include <vector>

#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/utility.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include "fcl_disk/almohamad_selim.h"
#include "fcl_disk/disk.h"
#include "fcl_disk/disk_intersection.h"
#include "fcl_disk/disk_penetration.h"
#include "fcl_disk/disk_shape_distance.h"
#include "fcl_disk/exact_distance.h"
#include "fcl_disk/fcl_templates.h"
#include "disk_narrowphase.h"
#include "disk_penetration_candidates.h"
#include "mesh_distance.h"
#include "mesh_collision.h"
#include "octree_collision.h"
#include "octree_distance.h"

namespace fcl_disk {
namespace {

using fcl::CollisionGeometry;
using fcl::Transform3;

std::atomic<DiskDistanceMethod> g_method{DiskDistanceMethod::exact};

// Counts disk-disk answers on this thread; the probe uses it to prove that a
// query reached fcl_disk rather than FCL's GJK. Initial-exec TLS: a plain
// %fs-relative increment instead of a __tls_get_addr call on every query (a
// shared library's default model). When libfcl_disk is dlopen'ed (a plugin's
// dependency), glibc serves these 8 bytes from its static TLS surplus; the
// consumer test's dlopen cases exercise that.
__attribute__((tls_model("initial-exec"))) thread_local std::uint64_t t_disk_answers = 0;

// ---------------------------------------------------------------------------
// 1. Disk-disk entries.

/// The Disk behind a geometry that reached a GEOM_CYLINDER slot, or nullptr for a
/// real cylinder. lz != 0 rejects real cylinders before RTTI; Disk is final, so
/// an exact typeid comparison suffices (a few ns, against ~6 ns per dynamic_cast).
template <typename S>
const Disk<S>* asDisk(const CollisionGeometry<S>* geometry) {
  if (static_cast<const fcl::Cylinder<S>*>(geometry)->lz != S(0)) return nullptr;
  if (typeid(*geometry) != typeid(Disk<S>)) return nullptr;
  return static_cast<const Disk<S>*>(geometry);
}

/// The Disk behind any geometry when its type_info is the one libfcl_disk sees,
/// else nullptr. Cheaper than asDisk on the geometries that are not Disks, which
/// is what every other pair pays for the shortcut: one load more than the type
/// query FCL makes anyway, where type_info::operator== would call strcmp on the
/// type names (a template's type_info may have copies). A Disk whose type_info is
/// another copy (code in a dlopen()ed plugin that links libfcl_disk privately)
/// is missed here and found by asDisk in FCL's tables.
template <typename S>
const Disk<S>* asDiskOfThisLibrary(const CollisionGeometry<S>* geometry) {
  if (&typeid(*geometry) != &typeid(Disk<S>)) return nullptr;
  return static_cast<const Disk<S>*>(geometry);
}

/// The answer for input that describes no disk pair: NaN, never a finite
/// made-up distance.
template <typename S>
S answerNoDistance(const CollisionGeometry<S>* o1, const CollisionGeometry<S>* o2,
                   fcl::DistanceResult<S>& result) {
  // Written directly: DistanceResult::update() keeps the old value for NaN.
  const S nan = std::numeric_limits<S>::quiet_NaN();
  result.min_distance = nan;
  result.o1 = o1;
  result.o2 = o2;
  result.b1 = result.b2 = fcl::DistanceResult<S>::NONE;
  result.nearest_points[0].setConstant(nan);
  result.nearest_points[1].setConstant(nan);
  return nan;
}

// FCL's DistanceRequest::isSatisfied and DistanceResult::update (the overload
// with nearest points), written out. libfcl exports their double
// instantiations, so calling them costs two round trips through the PLT per
// query: 4 ns of a disk query's ~25 ns dispatch cost (bench_disk_distance,
// docs/performance.md); written out they cost nothing measurable.
// test_hook's ResultConventionsMatchFcls checks they behave as FCL's.

/// isSatisfied: a result already at distance <= 0 (contact) cannot improve.
template <typename S>
bool distanceIsSettled(const fcl::DistanceResult<S>& result) {
  return result.min_distance <= 0;
}

/// update: the result keeps the nearer of what it holds and this pair.
template <typename S>
void keepIfNearer(fcl::DistanceResult<S>& result, S distance, const CollisionGeometry<S>* o1,
                  const CollisionGeometry<S>* o2, const fcl::Vector3<S>& p1,
                  const fcl::Vector3<S>& p2) {
  if (!(result.min_distance > distance)) return;
  result.min_distance = distance;
  result.o1 = o1;
  result.o2 = o2;
  result.b1 = result.b2 = fcl::DistanceResult<S>::NONE;
  result.nearest_points[0] = p1;
  result.nearest_points[1] = p2;
}

/// A pair proven no nearer than the result's distance by more than this many
/// scene sizes is not solved: beyond every rounding the bound and the solver's
/// distance carry (float's half ulp of the answer, 6e-8; in double a few eps).
constexpr double kNoNearerMargin = 1e-6;

/// Whether the valid disk pair (as exactDiskDistance validates it) lies
/// farther apart than `held`, a positive distance the result already holds (a
/// broadphase manager's distance callback keeps one result over its candidate
/// pairs, whose boxes only bound them), by more than kNoNearerMargin * (r1 +
/// r2 + |w|), w = c2 - c1, by the certificate along w (centreLineBound,
/// src/pair_in_frame1.h): then its answer could not replace the one held.
/// Invalid pairs are left to the solver, which answers them with NaN.
template <typename S>
bool diskPairNoNearerThan(S r1, const Transform3<S>& X_W1, S r2, const Transform3<S>& X_W2,
                          S held) {
  // A fresh result holds numeric_limits<S>::max(): nothing to beat, no check.
  if (!(held > 0 && held < std::numeric_limits<S>::max())) return false;
  if (!internal::checkDiskPair(r1, X_W1, r2, X_W2).valid) return false;
  const internal::CentreLineBound bound = internal::centreLineBound(r1, X_W1, r2, X_W2);
  return bound.exceeds(double(held) + kNoNearerMargin * bound.scale);
}

/// Whether a signed answer may be minus this depth. FCL's entry, for the indep
/// solver, answers a negative distance by asking collide() for a contact deeper
/// than numeric_limits<S>::min() and asserts that one exists: a depth not above
/// that (min() itself, a subnormal, 0) is reported as touching, distance 0.
template <typename S>
bool isReportableDepth(S depth) {
  return depth > std::numeric_limits<S>::min();
}

template <typename S>
S answerDiskDistance(const Disk<S>& disk1, const Transform3<S>& X_W1, const Disk<S>& disk2,
                     const Transform3<S>& X_W2, const fcl::DistanceRequest<S>& request,
                     fcl::DistanceResult<S>& result) {
  // Same early exit as FCL's ShapeShapeDistance.
  if (distanceIsSettled(result)) return result.min_distance;
  ++t_disk_answers;
  if (diskPairNoNearerThan(disk1.radius, X_W1, disk2.radius, X_W2, result.min_distance)) {
    return result.min_distance;
  }
  const bool exact =
      g_method.load(std::memory_order_relaxed) != DiskDistanceMethod::almohamad_selim;
  const DiskDistanceResult<S> answer =
      exact ? exactDiskDistance(disk1.radius, X_W1, disk2.radius, X_W2)
            : almohamadSelimDiskDistance(disk1.radius, X_W1, disk2.radius, X_W2);
  if (std::isnan(answer.distance)) return answerNoDistance<S>(&disk1, &disk2, result);
  if (request.enable_signed_distance && !(answer.distance > 0)) {
    // Overlap, signed: minus the penetration depth, with the deepest points
    // (p_W1 - p_W2 = PD * direction), as FCL's EPA reports them. Decided as
    // intersectDisks, and so collide(), decides: FCL's entry, for the indep
    // solver, re-asks collide() for a contact whenever the answer is negative.
    // The exact solver's `intersecting` is that decision (the same test on
    // the same pair), so it is not taken again.
    std::optional<DiskSignedDistanceResult<S>> penetration;
    if (exact && answer.feature == DiskPairFeature::intersecting) {
      penetration = internal::penetrationOfIntersecting(disk1.radius, X_W1, disk2.radius, X_W2);
    } else if (intersectDisks(disk1.radius, X_W1, disk2.radius, X_W2)) {
      penetration = diskPenetration(disk1.radius, X_W1, disk2.radius, X_W2);
    }
    if (penetration && isReportableDepth(-penetration->signed_distance)) {
      keepIfNearer(result, penetration->signed_distance, &disk1, &disk2, penetration->p_W1,
                   penetration->p_W2);
      return result.min_distance;
    }
  }
  // Overlap, unsigned: distance 0 with a common point as both nearest points.
  keepIfNearer(result, answer.distance, &disk1, &disk2, answer.p_W1, answer.p_W2);
  return result.min_distance;  // as FCL's ShapeShapeDistance: the result's minimum
}

/// FCL's shape-pair collision (ShapeCollisionTraversalNode::leafTesting), with
/// `intersect(&contact)` deciding the pair: between occupied shapes, a contact
/// when requested and room is left, and a cost source from the overlap of the
/// AABBs (each shape's computeBV: a Disk's is its tight box); between shapes
/// that are uncertain (neither occupied nor free), only the cost source.
template <typename S, typename Shape1, typename Shape2, typename Intersect>
std::size_t answerCollision(const Shape1& shape1, const Transform3<S>& X_W1, const Shape2& shape2,
                            const Transform3<S>& X_W2, const fcl::CollisionRequest<S>& request,
                            fcl::CollisionResult<S>& result, Intersect intersect) {
  if (request.isSatisfied(result)) return result.numContacts();
  ++t_disk_answers;
  const auto add_cost_source = [&] {
    fcl::AABB<S> aabb1, aabb2, overlap;
    fcl::computeBV(shape1, X_W1, aabb1);
    fcl::computeBV(shape2, X_W2, aabb2);
    aabb1.overlap(aabb2, overlap);
    result.addCostSource(fcl::CostSource<S>(overlap, shape1.cost_density * shape2.cost_density),
                         request.num_max_cost_sources);
  };
  if (!(shape1.isOccupied() && shape2.isOccupied())) {
    if (!shape1.isFree() && !shape2.isFree() && request.enable_cost && intersect(nullptr)) {
      add_cost_source();
    }
    return result.numContacts();
  }
  // The contact's point, normal and depth (an exact penetration depth: a
  // search over candidate directions, 10-100x the decision's cost) only
  // where they are reported.
  const bool room = request.num_max_contacts > result.numContacts();
  DiskContact<S> contact;
  if (!intersect(room && request.enable_contact ? &contact : nullptr)) {
    return result.numContacts();
  }
  if (room) {
    using Contact = fcl::Contact<S>;
    if (request.enable_contact) {
      result.addContact(Contact(&shape1, &shape2, Contact::NONE, Contact::NONE, contact.pos,
                                contact.normal, contact.penetration_depth));
    } else {
      result.addContact(Contact(&shape1, &shape2, Contact::NONE, Contact::NONE));
    }
  }
  if (request.enable_cost) add_cost_source();
  return result.numContacts();
}

template <typename S>
std::size_t answerDiskCollision(const Disk<S>& disk1, const Transform3<S>& X_W1,
                                const Disk<S>& disk2, const Transform3<S>& X_W2,
                                const fcl::CollisionRequest<S>& request,
                                fcl::CollisionResult<S>& result) {
  return answerCollision(disk1, X_W1, disk2, X_W2, request, result, [&](DiskContact<S>* contact) {
    return intersectDisks(disk1.radius, X_W1, disk2.radius, X_W2, contact);
  });
}

// ---------------------------------------------------------------------------
// 1b. The table: the FCL node types a Disk is answered against by fcl_disk, and
//     the shape class behind each (its solver: src/pairs/disk_<shape>.cpp,
//     include/fcl_disk/disk_shape_distance.h). A node type not listed keeps
//     FCL's own function (GJK on the flat cylinder). Adding a pair: its file in
//     src/pairs/ and one line here.

template <int NodeType, typename S>
struct DiskPairShape {
  using type = void;  // not answered by fcl_disk
};
#define FCL_DISK_PAIR(node_type, ShapeTemplate) \
  template <typename S>                          \
  struct DiskPairShape<fcl::node_type, S> {      \
    using type = ShapeTemplate<S>;               \
  };

FCL_DISK_PAIR(GEOM_SPHERE, fcl::Sphere)
FCL_DISK_PAIR(GEOM_BOX, fcl::Box)
FCL_DISK_PAIR(GEOM_CAPSULE, fcl::Capsule)
FCL_DISK_PAIR(GEOM_CYLINDER, fcl::Cylinder)  // a real cylinder (two Disks: section 1)
FCL_DISK_PAIR(GEOM_CONE, fcl::Cone)
FCL_DISK_PAIR(GEOM_ELLIPSOID, fcl::Ellipsoid)
FCL_DISK_PAIR(GEOM_CONVEX, fcl::Convex)
FCL_DISK_PAIR(GEOM_HALFSPACE, fcl::Halfspace)
FCL_DISK_PAIR(GEOM_PLANE, fcl::Plane)
FCL_DISK_PAIR(GEOM_TRIANGLE, fcl::TriangleP)
#undef FCL_DISK_PAIR

template <int NodeType, typename S>
constexpr bool kHasDiskPair = !std::is_void<typename DiskPairShape<NodeType, S>::type>::value;

/// Distance between a Disk and another shape, in FCL's argument order: the
/// disk is o1 when `disk_first`, else o2 (the points are swapped to match).
template <typename S, typename Shape>
S answerDiskShapeDistance(const Disk<S>& disk, const Transform3<S>& X_WD, const Shape& shape,
                          const Transform3<S>& X_WS, bool disk_first,
                          const fcl::DistanceRequest<S>& request,
                          fcl::DistanceResult<S>& result) {
  if (distanceIsSettled(result)) return result.min_distance;
  ++t_disk_answers;
  const DiskShapeDistanceResult<S> answer = diskShapeDistance(disk.radius, X_WD, shape, X_WS);
  const CollisionGeometry<S>* o1 = &disk;
  const CollisionGeometry<S>* o2 = &shape;
  if (!disk_first) std::swap(o1, o2);
  if (std::isnan(answer.distance)) return answerNoDistance<S>(o1, o2, result);
  fcl::Vector3<S> p_disk = answer.p_W_disk, p_shape = answer.p_W_shape;
  S distance = answer.distance;
  if constexpr (kExactDiskShapePenetration<Shape>) {
    // Overlap, signed: minus the exact penetration depth with the deepest
    // points, as for disk pairs (decided as collide() decides), from the
    // contact that decision computes.
    DiskContact<S> contact;
    if (request.enable_signed_distance && !(answer.distance > 0) &&
        diskShapeIntersect(disk.radius, X_WD, shape, X_WS, &contact)) {
      const DiskSignedDistanceResult<S> signed_answer =
          fcl_disk::detail::penetrationFromContact(disk.radius, X_WD, contact);
      if (isReportableDepth(-signed_answer.signed_distance)) {
        distance = signed_answer.signed_distance;
        p_disk = signed_answer.p_W1;
        p_shape = signed_answer.p_W2;
      }
    }
  }
  // Otherwise an overlap is distance 0 with a common point as both nearest points.
  if (disk_first) {
    keepIfNearer(result, distance, o1, o2, p_disk, p_shape);
  } else {
    keepIfNearer(result, distance, o1, o2, p_shape, p_disk);
  }
  return result.min_distance;
}

/// Collision between a Disk and another shape, in FCL's argument order; the
/// contact normal points from o1 to o2 (FCL's convention), so it is flipped
/// when the disk is o2.
template <typename S, typename Shape>
std::size_t answerDiskShapeCollision(const Disk<S>& disk, const Transform3<S>& X_WD,
                                     const Shape& shape, const Transform3<S>& X_WS,
                                     bool disk_first, const fcl::CollisionRequest<S>& request,
                                     fcl::CollisionResult<S>& result) {
  const auto intersect = [&](DiskContact<S>* contact) {
    if (!diskShapeIntersect(disk.radius, X_WD, shape, X_WS, contact)) return false;
    if (contact && !disk_first) contact->normal = -contact->normal;
    return true;
  };
  return disk_first
             ? answerCollision(disk, X_WD, shape, X_WS, request, result, intersect)
             : answerCollision(shape, X_WS, disk, X_WD, request, result, intersect);
}

// ---------------------------------------------------------------------------
// 1c. Meshes and octrees: the node types whose FCL function is a traversal
//     template over the shape and a narrowphase solver. Distance: fcl_disk's
//     best-first traversals (src/mesh_distance.h, src/octree_distance.h).
//     Collision: fcl_disk's depth-first traversals in FCL's order
//     (src/mesh_collision.h, src/octree_collision.h); with enable_cost, FCL's
//     template with Shape = Disk and DiskNarrowPhase (src/disk_narrowphase.h)
//     and the Disk's tight bounding volumes (include/fcl_disk/disk_bv.h), so
//     that cost sources are FCL's. Every leaf test is the exact disk-triangle
//     or disk-box solver. FCL's result and contact conventions are kept.
//     FCL's tables have a mesh only as o1 (fcl::distance and fcl::collide swap
//     a shape-mesh pair); an octree is either.

template <typename S>
const internal::DiskNarrowPhase<S> kDiskNarrowPhase{};

template <int NodeType, typename S>
struct DiskEnvironment {
  static constexpr bool kAnswered = false;  // not answered by fcl_disk
};

template <typename BV>
struct DiskMeshTraversal {
  static constexpr bool kAnswered = true;
  using S = typename BV::S;
  using Narrow = internal::DiskNarrowPhase<S>;
  static bool isTriangleModel(const CollisionGeometry<S>* mesh) {
    return static_cast<const fcl::BVHModel<BV>*>(mesh)->getModelType() == fcl::BVH_MODEL_TRIANGLES;
  }

  /// Distance: fcl_disk's best-first traversal in the mesh's frame M
  /// (src/mesh_distance.h), the disk posed there, the points mapped to the
  /// world. FCL's own distance traversals are not used: they bound nodes by
  /// the distance between two volumes (the disk's and the node's) and visit
  /// depth-first, and for AABB, OBB and k-DOP meshes FCL 0.7 has none that
  /// works (its generic one copies and rebuilds the mesh in the world frame
  /// per query, links to an initialize() it declares but never defines, and
  /// OBB and k-DOP have no distance between volumes).
  static S distance(const CollisionGeometry<S>* mesh, const Transform3<S>& X_WM,
                    const Disk<S>& disk, const Transform3<S>& X_WD,
                    const fcl::DistanceRequest<S>& request, fcl::DistanceResult<S>& result) {
    // A point cloud has no triangles to answer with: no answer (FCL's oriented
    // traversals would run on a node they left uninitialised and crash).
    if (!isTriangleModel(mesh)) return result.min_distance;
    if (request.isSatisfied(result)) return result.min_distance;
    const auto& model = *static_cast<const fcl::BVHModel<BV>*>(mesh);
    const internal::MeshDistanceAnswer answer = internal::diskMeshDistance(
        internal::orthonormalDiskInShape(disk.radius, X_WD, X_WM), model, double(result.min_distance),
        double(request.rel_err), double(request.abs_err));
    if (answer.triangle >= 0) {
      result.update(S(answer.distance), mesh, &disk, answer.triangle,
                    fcl::DistanceResult<S>::NONE,
                    internal::toWorldPoint(X_WM, answer.p_triangle).template cast<S>(),
                    internal::toWorldPoint(X_WM, answer.p_disk).template cast<S>());
    }
    return result.min_distance;
  }

  /// Collision: fcl_disk's depth-first traversal in the mesh's frame
  /// (src/mesh_collision.h), contacts mapped to the world at the end. With
  /// enable_cost FCL's path is kept, so that cost sources are FCL's
  /// world-frame boxes.
  static std::size_t collide(const CollisionGeometry<S>* mesh, const Transform3<S>& X_WM,
                             const Disk<S>& disk, const Transform3<S>& X_WD,
                             const fcl::CollisionRequest<S>& request,
                             fcl::CollisionResult<S>& result) {
    if (!isTriangleModel(mesh)) return result.numContacts();  // as distance()
    if (!request.enable_cost) return collideInMeshFrame(mesh, X_WM, disk, X_WD, request, result);
    return fcl::detail::BVHShapeCollider<BV, Disk<S>, Narrow>::collide(
        mesh, X_WM, &disk, X_WD, &kDiskNarrowPhase<S>, request, result);
  }

  static std::size_t collideInMeshFrame(const CollisionGeometry<S>* mesh,
                                        const Transform3<S>& X_WM, const Disk<S>& disk,
                                        const Transform3<S>& X_WD,
                                        const fcl::CollisionRequest<S>& request,
                                        fcl::CollisionResult<S>& result) {
    if (request.isSatisfied(result)) return result.numContacts();
    const auto& model = *static_cast<const fcl::BVHModel<BV>*>(mesh);
    // Not satisfied without enable_cost: room for at least one more contact.
    fcl::CollisionRequest<S> room_left = request;
    room_left.num_max_contacts = request.num_max_contacts - result.numContacts();
    fcl::CollisionResult<S> in_mesh_frame;
    internal::diskMeshCollide(internal::orthonormalDiskInShape(disk.radius, X_WD, X_WM), model,
                              disk, room_left, in_mesh_frame);
    for (std::size_t i = 0; i < in_mesh_frame.numContacts(); ++i) {
      fcl::Contact<S> contact = in_mesh_frame.getContact(i);
      if (request.enable_contact) {
        contact.pos = X_WM * contact.pos;
        contact.normal = X_WM.linear() * contact.normal;
      }
      result.addContact(contact);
    }
    return result.numContacts();
  }
};

#define FCL_DISK_MESH(node_type, ...) \
  template <typename S>               \
  struct DiskEnvironment<fcl::node_type, S> : DiskMeshTraversal<__VA_ARGS__> {};

FCL_DISK_MESH(BV_AABB, fcl::AABB<S>)
FCL_DISK_MESH(BV_OBB, fcl::OBB<S>)
FCL_DISK_MESH(BV_RSS, fcl::RSS<S>)
FCL_DISK_MESH(BV_kIOS, fcl::kIOS<S>)
FCL_DISK_MESH(BV_OBBRSS, fcl::OBBRSS<S>)
FCL_DISK_MESH(BV_KDOP16, fcl::KDOP<S, 16>)
FCL_DISK_MESH(BV_KDOP18, fcl::KDOP<S, 18>)
FCL_DISK_MESH(BV_KDOP24, fcl::KDOP<S, 24>)
#undef FCL_DISK_MESH

/// An octree: fcl_disk's traversals in the octree's frame O (FCL's traversal in
/// the world frame poses every cell in world coordinates, which costs the
/// rounding of their distance from the origin), the answer mapped to the
/// world. As FCL's shape-octree functions, the octree is o1 of the answer
/// whatever the argument order. With enable_cost FCL's world-frame collision
/// traversal is kept, so that cost sources are FCL's world boxes.
template <typename S>
struct DiskEnvironment<fcl::GEOM_OCTREE, S> {
  static constexpr bool kAnswered = true;
  using Narrow = internal::DiskNarrowPhase<S>;

  /// Distance: fcl_disk's best-first traversal in O (src/octree_distance.h).
  static S distance(const CollisionGeometry<S>* octree, const Transform3<S>& X_WO,
                    const Disk<S>& disk, const Transform3<S>& X_WD,
                    const fcl::DistanceRequest<S>& request, fcl::DistanceResult<S>& result) {
    if (request.isSatisfied(result)) return result.min_distance;
    const internal::OcTreeDistanceAnswer answer = internal::diskOcTreeDistance(
        internal::orthonormalDiskInShape(disk.radius, X_WD, X_WO), *static_cast<const fcl::OcTree<S>*>(octree),
        double(result.min_distance), double(request.rel_err), double(request.abs_err));
    if (answer.found) {
      result.update(S(answer.distance), octree, &disk, answer.cell, fcl::DistanceResult<S>::NONE,
                    internal::toWorldPoint(X_WO, answer.p_cell).template cast<S>(),
                    internal::toWorldPoint(X_WO, answer.p_disk).template cast<S>());
    }
    return result.min_distance;
  }
  static S distanceDiskFirst(const Disk<S>& disk, const Transform3<S>& X_WD,
                             const CollisionGeometry<S>* octree, const Transform3<S>& X_WO,
                             const fcl::DistanceRequest<S>& request,
                             fcl::DistanceResult<S>& result) {
    return distance(octree, X_WO, disk, X_WD, request, result);
  }

  static std::size_t collide(const CollisionGeometry<S>* octree, const Transform3<S>& X_WO,
                             const Disk<S>& disk, const Transform3<S>& X_WD,
                             const fcl::CollisionRequest<S>& request,
                             fcl::CollisionResult<S>& result) {
    if (request.enable_cost) {
      return fcl::detail::OcTreeShapeCollide<Disk<S>, Narrow>(octree, X_WO, &disk, X_WD,
                                                              &kDiskNarrowPhase<S>, request, result);
    }
    if (request.isSatisfied(result)) return result.numContacts();
    // Not satisfied without enable_cost: room for at least one more contact.
    fcl::CollisionRequest<S> room_left = request;
    room_left.num_max_contacts = request.num_max_contacts - result.numContacts();
    fcl::CollisionResult<S> in_octree_frame;
    internal::diskOcTreeCollide(internal::orthonormalDiskInShape(disk.radius, X_WD, X_WO),
                                *static_cast<const fcl::OcTree<S>*>(octree), disk, room_left,
                                in_octree_frame);
    for (std::size_t i = 0; i < in_octree_frame.numContacts(); ++i) {
      fcl::Contact<S> contact = in_octree_frame.getContact(i);
      if (request.enable_contact) {
        contact.pos = X_WO * contact.pos;
        contact.normal = X_WO.linear() * contact.normal;
      }
      result.addContact(contact);
    }
    return result.numContacts();
  }
  static std::size_t collideDiskFirst(const Disk<S>& disk, const Transform3<S>& X_WD,
                                      const CollisionGeometry<S>* octree,
                                      const Transform3<S>& X_WO,
                                      const fcl::CollisionRequest<S>& request,
                                      fcl::CollisionResult<S>& result) {
    return collide(octree, X_WO, disk, X_WD, request, result);
  }
};

template <int NodeType, typename S>
constexpr bool kHasDiskEnvironment = DiskEnvironment<NodeType, S>::kAnswered;

/// Distance between a Disk and a mesh or octree (node type EnvType), in FCL's
/// argument order: the disk is o1 when `disk_first` (octrees only).
template <int EnvType, typename S>
S answerDiskEnvironmentDistance(const Disk<S>& disk, const Transform3<S>& X_WD,
                                const CollisionGeometry<S>* environment,
                                const Transform3<S>& X_WE, bool disk_first,
                                const fcl::DistanceRequest<S>& request,
                                fcl::DistanceResult<S>& result) {
  if (distanceIsSettled(result)) return result.min_distance;
  ++t_disk_answers;
  // A radius or a pose that fails isValidDiskAndShapePose: no distance (NaN).
  if (!internal::isValidDiskAndShapePose(disk.radius, X_WD, X_WE)) {
    return disk_first ? answerNoDistance<S>(&disk, environment, result)
                      : answerNoDistance<S>(environment, &disk, result);
  }
  using Environment = DiskEnvironment<EnvType, S>;
  if constexpr (EnvType == fcl::GEOM_OCTREE) {
    if (disk_first) return Environment::distanceDiskFirst(disk, X_WD, environment, X_WE, request, result);
  }
  return Environment::distance(environment, X_WE, disk, X_WD, request, result);
}

/// Collision between a Disk and a mesh or octree, in FCL's argument order.
template <int EnvType, typename S>
std::size_t answerDiskEnvironmentCollision(const Disk<S>& disk, const Transform3<S>& X_WD,
                                           const CollisionGeometry<S>* environment,
                                           const Transform3<S>& X_WE, bool disk_first,
                                           const fcl::CollisionRequest<S>& request,
                                           fcl::CollisionResult<S>& result) {
  if (request.isSatisfied(result)) return result.numContacts();
  ++t_disk_answers;
  // No contact can be shown for input that describes no pose.
  if (!internal::isValidDiskAndShapePose(disk.radius, X_WD, X_WE)) return result.numContacts();
  using Environment = DiskEnvironment<EnvType, S>;
  if constexpr (EnvType == fcl::GEOM_OCTREE) {
    if (disk_first) {
      return Environment::collideDiskFirst(disk, X_WD, environment, X_WE, request, result);
    }
  }
  return Environment::collide(environment, X_WE, disk, X_WD, request, result);
}

// ---------------------------------------------------------------------------
// 2. Wrappers for the slots of FCL's tables that can see a Disk: the
//    GEOM_CYLINDER row and column. Disk-disk pairs and a Disk against a shape
//    of the table of section 1b or a mesh or octree of section 1c get
//    fcl_disk's answers; a pair with one Disk
//    whose poses describe no disk pair gets NaN / no contact (FCL's GJK would
//    abort on NaN, facts: Debian keeps asserts on); every other pair, real
//    cylinders included, goes to FCL's original entry unchanged.
//
// `Solver` is only passed through to FCL's original entry, never dereferenced
// here, so one wrapper shape serves every table; `Table` gives each patched table
// its own saved originals.

/// Whether a pair with a Disk may go to FCL: the Disk's pose is a disk pose and
/// the other pose is finite (the other shape's rotation is FCL's business).
template <typename S>
bool fitForFcl(const Disk<S>* disk1, const Transform3<S>& tf1, const Disk<S>* disk2,
               const Transform3<S>& tf2) {
  const auto fit = [](const Disk<S>* disk, const Transform3<S>& tf) {
    return disk ? isValidDiskPose(tf) && isValidDiskRadius(disk->radius)
                : tf.matrix().allFinite();
  };
  return fit(disk1, tf1) && fit(disk2, tf2);
}

/// What FCL's entry does for a pair its table has no function for (the slot was
/// empty before fcl_disk filled it for Disks): the same warning, and its result.
template <typename S, typename Value>
Value fclNotSupported(const char* query, const CollisionGeometry<S>* o1,
                      const CollisionGeometry<S>* o2, Value value) {
  std::cerr << "Warning: " << query << " function between node type " << o1->getNodeType()
            << " and node type " << o2->getNodeType() << " is not supported\n";
  return value;
}

/// The shape class of a node type answered against a Disk (section 1b).
template <int NodeType, typename S>
using PairShape = typename DiskPairShape<NodeType, S>::type;

template <typename S, int Row, int Col>
constexpr bool kSlotAnswersDisks = (Row == fcl::GEOM_CYLINDER && kHasDiskPair<Col, S>) ||
                                   (Col == fcl::GEOM_CYLINDER && kHasDiskPair<Row, S>) ||
                                   (Col == fcl::GEOM_CYLINDER && kHasDiskEnvironment<Row, S>) ||
                                   (Row == fcl::GEOM_CYLINDER && Col == fcl::GEOM_OCTREE);

template <typename S, typename Solver, int Table, int Row, int Col>
struct DistanceSlot {
  static constexpr int kRow = Row, kCol = Col;
  static constexpr bool kAnswersDisks = kSlotAnswersDisks<S, Row, Col>;
  using Entry = S (*)(const CollisionGeometry<S>*, const Transform3<S>&,
                      const CollisionGeometry<S>*, const Transform3<S>&, const Solver*,
                      const fcl::DistanceRequest<S>&, fcl::DistanceResult<S>&);
  static inline std::atomic<Entry> original{nullptr};

  static S call(const CollisionGeometry<S>* o1, const Transform3<S>& tf1,
                const CollisionGeometry<S>* o2, const Transform3<S>& tf2, const Solver* solver,
                const fcl::DistanceRequest<S>& request, fcl::DistanceResult<S>& result) {
    const Disk<S>* disk1 = Row == fcl::GEOM_CYLINDER ? asDisk(o1) : nullptr;
    const Disk<S>* disk2 = Col == fcl::GEOM_CYLINDER ? asDisk(o2) : nullptr;
    if (disk1 && disk2) return answerDiskDistance(*disk1, tf1, *disk2, tf2, request, result);
    if constexpr (Row == fcl::GEOM_CYLINDER && kHasDiskPair<Col, S>) {
      if (disk1) {
        return answerDiskShapeDistance(*disk1, tf1, static_cast<const PairShape<Col, S>&>(*o2),
                                       tf2, /*disk_first=*/true, request, result);
      }
    }
    if constexpr (Col == fcl::GEOM_CYLINDER && kHasDiskPair<Row, S>) {
      if (disk2) {
        return answerDiskShapeDistance(*disk2, tf2, static_cast<const PairShape<Row, S>&>(*o1),
                                       tf1, /*disk_first=*/false, request, result);
      }
    }
    if constexpr (Col == fcl::GEOM_CYLINDER && kHasDiskEnvironment<Row, S>) {
      if (disk2) {
        return answerDiskEnvironmentDistance<Row>(*disk2, tf2, o1, tf1, /*disk_first=*/false,
                                                  request, result);
      }
    }
    if constexpr (Row == fcl::GEOM_CYLINDER && Col == fcl::GEOM_OCTREE) {
      if (disk1) {
        return answerDiskEnvironmentDistance<Col>(*disk1, tf1, o2, tf2, /*disk_first=*/true,
                                                  request, result);
      }
    }
    if ((disk1 || disk2) && !fitForFcl(disk1, tf1, disk2, tf2)) {
      return answerNoDistance(o1, o2, result);
    }
    const Entry fcl_entry = original.load(std::memory_order_acquire);
    if (!fcl_entry) return fclNotSupported("distance", o1, o2, std::numeric_limits<S>::max());
    return fcl_entry(o1, tf1, o2, tf2, solver, request, result);
  }
};

template <typename S, typename Solver, int Table, int Row, int Col>
struct CollisionSlot {
  static constexpr int kRow = Row, kCol = Col;
  static constexpr bool kAnswersDisks = kSlotAnswersDisks<S, Row, Col>;
  using Entry = std::size_t (*)(const CollisionGeometry<S>*, const Transform3<S>&,
                                const CollisionGeometry<S>*, const Transform3<S>&,
                                const Solver*, const fcl::CollisionRequest<S>&,
                                fcl::CollisionResult<S>&);
  static inline std::atomic<Entry> original{nullptr};

  static std::size_t call(const CollisionGeometry<S>* o1, const Transform3<S>& tf1,
                          const CollisionGeometry<S>* o2, const Transform3<S>& tf2,
                          const Solver* solver, const fcl::CollisionRequest<S>& request,
                          fcl::CollisionResult<S>& result) {
    const Disk<S>* disk1 = Row == fcl::GEOM_CYLINDER ? asDisk(o1) : nullptr;
    const Disk<S>* disk2 = Col == fcl::GEOM_CYLINDER ? asDisk(o2) : nullptr;
    if (disk1 && disk2) return answerDiskCollision(*disk1, tf1, *disk2, tf2, request, result);
    if constexpr (Row == fcl::GEOM_CYLINDER && kHasDiskPair<Col, S>) {
      if (disk1) {
        return answerDiskShapeCollision(*disk1, tf1, static_cast<const PairShape<Col, S>&>(*o2),
                                        tf2, /*disk_first=*/true, request, result);
      }
    }
    if constexpr (Col == fcl::GEOM_CYLINDER && kHasDiskPair<Row, S>) {
      if (disk2) {
        return answerDiskShapeCollision(*disk2, tf2, static_cast<const PairShape<Row, S>&>(*o1),
                                        tf1, /*disk_first=*/false, request, result);
      }
    }
    if constexpr (Col == fcl::GEOM_CYLINDER && kHasDiskEnvironment<Row, S>) {
      if (disk2) {
        return answerDiskEnvironmentCollision<Row>(*disk2, tf2, o1, tf1, /*disk_first=*/false,
                                                   request, result);
      }
    }
    if constexpr (Row == fcl::GEOM_CYLINDER && Col == fcl::GEOM_OCTREE) {
      if (disk1) {
        return answerDiskEnvironmentCollision<Col>(*disk1, tf1, o2, tf2, /*disk_first=*/true,
                                                   request, result);
      }
    }
    // No contact can be shown for input that describes no pose.
    if ((disk1 || disk2) && !fitForFcl(disk1, tf1, disk2, tf2)) return result.numContacts();
    const Entry fcl_entry = original.load(std::memory_order_acquire);
    if (!fcl_entry) return fclNotSupported("collision", o1, o2, std::size_t(0));
    return fcl_entry(o1, tf1, o2, tf2, solver, request, result);
  }
};

/// Replaces table[kRow][kCol] by Wrapper::call, saving the original. An empty
/// slot (a pair FCL does not support) is filled only where the wrapper answers
/// Disks (e.g. cylinder-triangle distance); for real cylinders it then behaves
/// as FCL's empty slot. Atomic stores: other threads may be dispatching
/// non-disk pairs.
template <typename Wrapper, typename Table>
void installIntoSlot(Table& matrix) {
  auto& slot = matrix[Wrapper::kRow][Wrapper::kCol];
  using Entry = typename Wrapper::Entry;
  Entry current = __atomic_load_n(reinterpret_cast<Entry*>(&slot), __ATOMIC_ACQUIRE);
  if (current == &Wrapper::call) return;
  if (current == nullptr && !Wrapper::kAnswersDisks) return;
  Wrapper::original.store(current, std::memory_order_release);
  __atomic_store_n(reinterpret_cast<Entry*>(&slot), &Wrapper::call, __ATOMIC_RELEASE);
}

/// Wraps the GEOM_CYLINDER row and column of one distance or collision table.
template <template <int, int> class Wrapper, typename Table, int... Types>
void installIntoCylinderRowAndColumn(Table& matrix, std::integer_sequence<int, Types...>) {
  (installIntoSlot<Wrapper<fcl::GEOM_CYLINDER, Types>>(matrix), ...);
  (installIntoSlot<Wrapper<Types, fcl::GEOM_CYLINDER>>(matrix), ...);
}

template <typename S, typename Solver, int Table>
struct TableWrappers {
  template <int Row, int Col>
  using Distance = DistanceSlot<S, Solver, Table, Row, Col>;
  template <int Row, int Col>
  using Collision = CollisionSlot<S, Solver, Table, Row, Col>;

  template <typename DistanceMatrix, typename CollisionMatrix>
  static void install(DistanceMatrix& distance_matrix, CollisionMatrix& collision_matrix) {
    const auto types = std::make_integer_sequence<int, fcl::NODE_COUNT>();
    installIntoCylinderRowAndColumn<Distance>(distance_matrix, types);
    installIntoCylinderRowAndColumn<Collision>(collision_matrix, types);
  }
};

// ---------------------------------------------------------------------------
// 2b. The shortcut for FCL's object-level entry points (defined in section 5):
//     a pair of Disks, or a Disk and a shape of the table of section 1b (but a
//     cylinder), is answered at once; every other pair goes to FCL's
//     geometry-level entry, which is all FCL's object-level entry does with it.
//     The shortcut is taken only where FCL's entry would do nothing but build
//     a GJK solver object, look up the table and call the slot above, so the
//     answers are those of the tables, bit for bit.

/// Whether FCL's distance entry, for a pair with a Disk, only calls the slot. It
/// does more for the indep solver on a signed request whose answer is negative
/// (it recomputes the depth with collide() and reports the contact point as
/// both nearest points), and for a solver type it does not know (it returns -1).
template <typename S>
bool distanceEntryOnlyCallsSlot(const fcl::DistanceRequest<S>& request) {
  if (request.gjk_solver_type == fcl::GST_LIBCCD) return true;
  return request.gjk_solver_type == fcl::GST_INDEP && !request.enable_signed_distance;
}

/// Whether FCL's collision entry, for a pair with a Disk, only calls the slot. It
/// does not for num_max_contacts == 0 (a warning and 0) or an unknown solver.
template <typename S>
bool collisionEntryOnlyCallsSlot(const fcl::CollisionRequest<S>& request) {
  return request.num_max_contacts != 0 && (request.gjk_solver_type == fcl::GST_LIBCCD ||
                                           request.gjk_solver_type == fcl::GST_INDEP);
}

/// Calls answer(shape) with `geometry` as the shape class of its node type when
/// a Disk is answered against that type by fcl_disk (section 1b); returns
/// whether it did. A Disk's node type is GEOM_CYLINDER too, so there only an
/// fcl::Cylinder itself is answered (its type_info's address, as
/// asDiskOfThisLibrary compares): every other class of that node type (a Disk
/// another copy of the library made, a class derived from fcl::Cylinder) goes
/// to FCL's entry, whose tables tell them apart.
template <typename S, typename Answer, int... Types>
bool withDiskPairShape(const CollisionGeometry<S>* geometry, Answer&& answer,
                       std::integer_sequence<int, Types...>) {
  const int node_type = geometry->getNodeType();
  const auto try_type = [&](auto type) {
    constexpr int kType = decltype(type)::value;
    if constexpr (kHasDiskPair<kType, S>) {
      if (node_type != kType) return false;
      if (kType == fcl::GEOM_CYLINDER && &typeid(*geometry) != &typeid(fcl::Cylinder<S>)) {
        return false;
      }
      answer(static_cast<const PairShape<kType, S>&>(*geometry));
      return true;
    } else {
      return false;
    }
  };
  return (try_type(std::integral_constant<int, Types>()) || ...);
}

template <typename S, typename Answer>
bool withDiskPairShape(const CollisionGeometry<S>* geometry, Answer&& answer) {
  return withDiskPairShape(geometry, std::forward<Answer>(answer),
                           std::make_integer_sequence<int, fcl::NODE_COUNT>());
}

template <typename S>
S distanceOfObjects(const fcl::CollisionObject<S>* o1, const fcl::CollisionObject<S>* o2,
                    const fcl::DistanceRequest<S>& request, fcl::DistanceResult<S>& result) {
  const CollisionGeometry<S>* g1 = o1->collisionGeometry().get();
  const CollisionGeometry<S>* g2 = o2->collisionGeometry().get();
  const Disk<S>* disk1 = asDiskOfThisLibrary(g1);
  const Disk<S>* disk2 = asDiskOfThisLibrary(g2);
  if ((disk1 || disk2) && distanceEntryOnlyCallsSlot(request)) {
    const Transform3<S>& tf1 = o1->getTransform();
    const Transform3<S>& tf2 = o2->getTransform();
    if (disk1 && disk2) return answerDiskDistance(*disk1, tf1, *disk2, tf2, request, result);
    S distance = 0;
    const bool answered =
        disk1 ? withDiskPairShape(g2, [&](const auto& shape) {
                  distance = answerDiskShapeDistance(*disk1, tf1, shape, tf2, true, request, result);
                })
              : withDiskPairShape(g1, [&](const auto& shape) {
                  distance = answerDiskShapeDistance(*disk2, tf2, shape, tf1, false, request, result);
                });
    if (answered) return distance;
  }
  return fcl::distance(g1, o1->getTransform(), g2, o2->getTransform(), request, result);
}

template <typename S>
std::size_t collideObjects(const fcl::CollisionObject<S>* o1, const fcl::CollisionObject<S>* o2,
                           const fcl::CollisionRequest<S>& request,
                           fcl::CollisionResult<S>& result) {
  const CollisionGeometry<S>* g1 = o1->collisionGeometry().get();
  const CollisionGeometry<S>* g2 = o2->collisionGeometry().get();
  const Disk<S>* disk1 = asDiskOfThisLibrary(g1);
  const Disk<S>* disk2 = asDiskOfThisLibrary(g2);
  if ((disk1 || disk2) && collisionEntryOnlyCallsSlot(request)) {
    const Transform3<S>& tf1 = o1->getTransform();
    const Transform3<S>& tf2 = o2->getTransform();
    if (disk1 && disk2) return answerDiskCollision(*disk1, tf1, *disk2, tf2, request, result);
    std::size_t contacts = 0;
    const bool answered =
        disk1 ? withDiskPairShape(g2, [&](const auto& shape) {
                  contacts = answerDiskShapeCollision(*disk1, tf1, shape, tf2, true, request, result);
                })
              : withDiskPairShape(g1, [&](const auto& shape) {
                  contacts = answerDiskShapeCollision(*disk2, tf2, shape, tf1, false, request, result);
                });
    if (answered) return contacts;
  }
  return fcl::collide(g1, o1->getTransform(), g2, o2->getTransform(), request, result);
}

// ---------------------------------------------------------------------------
// 3a. The tables that code compiled against FCL's headers uses: float paths and
// the overloads taking a solver pointer. Their static objects are unique in the
// process (vague linkage), so writing ours writes theirs.

template <typename Solver>
void installIntoVisibleTables() {
  TableWrappers<typename Solver::S, Solver, 0>::install(
      fcl::getDistanceFunctionLookTable<Solver>().distance_matrix,
      fcl::getCollisionFunctionLookTable<Solver>().collision_matrix);
}

// 3b. The private copies inside libfcl.so (hidden visibility), used by plain
// fcl::distance<double> / fcl::collide<double> and hence by the broadphase
// default callbacks. They have no symbol, so we find them by content: a
// NODE_COUNT x NODE_COUNT array of function pointers whose null/non-null pattern
// equals the one FCL's own constructor produces (we build one to compare) and
// whose entries all point into libfcl's code. libfcl instantiates double only:
// one table per solver (libccd, indep), hence exactly two of each kind.

constexpr int kEntries = fcl::NODE_COUNT * fcl::NODE_COUNT;
constexpr int kPrivateTablesPerKind = 2;  // GJKSolver_libccd<double>, GJKSolver_indep<double>

struct AddressRange {
  std::uintptr_t begin, end;
  bool contains(std::uintptr_t a) const { return a >= begin && a < end; }
};

struct LibfclSegments {
  std::vector<AddressRange> writable, executable;
  std::string path;
};

LibfclSegments findLibfclSegments() {
  LibfclSegments segments;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* data) -> int {
        if (!info->dlpi_name || !std::strstr(info->dlpi_name, "libfcl.so")) return 0;
        auto* out = static_cast<LibfclSegments*>(data);
        out->path = info->dlpi_name;
        for (int i = 0; i < info->dlpi_phnum; ++i) {
          const ElfW(Phdr)& header = info->dlpi_phdr[i];
          if (header.p_type != PT_LOAD) continue;
          const AddressRange range{info->dlpi_addr + header.p_vaddr,
                                   info->dlpi_addr + header.p_vaddr + header.p_memsz};
          if (header.p_flags & PF_W) out->writable.push_back(range);
          if (header.p_flags & PF_X) out->executable.push_back(range);
        }
        return 1;
      },
      &segments);
  return segments;
}

template <typename Matrix>
std::vector<bool> nonNullPattern(const Matrix& matrix) {
  std::vector<bool> pattern(kEntries);
  for (int i = 0; i < kEntries; ++i) pattern[i] = (&matrix[0][0])[i] != nullptr;
  return pattern;
}

/// Addresses of the arrays in libfcl's writable segments that look like `pattern`.
std::vector<std::uintptr_t*> findTables(const LibfclSegments& segments,
                                        const std::vector<bool>& pattern) {
  auto is_code = [&](std::uintptr_t a) {
    for (const auto& r : segments.executable)
      if (r.contains(a)) return true;
    return false;
  };
  std::vector<std::uintptr_t*> found;
  for (const auto& range : segments.writable) {
    const std::size_t bytes = kEntries * sizeof(std::uintptr_t);
    std::uintptr_t first = (range.begin + alignof(std::uintptr_t) - 1) &
                           ~(std::uintptr_t(alignof(std::uintptr_t)) - 1);
    for (std::uintptr_t a = first; a + bytes <= range.end; a += sizeof(std::uintptr_t)) {
      const auto* words = reinterpret_cast<const std::uintptr_t*>(a);
      bool match = true;
      for (int i = 0; i < kEntries && match; ++i) {
        match = (words[i] != 0) == pattern[i] && (words[i] == 0 || is_code(words[i]));
      }
      if (match) found.push_back(reinterpret_cast<std::uintptr_t*>(a));
    }
  }
  return found;
}

// libfcl's private tables hold entries typed for GJKSolver_libccd<double> or
// GJKSolver_indep<double>; which is which cannot be told from memory. The
// wrappers only pass the solver pointer through, so they are declared with an
// opaque solver type; the ABI of the call is the same.
struct OpaqueSolver;

template <int Table>
void installIntoPrivateTables(std::uintptr_t* distance_table, std::uintptr_t* collision_table) {
  using Wrappers = TableWrappers<double, OpaqueSolver, Table>;
  using DistanceEntry = typename Wrappers::template Distance<0, 0>::Entry;
  using CollisionEntry = typename Wrappers::template Collision<0, 0>::Entry;
  using DistanceMatrix = DistanceEntry[fcl::NODE_COUNT][fcl::NODE_COUNT];
  using CollisionMatrix = CollisionEntry[fcl::NODE_COUNT][fcl::NODE_COUNT];
  Wrappers::install(*reinterpret_cast<DistanceMatrix*>(distance_table),
                    *reinterpret_cast<CollisionMatrix*>(collision_table));
}

std::string hookFailureAdvice(const std::string& what) {
  return "fcl_disk: cannot install the disk functions into FCL's dispatch: " + what +
         ". fcl_disk supports FCL 0.7 as Debian/Ubuntu ship it (libfcl.so with private "
         "dispatch tables). Use the libfcl that fcl_disk was built against, or build FCL "
         "from source with the same headers; see docs/fcl_hook.md.";
}

/// Makes libfcl build its private tables (they are function-local statics,
/// created on first use) by running one query per solver through libfcl's own
/// fcl::distance<double> / fcl::collide<double>.
void initializeLibfclTables() {
  auto sphere = std::make_shared<fcl::Sphere<double>>(1.0);
  fcl::Transform3<double> apart = fcl::Transform3<double>::Identity();
  apart.translation() << 3.0, 0.0, 0.0;
  fcl::CollisionObject<double> a(sphere), b(sphere, apart);
  for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
    fcl::DistanceRequest<double> distance_request;
    distance_request.gjk_solver_type = solver;
    fcl::DistanceResult<double> distance_result;
    fcl::distance(&a, &b, distance_request, distance_result);
    fcl::CollisionRequest<double> collision_request;
    collision_request.gjk_solver_type = solver;
    fcl::CollisionResult<double> collision_result;
    fcl::collide(&a, &b, collision_request, collision_result);
  }
}

void installIntoLibfclPrivateTables() {
  initializeLibfclTables();
  const LibfclSegments segments = findLibfclSegments();
  if (segments.writable.empty() || segments.executable.empty()) {
    throw std::runtime_error(hookFailureAdvice("libfcl.so is not loaded in this process"));
  }
  using Libccd = fcl::detail::GJKSolver_libccd<double>;
  const fcl::detail::DistanceFunctionMatrix<Libccd> distance_reference;
  const fcl::detail::CollisionFunctionMatrix<Libccd> collision_reference;
  const auto distance_tables =
      findTables(segments, nonNullPattern(distance_reference.distance_matrix));
  const auto collision_tables =
      findTables(segments, nonNullPattern(collision_reference.collision_matrix));
  if (distance_tables.size() != kPrivateTablesPerKind ||
      collision_tables.size() != kPrivateTablesPerKind) {
    throw std::runtime_error(hookFailureAdvice(
        "found " + std::to_string(distance_tables.size()) + " distance and " +
        std::to_string(collision_tables.size()) + " collision tables in " + segments.path +
        ", expected " + std::to_string(kPrivateTablesPerKind) + " of each"));
  }
  // Which distance table goes with which collision table does not matter: each
  // Table index only keeps its own wrappers' saved originals apart.
  installIntoPrivateTables<0>(distance_tables[0], collision_tables[0]);
  installIntoPrivateTables<1>(distance_tables[1], collision_tables[1]);
}

// ---------------------------------------------------------------------------
// 4. The probe: two disks through every public entry point must reach us.

// Set while installing on this thread, so the probe's Disks do not re-enter
// registration.
thread_local bool t_installing = false;

/// Runs `query` and throws unless it reached fcl_disk exactly once.
template <typename Query>
void probeOnePath(const std::string& path, Query query) {
  const std::uint64_t before = t_disk_answers;
  query();
  if (t_disk_answers != before + 1) {
    throw std::runtime_error(hookFailureAdvice("the probe query through " + path +
                                               " did not reach fcl_disk"));
  }
}

template <typename S>
void probeScalar(const char* scalar_name) {
  auto disk = std::make_shared<Disk<S>>(S(1));
  fcl::Transform3<S> lifted = fcl::Transform3<S>::Identity();
  lifted.translation() << S(0.25), S(0), S(0.5);
  const fcl::CollisionObject<S> a(disk), b(disk, lifted);
  for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
    const std::string name = std::string(scalar_name) +
                             (solver == fcl::GST_LIBCCD ? ", libccd" : ", indep");
    fcl::DistanceRequest<S> distance_request;
    distance_request.gjk_solver_type = solver;
    fcl::CollisionRequest<S> collision_request;
    collision_request.gjk_solver_type = solver;
    // On objects (section 5, or FCL's own entry where libfcl comes first), and
    // on geometries, which always goes through FCL's tables.
    probeOnePath("fcl::distance on objects (" + name + ")", [&] {
      fcl::DistanceResult<S> result;
      fcl::distance(&a, &b, distance_request, result);
    });
    probeOnePath("fcl::distance on geometries (" + name + ")", [&] {
      fcl::DistanceResult<S> result;
      fcl::distance(disk.get(), a.getTransform(), disk.get(), b.getTransform(), distance_request,
                    result);
    });
    probeOnePath("fcl::collide on objects (" + name + ")", [&] {
      fcl::CollisionResult<S> result;
      fcl::collide(&a, &b, collision_request, result);
    });
    probeOnePath("fcl::collide on geometries (" + name + ")", [&] {
      fcl::CollisionResult<S> result;
      fcl::collide(disk.get(), a.getTransform(), disk.get(), b.getTransform(), collision_request,
                   result);
    });
  }
}

void installOnce() {
  t_installing = true;
  struct Reset {
    ~Reset() { t_installing = false; }
  } reset;
  installIntoVisibleTables<fcl::detail::GJKSolver_libccd<float>>();
  installIntoVisibleTables<fcl::detail::GJKSolver_indep<float>>();
  installIntoVisibleTables<fcl::detail::GJKSolver_libccd<double>>();
  installIntoVisibleTables<fcl::detail::GJKSolver_indep<double>>();
  installIntoLibfclPrivateTables();
  probeScalar<double>("double");
  probeScalar<float>("float");
}

std::once_flag g_install_once;

void install() {
  if (t_installing) return;  // the probe's own Disks
  std::call_once(g_install_once, installOnce);
}

// Installed when libfcl_disk is loaded: before main() for a linked library,
// inside dlopen() for a plugin, so before any thread of the program can
// dispatch through the tables. FCL reads its tables with plain loads; patching
// them while another thread dispatches would be a data race (ThreadSanitizer
// reports it if the tables are patched at the first Disk while another thread
// queries spheres). A failure is not thrown here, where it would terminate the program
// at load: call_once then stays unset, and the first Disk or
// registerDiskFunctions() retries and throws the message.
[[maybe_unused]] const bool g_installed_at_load = [] {
  try {
    install();
    return true;
  } catch (const std::exception&) {
    return false;
  }
}();

}  // namespace

namespace detail {
void ensureDiskFunctionsRegistered() { install(); }
}  // namespace detail

void registerDiskFunctions(DiskDistanceMethod method) {
  install();
  g_method.store(method, std::memory_order_relaxed);
}

DiskDistanceMethod registeredDiskDistanceMethod() {
  return g_method.load(std::memory_order_relaxed);
}

}  // namespace fcl_disk

// ---------------------------------------------------------------------------
// 5. FCL's object-level entry points, fcl::distance(o1, o2, request, result) and
// fcl::collide(o1, o2, request, result), the ones planners and FCL's broadphase
// callbacks call, defined here with the shortcut of section 2b.
//
// Why: before FCL's entry reaches a slot it builds a GJK solver object, makes
// four virtual type queries, looks up the table and, in double, calls into
// libfcl through the PLT several times: 20 ns per query, more than 10% of a
// disk query (docs/performance.md, docs/fcl_hook.md "The object-level entry").
//
// How: the functions below carry the symbols of FCL's template instantiations
// (Itanium mangling of fcl::distance<S> / fcl::collide<S> on CollisionObjects).
// Float: fcl_templates.h declares them `extern template`, so every caller
// links to these; libfcl has no float code. Double: libfcl exports the same
// symbols, and the dynamic linker binds each call to the first definition in
// load order, libfcl_disk's in every program that links fcl_disk::fcl_disk
// (libfcl comes after it, as its dependency). Where libfcl comes first (linked
// before fcl_disk, or libfcl_disk dlopen()ed) FCL's own entry runs and reaches
// the same answers through the patched tables, without the shortcut.
// test_hook's ObjectEntryPointsAreFcl_disks checks which definition runs.
namespace fcl_disk::detail {

double distanceOfObjectsDouble(const fcl::CollisionObject<double>* o1,
                               const fcl::CollisionObject<double>* o2,
                               const fcl::DistanceRequest<double>& request,
                               fcl::DistanceResult<double>& result)
    __asm__("_ZN3fcl8distanceIdEET_PKNS_15CollisionObjectIS1_EES5_RKNS_15DistanceRequestIS1_EERNS_14DistanceResultIS1_EE");
float distanceOfObjectsFloat(const fcl::CollisionObject<float>* o1,
                             const fcl::CollisionObject<float>* o2,
                             const fcl::DistanceRequest<float>& request,
                             fcl::DistanceResult<float>& result)
    __asm__("_ZN3fcl8distanceIfEET_PKNS_15CollisionObjectIS1_EES5_RKNS_15DistanceRequestIS1_EERNS_14DistanceResultIS1_EE");
std::size_t collideObjectsDouble(const fcl::CollisionObject<double>* o1,
                                 const fcl::CollisionObject<double>* o2,
                                 const fcl::CollisionRequest<double>& request,
                                 fcl::CollisionResult<double>& result)
    __asm__("_ZN3fcl7collideIdEEmPKNS_15CollisionObjectIT_EES5_RKNS_16CollisionRequestIS2_EERNS_15CollisionResultIS2_EE");
std::size_t collideObjectsFloat(const fcl::CollisionObject<float>* o1,
                                const fcl::CollisionObject<float>* o2,
                                const fcl::CollisionRequest<float>& request,
                                fcl::CollisionResult<float>& result)
    __asm__("_ZN3fcl7collideIfEEmPKNS_15CollisionObjectIT_EES5_RKNS_16CollisionRequestIS2_EERNS_15CollisionResultIS2_EE");

double distanceOfObjectsDouble(const fcl::CollisionObject<double>* o1,
                               const fcl::CollisionObject<double>* o2,
                               const fcl::DistanceRequest<double>& request,
                               fcl::DistanceResult<double>& result) {
  return distanceOfObjects(o1, o2, request, result);
}
float distanceOfObjectsFloat(const fcl::CollisionObject<float>* o1,
                             const fcl::CollisionObject<float>* o2,
                             const fcl::DistanceRequest<float>& request,
                             fcl::DistanceResult<float>& result) {
  return distanceOfObjects(o1, o2, request, result);
}
std::size_t collideObjectsDouble(const fcl::CollisionObject<double>* o1,
                                 const fcl::CollisionObject<double>* o2,
                                 const fcl::CollisionRequest<double>& request,
                                 fcl::CollisionResult<double>& result) {
  return collideObjects(o1, o2, request, result);
}
std::size_t collideObjectsFloat(const fcl::CollisionObject<float>* o1,
                                const fcl::CollisionObject<float>* o2,
                                const fcl::CollisionRequest<float>& request,
                                fcl::CollisionResult<float>& result) {
  return collideObjects(o1, o2, request, result);
}

}  // namespace fcl_disk::detail
