// libFuzzer target: fcl::distance and fcl::collide between a Disk and a triangle
// mesh (fcl::BVHModel of every BV type) or an octree (fcl::OcTree), as planners
// call them, double and float, either argument order, both solver types.
//
// Bytes: the geometry (eight BV types or the octree), a flags byte (scalar,
// argument order, solver type, raw mode), the disk (radius, rotation,
// centre), then 1..8 triangles (vertices in the unit cube around the mesh
// origin, sometimes snapped onto each other: zero-area triangles and slivers)
// or 1..24 octree cells (resolution 0.05..0.5), and the other geometry's pose.
// In raw mode the disk's radius and centre are IEEE bit patterns.
// Checks, for input that describes a pair: the distance equals the least
// diskShapeDistance over every triangle (fcl::TriangleP) or occupied cell
// (fcl::Box), so the traversal and its bounding volumes lose nothing; the
// nearest points lie on the disk and on the mesh (a triangle) or an occupied
// cell, on the sides result.o1 / o2 name (long-double distances of disk_shape_oracle.h);
// |p - q| == distance; collide reports a contact exactly when that least
// distance is 0 (outside the touching band), each contact's pos on both. Input
// that describes no pair (a NaN or out-of-range disk pose) must give a NaN
// distance and no contact. Bounds are loose multiples of the documented ones:
// the fuzzer hunts crashes, hangs and gross errors.
#include <fcl_disk/fcl_disk.h>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/octree/octree.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <octomap/octomap.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "disk_shape_oracle.h"
#include "fuzz_input.h"

namespace {

using namespace fcl_disk_test::oracle;
using fcl_disk_fuzz::ByteReader;

/// Abort thresholds relative to the scene: 1e3 times the documented 1e-12 in
/// double; in float 64 ulps (answers are rounded to float).
constexpr double kFuzzRelativeDouble = 1e-9;
constexpr double kFuzzRelativeFloat = 64 * 1.1920928955078125e-07;
/// Pairs closer than this many tolerances may be called touching or apart.
constexpr double kTouchingBand = 1e3;

[[noreturn]] void fail(const std::string& what, const std::string& detail) {
  std::fprintf(stderr, "invariant violated: %s\n  %s\n", what.c_str(), detail.c_str());
  std::abort();
}

M3 rotationFrom(ByteReader& in) {
  Eigen::Quaternion<Real> q(Real(in.fraction() - 0.5), Real(in.fraction() - 0.5),
                            Real(in.fraction() - 0.5), Real(in.fraction() - 0.5));
  if (!(q.norm() > 1e-3)) q = Eigen::Quaternion<Real>::Identity();
  return q.normalized().toRotationMatrix();
}

V3 pointFrom(ByteReader& in, Real half_width) {
  return V3(Real(2 * in.fraction() - 1), Real(2 * in.fraction() - 1), Real(2 * in.fraction() - 1)) *
         half_width;
}

/// What the other geometry is, in its frame: triangles or occupied cells.
struct Environment {
  std::vector<std::array<V3, 3>> triangles;
  std::vector<std::pair<V3, Real>> cells;  ///< centre, half side
};

template <typename S>
fcl::Transform3<S> poseOf(const M3& R, const V3& t) {
  fcl::Transform3<S> X = fcl::Transform3<S>::Identity();
  X.linear() = R.cast<S>();
  X.translation() = t.cast<S>();
  return X;
}

template <typename BV>
std::shared_ptr<fcl::CollisionGeometry<typename BV::S>> meshOf(Environment& environment) {
  using S = typename BV::S;
  auto mesh = std::make_shared<fcl::BVHModel<BV>>();
  mesh->beginModel();
  for (auto& triangle : environment.triangles) {
    for (V3& v : triangle) v = v.cast<S>().template cast<Real>();  // as stored
    mesh->addTriangle(triangle[0].cast<S>(), triangle[1].cast<S>(), triangle[2].cast<S>());
  }
  mesh->endModel();
  return mesh;
}

template <typename S>
std::shared_ptr<fcl::CollisionGeometry<S>> geometryOf(int kind, Environment& environment) {
  switch (kind) {
    case 0: return meshOf<fcl::OBBRSS<S>>(environment);
    case 1: return meshOf<fcl::RSS<S>>(environment);
    case 2: return meshOf<fcl::kIOS<S>>(environment);
    case 3: return meshOf<fcl::OBB<S>>(environment);
    case 4: return meshOf<fcl::AABB<S>>(environment);
    case 5: return meshOf<fcl::KDOP<S, 16>>(environment);
    case 6: return meshOf<fcl::KDOP<S, 18>>(environment);
    case 7: return meshOf<fcl::KDOP<S, 24>>(environment);
    default: break;
  }
  // The octree: the cells as octomap stores them (its own keys and sizes).
  auto tree = std::make_shared<octomap::OcTree>(double(environment.cells.front().second));
  std::vector<V3> wanted;
  for (const auto& cell : environment.cells) wanted.push_back(cell.first);
  for (const V3& centre : wanted) {
    tree->updateNode(octomap::point3d(float(centre.x()), float(centre.y()), float(centre.z())), true);
  }
  environment.cells.clear();
  for (auto it = tree->begin_leafs(); it != tree->end_leafs(); ++it) {
    if (!tree->isNodeOccupied(*it)) continue;
    environment.cells.emplace_back(V3(Real(it.getX()), Real(it.getY()), Real(it.getZ())),
                                   Real(it.getSize()) / 2);
  }
  return std::make_shared<fcl::OcTree<S>>(tree);
}

template <typename S>
void run(ByteReader& in, int kind, std::uint8_t flags) {
  const bool disk_first = flags & 2;
  const bool raw = (flags & 0x70) == 0x70;  // one input in eight
  const auto solver = (flags & 4) ? fcl::GST_INDEP : fcl::GST_LIBCCD;
  // The disk.
  Real r = Real(0.02 + in.fraction());
  const M3 R_WD = rotationFrom(in);
  V3 c_WD = pointFrom(in, 1.5);
  if (raw) {
    r = Real(in.raw<double>());
    c_WD = V3(Real(in.raw<double>()), Real(in.raw<double>()), Real(in.raw<double>()));
  }
  // The environment, in its frame E.
  Environment environment;
  if (kind < 8) {
    const int count = 1 + in.byte() % 8;
    std::vector<V3> corners;
    for (int t = 0; t < count; ++t) {
      std::array<V3, 3> triangle;
      for (V3& v : triangle) {
        const std::uint8_t snap = in.byte();
        // One vertex in four repeats an earlier one or lies on an earlier
        // edge's line: zero-area triangles and slivers.
        if (!corners.empty() && snap % 4 == 0) {
          v = corners[snap / 4 % corners.size()];
        } else if (corners.size() >= 2 && snap % 4 == 1) {
          const V3& a = corners[snap / 4 % corners.size()];
          const V3& b = corners[(snap / 4 + 1) % corners.size()];
          v = a + Real(3 * in.fraction() - 1) * (b - a);
        } else {
          v = pointFrom(in, 1);
        }
        corners.push_back(v);
      }
      environment.triangles.push_back(triangle);
    }
  } else {
    const Real side = Real(0.05 + 0.45 * in.fraction());
    const int count = 1 + in.byte() % 24;
    for (int i = 0; i < count; ++i) environment.cells.emplace_back(pointFrom(in, 1), side);
  }
  const M3 R_WE = rotationFrom(in);
  const V3 c_WE = pointFrom(in, 0.5);

  const auto geometry = geometryOf<S>(kind, environment);
  auto disk_shape = std::shared_ptr<fcl_disk::Disk<S>>();
  const S radius = S(r);
  if (!fcl_disk::isValidDiskRadius(radius)) return;  // Disk() throws: not a pair to query
  disk_shape = std::make_shared<fcl_disk::Disk<S>>(radius);
  const fcl::Transform3<S> X_WD = poseOf<S>(R_WD, c_WD), X_WE = poseOf<S>(R_WE, c_WE);
  fcl::CollisionObject<S> disk_object(disk_shape, X_WD), other(geometry, X_WE);
  fcl::CollisionObject<S>* o1 = disk_first ? &disk_object : &other;
  fcl::CollisionObject<S>* o2 = disk_first ? &other : &disk_object;

  fcl::DistanceRequest<S> distance_request;
  distance_request.gjk_solver_type = solver;
  fcl::DistanceResult<S> result;
  fcl::distance(o1, o2, distance_request, result);
  fcl::CollisionRequest<S> collision_request(8, true);
  collision_request.gjk_solver_type = solver;
  fcl::CollisionResult<S> contacts;
  fcl::collide(o1, o2, collision_request, contacts);

  std::ostringstream detail;
  detail.precision(17);
  detail << (std::is_same<S, float>::value ? "float" : "double") << " kind " << kind
         << (disk_first ? " disk first" : " disk second") << " r " << r << " c_WD "
         << c_WD.transpose().cast<double>() << " items "
         << (kind < 8 ? environment.triangles.size() : environment.cells.size()) << " distance "
         << result.min_distance;
  if (fcl_disk_fuzz::printInputs()) std::fprintf(stderr, "%s\n", detail.str().c_str());
  if (!fcl_disk::isValidDiskPose(X_WD)) {
    if (!std::isnan(double(result.min_distance)) || contacts.isCollision()) {
      fail("a pose describing no pair gives NaN and no contact", detail.str());
    }
    return;
  }
  if (kind == 8 && environment.cells.empty()) return;  // nothing occupied: FCL keeps max()

  // The least distance over every item, by the primitive solver.
  const Real far = std::max(c_WD.norm(), c_WE.norm());
  Real least = std::numeric_limits<Real>::infinity();
  Real bounding = 0;
  for (const auto& triangle : environment.triangles) {
    const fcl::TriangleP<S> item(triangle[0].cast<S>(), triangle[1].cast<S>(), triangle[2].cast<S>());
    least = std::min(least, Real(fcl_disk::diskShapeDistance(radius, X_WD, item, X_WE).distance));
    for (const V3& v : triangle) bounding = std::max(bounding, v.norm());
  }
  for (const auto& cell : environment.cells) {
    const S side = S(2 * cell.second);
    fcl::Transform3<S> X_WC = X_WE;
    X_WC.translation() = (X_WE * cell.first.cast<S>());
    least = std::min(least, Real(fcl_disk::diskShapeDistance(radius, X_WD, fcl::Box<S>(side, side, side), X_WC).distance));
    bounding = std::max(bounding, cell.first.norm() + std::sqrt(Real(3)) * cell.second);
  }
  const Real scale = r + bounding + (c_WD - c_WE).norm();
  const Real relative = std::is_same<S, float>::value ? kFuzzRelativeFloat : kFuzzRelativeDouble;
  const Real tolerance = relative * scale + 8 * Real(std::numeric_limits<S>::epsilon()) * far;
  if (!(std::abs(Real(result.min_distance) - least) <= tolerance)) {
    detail << " least " << double(least);
    fail("the distance is the least over the items", detail.str());
  }
  // The points: FCL names the mesh or octree o1 whatever the order.
  const bool disk_is_o1 = result.o1 == disk_shape.get();
  if (disk_is_o1 == (result.o2 == disk_shape.get())) fail("the disk is exactly one of o1, o2", detail.str());
  const V3 p_disk = result.nearest_points[disk_is_o1 ? 0 : 1].template cast<Real>();
  const V3 p_other = result.nearest_points[disk_is_o1 ? 1 : 0].template cast<Real>();
  const Disk disk{c_WD, R_WD.col(0), R_WD.col(1), r};
  Pose X_E;
  X_E.R = R_WE;
  X_E.t = c_WE;
  const auto on_environment = [&](const V3& p) {
    Real nearest = std::numeric_limits<Real>::infinity();
    for (const auto& triangle : environment.triangles) {
      Shape shape;
      shape.kind = Kind::triangle;
      shape.vertices = {triangle[0], triangle[1], triangle[2]};
      nearest = std::min(nearest, pointDistanceWorld(shape, X_E, p));
    }
    for (const auto& cell : environment.cells) {
      Shape shape;
      shape.kind = Kind::box;
      shape.dims = V3::Constant(cell.second);
      Pose X_C = X_E;
      X_C.t = X_E.toWorld(cell.first);
      nearest = std::min(nearest, pointDistanceWorld(shape, X_C, p));
    }
    return nearest;
  };
  if (!(pointToDisk(disk, p_disk) <= tolerance)) fail("the disk point lies on the disk", detail.str());
  if (!(on_environment(p_other) <= tolerance)) {
    detail << " point " << p_other.transpose().cast<double>() << " off by " << double(on_environment(p_other))
           << " least " << double(least) << " b1 " << result.b1 << " b2 " << result.b2 << " disk point "
           << p_disk.transpose().cast<double>();
    for (const auto& triangle : environment.triangles) {
      detail << "\n  triangle " << triangle[0].transpose().cast<double>() << " | "
             << triangle[1].transpose().cast<double>() << " | " << triangle[2].transpose().cast<double>();
    }
    detail << "\n  X_WE " << c_WE.transpose().cast<double>() << " R " << Eigen::Map<const Eigen::Matrix<Real, 1, 9>>(R_WE.data()).cast<double>();
    fail("the other point lies on the mesh or a cell", detail.str());
  }
  if (!(std::abs((p_disk - p_other).norm() - Real(result.min_distance)) <= 2 * tolerance)) {
    fail("|p - q| == distance", detail.str());
  }
  // Collision agrees with the least distance outside the touching band.
  const Real band = kTouchingBand * tolerance;
  // Distance 0 from both the brute force and the traversal (in float the two
  // frames round apart by ulps of the scene) means a contact.
  if (least == 0 && result.min_distance == 0 && !contacts.isCollision()) {
    fail("distance 0 means a contact", detail.str());
  }
  if (least > band && contacts.isCollision()) fail("apart means no contact", detail.str());
  for (std::size_t i = 0; i < contacts.numContacts(); ++i) {
    const V3 pos = contacts.getContact(i).pos.template cast<Real>();
    if (!(pointToDisk(disk, pos) <= band && on_environment(pos) <= band)) {
      fail("a contact lies on both", detail.str());
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ByteReader in(data, size);
  const int kind = in.byte() % 9;
  const std::uint8_t flags = in.byte();
  if (flags & 1) {
    run<float>(in, kind, flags);
  } else {
    run<double>(in, kind, flags);
  }
  return 0;
}
