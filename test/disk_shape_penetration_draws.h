// The random disk-shape poses of test_disk_shape_penetration, shared with
// fcl_disk_report's penetration table (bench/disk_shape_penetration_cases.h):
// poses with a uniform rotation and a centre in a ball, and a shape of each
// kind with an exact penetration depth, of size ~0.5, so that a disk of radius
// 0.2..1 at a centre in the unit ball meets a good share of them.
#pragma once

#include <fcl/common/types.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/plane.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "test_random.h"

namespace fcl_disk_shape_penetration_draws {

using fcl_disk_test::Random;
using Vd = Eigen::Vector3d;

template <typename S>
fcl::Transform3<S> randomPose(Random& rng, double reach) {
  fcl::Transform3<S> X = fcl::Transform3<S>::Identity();
  X.linear() = rng.rotation().cast<S>();
  X.translation() = rng.inBall(reach).cast<S>();
  return X;
}

/// Random shapes of size ~0.5 at centres in the unit ball, a disk of radius
/// 0.2..1, so that a good share of poses intersect.
template <typename S>
fcl::Sphere<S> randomShape(Random& rng, fcl::Sphere<S>*) {
  return fcl::Sphere<S>(S(rng.uniform(0.05, 1.0)));
}
template <typename S>
fcl::Halfspace<S> randomShape(Random& rng, fcl::Halfspace<S>*) {
  return fcl::Halfspace<S>(rng.unitVector().cast<S>(), S(rng.uniform(-0.5, 0.5)));
}
template <typename S>
fcl::Capsule<S> randomShape(Random& rng, fcl::Capsule<S>*) {
  return fcl::Capsule<S>(S(rng.uniform(0.0, 0.5)), S(rng.uniform(0.0, 2.0)));
}
template <typename S>
fcl::Cylinder<S> randomShape(Random& rng, fcl::Cylinder<S>*) {
  return fcl::Cylinder<S>(S(rng.uniform(0.05, 1.0)), S(rng.uniform(0.0, 2.0)));
}
template <typename S>
fcl::Cone<S> randomShape(Random& rng, fcl::Cone<S>*) {
  return fcl::Cone<S>(S(rng.uniform(0.0, 1.0)), S(rng.uniform(0.0, 2.0)));
}
template <typename S>
fcl::Plane<S> randomShape(Random& rng, fcl::Plane<S>*) {
  return fcl::Plane<S>(rng.unitVector().cast<S>(), S(rng.uniform(-0.5, 0.5)));
}
template <typename S>
fcl::Box<S> randomShape(Random& rng, fcl::Box<S>*) {
  return fcl::Box<S>(S(rng.uniform(0.0, 1.2)), S(rng.uniform(0.0, 1.2)), S(rng.uniform(0.0, 1.2)));
}
template <typename S>
fcl::TriangleP<S> randomShape(Random& rng, fcl::TriangleP<S>*) {
  return fcl::TriangleP<S>(rng.inBall(0.8).cast<S>(), rng.inBall(0.8).cast<S>(),
                           rng.inBall(0.8).cast<S>());
}
/// A tetrahedron, or a prism over a triangle with its top shifted (planar
/// parallelogram sides), in the ball of radius 1; faces counter-clockwise seen
/// from outside. Coordinates are multiples of kConvexGrid, so that every vertex,
/// and so every side's planarity, is exact in float too (the solvers take a
/// face to be the plane of its Newell normal).
constexpr double kConvexGrid = 1.0 / 1024;
template <typename S>
fcl::Convex<S> randomShape(Random& rng, fcl::Convex<S>*) {
  const auto on_grid = [&](double reach) {
    Vd x = rng.inBall(reach);
    for (int i = 0; i < 3; ++i) x[i] = std::round(x[i] / kConvexGrid) * kConvexGrid;
    return x;
  };
  auto vertices = std::make_shared<std::vector<fcl::Vector3<S>>>();
  std::vector<std::vector<int>> faces;
  Vd base[3];
  for (;;) {
    for (Vd& x : base) x = on_grid(0.5);
    if ((base[1] - base[0]).cross(base[2] - base[0]).norm() > 0.05) break;
  }
  const Vd base_normal = (base[1] - base[0]).cross(base[2] - base[0]).normalized();
  Vd lift;
  do lift = on_grid(0.5);
  while (std::abs(lift.dot(base_normal)) < 0.1);
  if (rng.uniform(0.0, 1.0) < 0.5) {
    for (const Vd& x : base) vertices->push_back(x.cast<S>());
    vertices->push_back((base[0] + lift).cast<S>());
    faces = {{0, 1, 2}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  } else {
    for (const Vd& x : base) vertices->push_back(x.cast<S>());
    for (const Vd& x : base) vertices->push_back((x + lift).cast<S>());
    faces = {{0, 1, 2}, {3, 4, 5}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}};
  }
  Vd centroid = Vd::Zero();
  for (const auto& x : *vertices) centroid += x.template cast<double>();
  centroid /= double(vertices->size());
  auto list = std::make_shared<std::vector<int>>();
  for (auto& face : faces) {
    const Vd a = (*vertices)[face[0]].template cast<double>();
    const Vd normal = ((*vertices)[face[1]].template cast<double>() - a)
                          .cross((*vertices)[face[2]].template cast<double>() - a);
    if (normal.dot(a - centroid) < 0) std::reverse(face.begin(), face.end());
    list->push_back(int(face.size()));
    list->insert(list->end(), face.begin(), face.end());
  }
  return fcl::Convex<S>(vertices, int(faces.size()), list);
}

}  // namespace fcl_disk_shape_penetration_draws
