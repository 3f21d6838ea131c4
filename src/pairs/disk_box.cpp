// Disk - fcl::Box: closed forms where they certify, else the generic solver with
// the box's projection (clamping in the box frame) and support (a vertex).
// docs/disk_shape_distance.md, section 4.
#include "../disk_shape_pair.h"
#include "feature_candidates.h"
#include "../leaf_solvers.h"

#include <vector>

namespace fcl_disk {
namespace internal {
namespace {

/// The solid box {|y_i| <= half_i}, in its frame.
struct BoxTarget {
  Vec3 half;

  Projection project(const Vec3& y) const {
    Vec3 q;
    // psi's Hessian: diagonal, 1 along each clamped axis.
    Vec3 clamped;
    for (int i = 0; i < 3; ++i) {
      q[i] = std::clamp(y[i], -half[i], half[i]);
      clamped[i] = q[i] != y[i] ? 1.0 : 0.0;
    }
    return Projection{q, FactoredHessian::diagonalOf(clamped)};
  }

  Vec3 support(const Vec3& w) const {
    // Ties (w perpendicular to an axis) take the + side.
    return Vec3(w.x() < 0.0 ? -half.x() : half.x(), w.y() < 0.0 ? -half.y() : half.y(),
                w.z() < 0.0 ? -half.z() : half.z());
  }

  /// The six faces, for the nearly-parallel candidates: normal +-e_i, corners
  /// in order around the face.
  template <typename Visit>
  void forEachFace(Visit&& visit) const {
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      for (const double side : {1.0, -1.0}) {
        Vec3 normal = Vec3::Zero();
        normal[i] = side;
        visit(normal, 4, [&](int corner) {
          Vec3 x;
          x[i] = side * half[i];
          x[j] = (corner == 0 || corner == 3) ? half[j] : -half[j];
          x[k] = corner < 2 ? half[k] : -half[k];
          return x;
        });
      }
    }
  }
};

template <typename S>
struct BoxTraits {
  static bool valid(const fcl::Box<S>& box) {
    return areValidShapeLengths({double(box.side.x()), double(box.side.y()), double(box.side.z())});
  }
  static double boundingRadius(const fcl::Box<S>& box) {
    return 0.5 * box.side.template cast<double>().norm();
  }
  static double inflation(const fcl::Box<S>&) { return 0.0; }
  /// A corner, an edge or a face nearest a disk point, certified without the
  /// generic solver (alignedBoxToDisk, src/environment_bounds.h). Flattened:
  /// its helpers are inlined here and the box's centre folds to the constant
  /// 0, which takes fewer instructions and less time than the calls
  /// (docs/performance.md, "A Disk against FCL's primitives").
  [[gnu::flatten]] static LeafToDisk closedForm(const DiskInShape& disk, const fcl::Box<S>& box,
                                                double scale) {
    return alignedBoxToDisk(disk, Vec3::Zero(), 0.5 * box.side.template cast<double>(), scale);
  }
  static BoxTarget target(const fcl::Box<S>& box) {
    return BoxTarget{0.5 * box.side.template cast<double>()};
  }
  /// The directions among which the shortest separating translation lies
  /// (shortestSeparation adds the disk's normals and both signs), so the contact's
  /// depth is the exact penetration depth. The box's support h(-w) = -sum
  /// half_i |w_i| is kinked on the circles w_i = 0: a corner is the support
  /// inside each octant, an edge on an arc, a face at +-e_i. The face normals,
  /// and the candidates of the 8 corners and the 12 edge lines
  /// (feature_candidates.h; docs/penetration_depth.md, section 7).
  template <typename Search>
  static void contactDirections(const BoxTarget& target, const DiskInShape& disk,
                                Search* directions) {
    for (int i = 0; i < 3; ++i) directions->push_back(Vec3::Unit(i));
    const Vec3& half = target.half;
    for (const double x : {-half.x(), half.x()}) {
      for (const double y : {-half.y(), half.y()}) {
        for (const double z : {-half.z(), half.z()}) addVertexCandidates(disk, Vec3(x, y, z), directions);
      }
    }
    for (int i = 0; i < 3; ++i) {  // the 4 edges along e_i, through (0, +-half_j, +-half_k)
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      for (const double side_j : {-1.0, 1.0}) {
        for (const double side_k : {-1.0, 1.0}) {
          Vec3 point = Vec3::Zero();
          point[j] = side_j * half[j];
          point[k] = side_k * half[k];
          addEdgeLineCandidates(disk, point, Vec3::Unit(i), directions);
        }
      }
    }
  }
};

}  // namespace

template <typename S>
struct DiskShapePair<fcl::Box<S>> : GenericDiskShapePair<S, fcl::Box<S>, BoxTraits<S>> {};

DiskShapeSolution solveDiskBox(const DiskInShape& disk, const Vec3& half) {
  return DiskShapePair<fcl::Box<double>>::solveInShapeFrame(disk, fcl::Box<double>(2.0 * half),
                                                              /*try_closed_form=*/false);
}

bool intersectDiskBox(const DiskInShape& disk, const Vec3& half, FrameContact* contact) {
  return DiskShapePair<fcl::Box<double>>::intersectInShapeFrame(disk, fcl::Box<double>(2.0 * half),
                                                               contact, /*try_early_exit=*/false);
}

}  // namespace internal
}  // namespace fcl_disk

FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::Box)
