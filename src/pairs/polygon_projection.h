// Internal: projection onto a segment and onto a convex polygon in 3-D, with psi's
// Hessian (I - D proj), shared by the triangle and convex-polytope pairs.
#pragma once

#include "../disk_shape_solver.h"

namespace fcl_disk {
namespace internal {

/// Nearest point of the segment a-b to x: on the open segment psi's Hessian is
/// I - e e^T (e the unit direction), at an end (or a zero-length segment) I.
inline Projection projectOntoSegment(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 edge = b - a;
  const double length_squared = edge.squaredNorm();
  const double t = length_squared > 0.0 ? edge.dot(x - a) / length_squared : 0.0;
  if (t > 0.0 && t < 1.0) {
    return Projection{a + t * edge,
                      FactoredHessian::identity().add(-1.0 / length_squared, edge)};
  }
  return Projection{t <= 0.0 ? a : b, FactoredHessian::identity()};
}

/// Nearest point of the closed convex polygon with vertices `vertex(0..count-1)`
/// (in order around it) and normal `normal` (any length; zero for a degenerate
/// polygon) to x: the foot of x on the plane if it lies inside every edge (then
/// psi's Hessian is n n^T), else the nearest point of the boundary.
template <typename VertexAt>
Projection projectOntoPolygon(const Vec3& x, int count, VertexAt vertex, const Vec3& normal) {
  const double normal_squared = normal.squaredNorm();
  if (normal_squared > 0.0) {
    bool inside = true;
    for (int i = 0; i < count && inside; ++i) {
      const Vec3 from = vertex(i), to = vertex((i + 1) % count);
      inside = normal.dot((to - from).cross(x - from)) >= 0.0;
    }
    if (inside) {
      const Vec3 on_plane = x - (normal.dot(x - vertex(0)) / normal_squared) * normal;
      return Projection{on_plane, FactoredHessian().add(1.0 / normal_squared, normal)};
    }
  }
  Projection best{vertex(0), FactoredHessian::identity()};
  double best_squared = (x - best.q).squaredNorm();
  for (int i = 0; i < count; ++i) {
    const Projection on_edge = projectOntoSegment(x, vertex(i), vertex((i + 1) % count));
    const double squared = (x - on_edge.q).squaredNorm();
    if (squared < best_squared) best = on_edge, best_squared = squared;
  }
  return best;
}

}  // namespace internal
}  // namespace fcl_disk
