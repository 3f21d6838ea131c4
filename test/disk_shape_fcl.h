// The test-side shapes of disk_shape_oracle.h as FCL shapes, and
// diskShapeDistance() on any of them: shared by the disk-shape tests and the
// fuzz target. Depends on FCL and fcl_disk's public header.
#pragma once

#include <fcl_disk/disk_shape_distance.h>

#include <cstdlib>
#include <memory>
#include <vector>

#include "disk_shape_oracle.h"

namespace fcl_disk_test {
namespace oracle {

/// The FCL shape for `s` (FCL takes full lengths where `s` holds halves).
template <typename S>
std::shared_ptr<fcl::ShapeBase<S>> toFcl(const Shape& s) {
  const auto v = [](const V3& x) { return fcl::Vector3<S>(S(x.x()), S(x.y()), S(x.z())); };
  switch (s.kind) {
    case Kind::sphere: return std::make_shared<fcl::Sphere<S>>(S(s.dims.x()));
    case Kind::box:
      return std::make_shared<fcl::Box<S>>(S(2 * s.dims.x()), S(2 * s.dims.y()), S(2 * s.dims.z()));
    case Kind::capsule: return std::make_shared<fcl::Capsule<S>>(S(s.dims.x()), S(2 * s.dims.y()));
    case Kind::cylinder: return std::make_shared<fcl::Cylinder<S>>(S(s.dims.x()), S(2 * s.dims.y()));
    case Kind::cone: return std::make_shared<fcl::Cone<S>>(S(s.dims.x()), S(2 * s.dims.y()));
    case Kind::ellipsoid:
      return std::make_shared<fcl::Ellipsoid<S>>(S(s.dims.x()), S(s.dims.y()), S(s.dims.z()));
    case Kind::convex: {
      auto vertices = std::make_shared<std::vector<fcl::Vector3<S>>>();
      for (const V3& x : s.vertices) vertices->push_back(v(x));
      auto faces = std::make_shared<std::vector<int>>();
      for (const auto& face : s.faces) {
        faces->push_back(int(face.size()));
        faces->insert(faces->end(), face.begin(), face.end());
      }
      return std::make_shared<fcl::Convex<S>>(vertices, int(s.faces.size()), faces);
    }
    case Kind::halfspace: return std::make_shared<fcl::Halfspace<S>>(v(s.n), S(s.d));
    case Kind::plane: return std::make_shared<fcl::Plane<S>>(v(s.n), S(s.d));
    case Kind::triangle:
      return std::make_shared<fcl::TriangleP<S>>(v(s.vertices[0]), v(s.vertices[1]),
                                                 v(s.vertices[2]));
  }
  return nullptr;
}

/// Calls f(shape as its FCL class) for an FCL primitive.
template <typename S, typename F>
auto withShapeClass(const fcl::ShapeBase<S>& shape, F f) {
  switch (shape.getNodeType()) {
    case fcl::GEOM_SPHERE: return f(static_cast<const fcl::Sphere<S>&>(shape));
    case fcl::GEOM_BOX: return f(static_cast<const fcl::Box<S>&>(shape));
    case fcl::GEOM_CAPSULE: return f(static_cast<const fcl::Capsule<S>&>(shape));
    case fcl::GEOM_CYLINDER: return f(static_cast<const fcl::Cylinder<S>&>(shape));
    case fcl::GEOM_CONE: return f(static_cast<const fcl::Cone<S>&>(shape));
    case fcl::GEOM_ELLIPSOID: return f(static_cast<const fcl::Ellipsoid<S>&>(shape));
    case fcl::GEOM_CONVEX: return f(static_cast<const fcl::Convex<S>&>(shape));
    case fcl::GEOM_HALFSPACE: return f(static_cast<const fcl::Halfspace<S>&>(shape));
    case fcl::GEOM_PLANE: return f(static_cast<const fcl::Plane<S>&>(shape));
    case fcl::GEOM_TRIANGLE: return f(static_cast<const fcl::TriangleP<S>&>(shape));
    default: std::abort();  // not a primitive a Disk is answered against
  }
}

template <typename S>
fcl_disk::DiskShapeDistanceResult<S> diskShapeDistanceAny(S r, const fcl::Transform3<S>& X_WD,
                                                          const fcl::ShapeBase<S>& shape,
                                                          const fcl::Transform3<S>& X_WS) {
  return withShapeClass(shape, [&](const auto& typed) {
    return fcl_disk::diskShapeDistance(r, X_WD, typed, X_WS);
  });
}

template <typename S>
bool diskShapeIntersectAny(S r, const fcl::Transform3<S>& X_WD, const fcl::ShapeBase<S>& shape,
                           const fcl::Transform3<S>& X_WS) {
  return withShapeClass(shape, [&](const auto& typed) {
    return fcl_disk::diskShapeIntersect(r, X_WD, typed, X_WS);
  });
}

}  // namespace oracle
}  // namespace fcl_disk_test
