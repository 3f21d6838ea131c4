// DiskApi for binaries that link fcl_disk: the only consumer source that includes
// fcl_disk's headers.
#include <fcl_disk/fcl_disk.h>

#include "consumer_checks.h"

#include <limits>

namespace consumer {
namespace {

template <typename S>
std::shared_ptr<fcl::CollisionGeometry<S>> makeDisk(S radius) {
  return std::make_shared<fcl_disk::Disk<S>>(radius);
}

template <typename S>
ExactAnswer<S> exact(S r1, const fcl::Transform3<S>& X_W1, S r2, const fcl::Transform3<S>& X_W2) {
  const fcl_disk::DiskDistanceResult<S> r = fcl_disk::exactDiskDistance(r1, X_W1, r2, X_W2);
  return {r.distance, r.p_W1, r.p_W2};
}

template <typename S>
IntersectAnswer<S> intersect(S r1, const fcl::Transform3<S>& X_W1, S r2,
                             const fcl::Transform3<S>& X_W2) {
  fcl_disk::DiskContact<S> contact;
  IntersectAnswer<S> answer;
  answer.intersect = fcl_disk::intersectDisks(r1, X_W1, r2, X_W2, &contact);
  if (answer.intersect) {
    answer.pos = contact.pos;
    answer.normal = contact.normal;
    answer.depth = contact.penetration_depth;
  }
  return answer;
}

template <typename S>
ExactAnswer<S> diskShape(S r, const fcl::Transform3<S>& X_WD,
                         const fcl::CollisionGeometry<S>& shape, const fcl::Transform3<S>& X_WS) {
  fcl_disk::DiskShapeDistanceResult<S> answer;
  switch (shape.getNodeType()) {
    case fcl::GEOM_CYLINDER:
      answer = fcl_disk::diskShapeDistance(r, X_WD, static_cast<const fcl::Cylinder<S>&>(shape), X_WS);
      break;
    case fcl::GEOM_BOX:
      answer = fcl_disk::diskShapeDistance(r, X_WD, static_cast<const fcl::Box<S>&>(shape), X_WS);
      break;
    case fcl::GEOM_HALFSPACE:
      answer =
          fcl_disk::diskShapeDistance(r, X_WD, static_cast<const fcl::Halfspace<S>&>(shape), X_WS);
      break;
    default:
      answer.distance = std::numeric_limits<S>::quiet_NaN();
  }
  return {answer.distance, answer.p_W_disk, answer.p_W_shape};
}

}  // namespace

const DiskApi& linkedDiskApi() {
  static const DiskApi api{CONSUMER_BINARY_NAME,  makeDisk<double>,  makeDisk<float>,
                           exact<double>,         exact<float>,      intersect<double>,
                           intersect<float>,      diskShape<double>, diskShape<float>};
  return api;
}

}  // namespace consumer
