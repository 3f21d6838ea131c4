// Disk - fcl::TriangleP (the leaf of meshes): the generic solver with the
// triangle's projection (its face, else its nearest edge) and support (a vertex).
// docs/disk_shape_distance.md, section 4.
#include "../disk_shape_pair.h"
#include "polygon_projection.h"

namespace fcl_disk {
namespace internal {
namespace {

/// The closed flat triangle, in its frame (a zero-area triangle is the union of
/// its edges).
struct TriangleTarget {
  std::array<Vec3, 3> vertices;
  Vec3 normal;  ///< (b - a) x (c - a), not normalised; zero when degenerate.

  Projection project(const Vec3& x) const {
    return projectOntoPolygon(x, 3, [this](int i) { return vertices[i]; }, normal);
  }

  Vec3 support(const Vec3& w) const {
    int best = 0;  // ties take the first vertex
    for (int i = 1; i < 3; ++i) {
      if (w.dot(vertices[i]) > w.dot(vertices[best])) best = i;
    }
    return vertices[best];
  }
};

template <typename S>
struct TriangleTraits {
  static bool valid(const fcl::TriangleP<S>& triangle) {
    bool valid = true;
    for (const auto* v : {&triangle.a, &triangle.b, &triangle.c}) {
      valid &= (v->array().abs() <= kMaxDiskLength<S>).all();
    }
    return valid;
  }
  static double boundingRadius(const fcl::TriangleP<S>& triangle) {
    return std::sqrt(std::max({triangle.a.template cast<double>().squaredNorm(),
                               triangle.b.template cast<double>().squaredNorm(),
                               triangle.c.template cast<double>().squaredNorm()}));
  }
  static double inflation(const fcl::TriangleP<S>&) { return 0.0; }
  static TriangleTarget target(const fcl::TriangleP<S>& triangle) {
    TriangleTarget target{{triangle.a.template cast<double>(), triangle.b.template cast<double>(),
                           triangle.c.template cast<double>()},
                          Vec3::Zero()};
    target.normal =
        (target.vertices[1] - target.vertices[0]).cross(target.vertices[2] - target.vertices[0]);
    return target;
  }
  /// The triangle's normal.
  static std::array<Vec3, 1> contactDirections(const TriangleTarget& triangle) {
    return {triangle.normal};
  }
};

}  // namespace

template <typename S>
struct DiskShapePair<fcl::TriangleP<S>>
    : GenericDiskShapePair<S, fcl::TriangleP<S>, TriangleTraits<S>> {};

}  // namespace internal
}  // namespace fcl_disk

FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::TriangleP)
