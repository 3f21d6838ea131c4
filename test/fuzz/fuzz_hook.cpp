// libFuzzer target: disks through FCL's public entry points (the hook of
// src/fcl_hook.cpp), double and float.
//
// For two fcl::CollisionObject with Disk geometries, with both
// DistanceRequest::gjk_solver_type values and the selected method:
// - fcl::distance gives bit for bit the selected standalone solver's distance
//   and nearest points, and result.min_distance NaN where the solver gives NaN
//   (every input describing no disk pair: NaN/inf poses, rotations beyond the
//   defect tolerance);
// - fcl::collide gives bit for bit intersectDisks()'s verdict and contact, and
//   no contact for input describing no disk pair;
// - a DynamicAABBTreeCollisionManager over a chain of disks gives the least
//   pair distance and a collision exactly when some pair collides;
// - Disk's constructor throws std::invalid_argument exactly for a radius that
//   is outside the library's range (isValidDiskRadius).
// Option byte after the pair: bit 0 selects DiskDistanceMethod::almohamad_selim,
// bit 1 enable_signed_distance, bits 2-3 the number of extra disks (0-2) in the
// broadphase chain.
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <fcl_disk/fcl_disk.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

#include "fuzz_checks.h"

/// A NaN answer must reach the caller as result.min_distance = NaN. FCL's
/// DistanceResult::update() skips a NaN (`min_distance > NaN` is false), so
/// src/fcl_hook.cpp writes it directly. 1 (the default) requires NaN; 0 also
/// accepts numeric_limits::max(), what update() alone leaves (CMake option
/// FCL_DISK_FUZZ_HOOK_PROPAGATES_NAN).
#ifndef FCL_DISK_FUZZ_HOOK_PROPAGATES_NAN
#define FCL_DISK_FUZZ_HOOK_PROPAGATES_NAN 1
#endif

namespace fcl_disk_fuzz {
namespace {

using fcl_disk::Disk;
using fcl_disk::DiskDistanceMethod;

template <typename S>
fcl_disk::DiskDistanceResult<S> selectedSolver(DiskDistanceMethod method, S r1,
                                               const fcl::Transform3<S>& X_W1, S r2,
                                               const fcl::Transform3<S>& X_W2) {
  return method == DiskDistanceMethod::exact
             ? fcl_disk::exactDiskDistance<S>(r1, X_W1, r2, X_W2)
             : fcl_disk::almohamadSelimDiskDistance<S>(r1, X_W1, r2, X_W2);
}

template <typename S>
bool constructorThrowsInvalidArgument(S radius) {
  try {
    Disk<S> disk(radius);
  } catch (const std::invalid_argument&) {
    return true;
  }
  return false;
}

/// What the hook answers a signed request on intersecting disks with: minus the
/// penetration depth and the deepest points; FCL's entry, for the indep solver,
/// replaces a negative answer's points by collide()'s contact point.
template <typename S>
void expectPenetration(const DiskPairInput<S>& in, fcl::GJKSolverType solver,
                       fcl_disk::DiskDistanceResult<S>& expected) {
  const auto penetration = fcl_disk::diskPenetration<S>(in.r1, in.X_W1, in.r2, in.X_W2);
  expected.distance = penetration.signed_distance;
  expected.p_W1 = penetration.p_W1;
  expected.p_W2 = penetration.p_W2;
  if (solver == fcl::GST_INDEP && penetration.signed_distance < 0) {
    fcl_disk::DiskContact<S> contact;
    fcl_disk::intersectDisks<S>(in.r1, in.X_W1, in.r2, in.X_W2, &contact);
    expected.distance = -contact.penetration_depth;
    expected.p_W1 = expected.p_W2 = contact.pos;
  }
}

template <typename S>
void checkDistance(const DiskPairInput<S>& in, DiskDistanceMethod method, bool signed_distance,
                   const Disk<S>& disk1, const Disk<S>& disk2, const fcl::CollisionObject<S>& o1,
                   const fcl::CollisionObject<S>& o2) {
  const auto solved = selectedSolver<S>(method, in.r1, in.X_W1, in.r2, in.X_W2);
  for (const auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
    auto expected = solved;
    // A depth not above the smallest normal S is reported as touching (FCL's
    // indep entry asserts a contact deeper than that behind every negative answer).
    if (signed_distance && !(solved.distance > 0) &&
        fcl_disk::intersectDisks<S>(in.r1, in.X_W1, in.r2, in.X_W2) &&
        -fcl_disk::diskPenetration<S>(in.r1, in.X_W1, in.r2, in.X_W2).signed_distance >
            std::numeric_limits<S>::min()) {
      expectPenetration(in, solver, expected);
    }
    fcl::DistanceRequest<S> request;
    request.gjk_solver_type = solver;
    request.enable_signed_distance = signed_distance;
    request.enable_nearest_points = true;
    fcl::DistanceResult<S> result;
    const S returned = fcl::distance(&o1, &o2, request, result);
    const S got = result.min_distance;
    const auto resultText = [&] {
      return std::string(solver == fcl::GST_LIBCCD ? "libccd" : "indep") +
             (method == DiskDistanceMethod::exact ? ", exact" : ", almohamad_selim") +
             (signed_distance ? ", signed" : "") + ": fcl::distance returned " +
             numberText(returned) + ", min_distance " + numberText(got) + ", nearest " +
             vectorText(result.nearest_points[0]) + ", " + vectorText(result.nearest_points[1]) +
             "; solver distance " + numberText(expected.distance) + ", points " +
             vectorText(expected.p_W1) + ", " + vectorText(expected.p_W2);
    };
    const bool left_at_max = got == std::numeric_limits<S>::max();  // update() skipped a NaN
    if (std::isnan(expected.distance) || verdictOf(in) == Verdict::no_disk_pair) {
      // NaN bits may differ (the hook writes its own NaN): compared as NaN.
      require(std::isnan(got) || (!FCL_DISK_FUZZ_HOOK_PROPAGATES_NAN && left_at_max),
              "hook: a pair the solver answers with NaN gives min_distance NaN", in,
              resultText);
      continue;
    }
    require(sameBits(got, expected.distance) && sameBits(returned, expected.distance),
            "hook: fcl::distance == the selected solver's distance, bit for bit", in,
            resultText);
    require(sameBits(result.nearest_points[0], expected.p_W1) &&
                sameBits(result.nearest_points[1], expected.p_W2),
            "hook: nearest points == the selected solver's points, bit for bit", in, resultText);
    require(result.o1 == &disk1 && result.o2 == &disk2,
            "hook: result.o1, o2 are the two disks, in order", in, resultText);
  }
}

template <typename S>
void checkCollision(const DiskPairInput<S>& in, const Disk<S>& disk1, const Disk<S>& disk2,
                    const fcl::CollisionObject<S>& o1, const fcl::CollisionObject<S>& o2) {
  fcl_disk::DiskContact<S> expected;
  const bool intersects = fcl_disk::intersectDisks<S>(in.r1, in.X_W1, in.r2, in.X_W2, &expected);
  for (const auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
    fcl::CollisionRequest<S> request(1, /*enable_contact=*/true);
    request.gjk_solver_type = solver;
    fcl::CollisionResult<S> result;
    fcl::collide(&o1, &o2, request, result);
    const auto resultText = [&] {
      std::string text = std::string(solver == fcl::GST_LIBCCD ? "libccd" : "indep") +
                         ": fcl::collide contacts " + std::to_string(result.numContacts()) +
                         "; intersectDisks " + (intersects ? "true" : "false");
      if (result.numContacts() > 0) {
        const auto& c = result.getContact(0);
        text += "; contact pos " + vectorText(c.pos) + ", normal " + vectorText(c.normal) +
                ", depth " + numberText(c.penetration_depth);
      }
      return text;
    };
    if (verdictOf(in) == Verdict::no_disk_pair) {
      require(result.numContacts() == 0, "hook: a pair describing no disk pair gives no contact",
              in, resultText);
    }
    require(result.numContacts() == (intersects ? 1u : 0u),
            "hook: fcl::collide == intersectDisks()", in, resultText);
    if (!intersects) continue;
    const auto& contact = result.getContact(0);
    require(sameBits(contact.pos, expected.pos) && sameBits(contact.normal, expected.normal) &&
                sameBits(contact.penetration_depth, expected.penetration_depth),
            "hook: the contact is intersectDisks()'s, bit for bit", in, resultText);
    require(contact.o1 == &disk1 && contact.o2 == &disk2,
            "hook: contact.o1, o2 are the two disks, in order", in, resultText);
  }
}

/// Disk 1, disk 2 and then `extra` more, each placed relative to the previous
/// as disk 2 is to disk 1 (radii alternating), in a DynamicAABBTree manager:
/// its distance is the least pair distance and it reports a collision when a
/// pair collides (valid input only: FCL's own tree code is not under test).
template <typename S>
void checkBroadphase(const DiskPairInput<S>& in, DiskDistanceMethod method, int extra) {
  using E = Eps<S>;
  const Pose3d X_W1 = toDouble(in.X_W1), X_W2 = toDouble(in.X_W2);
  const Pose3d X_12 = X_W1.inverse(Eigen::Isometry) * X_W2;
  std::vector<fcl::Transform3<S>> poses = {in.X_W1, in.X_W2};
  std::vector<S> radii = {in.r1, in.r2};
  Pose3d X_WLast = X_W2;
  for (int k = 0; k < extra; ++k) {
    X_WLast = X_WLast * X_12;
    poses.push_back(X_WLast.template cast<S>());
    radii.push_back(radii[radii.size() - 2]);
  }
  // FCL's broadphase squares coordinate differences in S (AABB distances):
  // past sqrt(max()) / 4 they overflow to inf and prune pairs wrongly (float
  // at 1.6e19: corpus/fuzz_hook/regression-float-broadphase-overflow),
  // which is FCL's limit, not fcl_disk's.
  const double broadphase_limit = std::sqrt(double(std::numeric_limits<S>::max())) / 4;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (!(poses[i].translation().template cast<double>().cwiseAbs().maxCoeff() +
              double(radii[i]) <= broadphase_limit))
      return;
  }

  std::vector<std::shared_ptr<Disk<S>>> disks;
  std::vector<std::unique_ptr<fcl::CollisionObject<S>>> objects;
  fcl::DynamicAABBTreeCollisionManager<S> manager;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    disks.push_back(std::make_shared<Disk<S>>(radii[i]));
    objects.push_back(std::make_unique<fcl::CollisionObject<S>>(disks.back(), poses[i]));
    manager.registerObject(objects.back().get());
  }
  manager.setup();

  // Every pair in both orders: the manager may visit either.
  double least_low = std::numeric_limits<double>::infinity(), least_high = least_low;
  bool must_collide = false, may_collide = false;
  double scene = 0.0;  // the largest |c_i| + r_i: no floor, the bounds are relative
  for (std::size_t i = 0; i < poses.size(); ++i) {
    scene = std::max(scene, double(poses[i].translation().template cast<double>().norm()) +
                                double(radii[i]));
    for (std::size_t j = i + 1; j < poses.size(); ++j) {
      const double d_ij = selectedSolver<S>(method, radii[i], poses[i], radii[j], poses[j]).distance;
      const double d_ji = selectedSolver<S>(method, radii[j], poses[j], radii[i], poses[i]).distance;
      least_low = std::min(least_low, std::min(d_ij, d_ji));
      least_high = std::min(least_high, std::max(d_ij, d_ji));
      const bool hit_ij = fcl_disk::intersectDisks<S>(radii[i], poses[i], radii[j], poses[j]);
      const bool hit_ji = fcl_disk::intersectDisks<S>(radii[j], poses[j], radii[i], poses[i]);
      may_collide |= hit_ij || hit_ji;
      // The manager only tests pairs whose AABBs (its own, rounded) overlap.
      must_collide |= hit_ij && hit_ji && objects[i]->getAABB().overlap(objects[j]->getAABB());
    }
  }

  fcl::DefaultDistanceData<S> distance_data;
  manager.distance(&distance_data, fcl::DefaultDistanceFunction<S>);
  const double got = distance_data.result.min_distance;
  // AABB culling in S may drop a pair whose box rounding cut off its nearest
  // point: a few ulps of the scene.
  const double culling = kBoundSafetyFactor * E::kPoseRoundingRelative * scene;
  const auto chainText = [&] {
    return std::to_string(poses.size()) + " disks: manager distance " + numberText(got) +
           ", least pair distance in [" + numberText(least_low) + ", " + numberText(least_high) +
           "]; may collide " + (may_collide ? "yes" : "no") + ", must collide " +
           (must_collide ? "yes" : "no");
  };
  require(got >= least_low && got <= least_high + culling,
          "hook: the broadphase distance is the least pair distance", in, chainText);

  fcl::DefaultCollisionData<S> collision_data;
  manager.collide(&collision_data, fcl::DefaultCollisionFunction<S>);
  const bool found = collision_data.result.isCollision();
  require(!must_collide || found, "hook: the broadphase finds a colliding pair", in, chainText);
  require(!found || may_collide, "hook: the broadphase collision is a colliding pair", in,
          chainText);
}

template <typename S>
void checkHook(const DiskPairInput<S>& in, ByteReader& options) {
  if (!in.radiiValid()) {
    for (const S r : {in.r1, in.r2}) {
      require(constructorThrowsInvalidArgument(r) == !DiskPairInput<S>::radiusValid(r),
              "hook: Disk(r) throws std::invalid_argument iff r is out of range", in);
    }
    return;
  }
  const int option = options.byte();
  const DiskDistanceMethod method =
      (option & 1) ? DiskDistanceMethod::almohamad_selim : DiskDistanceMethod::exact;
  const bool signed_distance = option & 2;
  const int extra_disks = ((option >> 2) & 3) % 3;

  fcl_disk::registerDiskFunctions(method);
  const auto disk1 = std::make_shared<Disk<S>>(in.r1);
  const auto disk2 = std::make_shared<Disk<S>>(in.r2);
  const fcl::CollisionObject<S> o1(disk1, in.X_W1), o2(disk2, in.X_W2);
  checkDistance(in, method, signed_distance, *disk1, *disk2, o1, o2);
  checkCollision(in, *disk1, *disk2, o1, o2);
  // The chain composes the rotations: only for our constructed (orthonormal) ones.
  if (fullyChecked(in) && in.rotations_orthonormal) checkBroadphase(in, method, extra_disks);
}

}  // namespace
}  // namespace fcl_disk_fuzz

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  fcl_disk::registerDiskFunctions();  // install once, outside the measured inputs
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fcl_disk_fuzz::forBothScalars(data, size,
                                       [](const auto& pair, fcl_disk_fuzz::ByteReader& options) {
                                         fcl_disk_fuzz::checkHook(pair, options);
                                       });
}
