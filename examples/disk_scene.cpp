// A small planner-style scene: disks next to FCL's own shapes (a ground
// halfspace among them), queried through plain fcl::distance / fcl::collide and a
// broadphase manager. Every pair with a disk is answered by fcl_disk.
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <fcl_disk/fcl_disk.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace {

using fcl::Transform3d;
using fcl::Vector3d;

Transform3d pose(const Vector3d& centre, const Vector3d& normal) {
  Transform3d X = Transform3d::Identity();
  X.translation() = centre;
  X.linear() = Eigen::Quaterniond::FromTwoVectors(Vector3d::UnitZ(), normal.normalized())
                   .toRotationMatrix();
  return X;
}

struct Named {
  std::string name;
  std::unique_ptr<fcl::CollisionObjectd> object;
  bool is_disk;
};

}  // namespace

int main() {
  // Creating a Disk registers fcl_disk's functions (method: exact).
  auto coin = std::make_shared<fcl_disk::Diskd>(0.5);
  auto plate = std::make_shared<fcl_disk::Diskd>(1.0);
  auto rotor_a = std::make_shared<fcl_disk::Diskd>(0.3);
  auto rotor_b = std::make_shared<fcl_disk::Diskd>(0.3);
  auto link = std::make_shared<fcl_disk::Diskd>(0.4);
  std::vector<Named> scene;
  auto add = [&](std::string name, std::shared_ptr<fcl::CollisionGeometryd> geometry,
                 const Transform3d& X) {
    const bool is_disk = dynamic_cast<const fcl_disk::Diskd*>(geometry.get()) != nullptr;
    scene.push_back(
        {std::move(name), std::make_unique<fcl::CollisionObjectd>(geometry, X), is_disk});
  };
  add("coin (tilted)", coin, pose({0, 0, 0}, {0, 1, 2}));
  add("plate", plate, pose({0, 0, -0.5}, {0, 0, 1}));
  add("rotor A", rotor_a, pose({2, 0, 0.2}, {0, 0, 1}));
  add("rotor B", rotor_b, pose({2.5, 0.1, 0.2}, {1, 0, 1}));
  add("link", link, pose({0.6, 0, -0.5}, {1, 0, 0}));  // crosses the plate like a chain link
  add("box", std::make_shared<fcl::Boxd>(0.4, 0.4, 0.4), pose({-2, 0, 0}, {0, 0, 1}));
  add("sphere", std::make_shared<fcl::Sphered>(0.25), pose({0, 2, 0}, {0, 0, 1}));
  add("capsule", std::make_shared<fcl::Capsuled>(0.1, 1.0), pose({1.2, 0.3, 0.4}, {0, 1, 0}));
  add("cylinder", std::make_shared<fcl::Cylinderd>(0.3, 0.6), pose({-1, 1, 0}, {1, 0, 0}));
  // The ground: z <= -1.2 (FCL's own GJK crashes on a flat cylinder against it).
  add("ground", std::make_shared<fcl::Halfspaced>(Vector3d::UnitZ(), -1.2),
      pose({0, 0, 0}, {0, 0, 1}));

  std::printf("fcl_disk example: %zu objects, disk method = %s\n\n", scene.size(),
              fcl_disk::registeredDiskDistanceMethod() == fcl_disk::DiskDistanceMethod::exact
                  ? "exact"
                  : "almohamad_selim");
  std::printf("%-14s %-14s %12s %9s   nearest points (world)\n", "object 1", "object 2",
              "distance", "collide");
  // Every pair with a disk (pairs of FCL's own shapes are FCL's: its sphere,
  // box and capsule against a halfspace crash in Debian's FCL 0.7).
  for (std::size_t i = 0; i < scene.size(); ++i) {
    for (std::size_t j = i + 1; j < scene.size(); ++j) {
      if (!scene[i].is_disk && !scene[j].is_disk) continue;
      fcl::DistanceRequestd distance_request;
      fcl::DistanceResultd distance_result;
      fcl::distance(scene[i].object.get(), scene[j].object.get(), distance_request,
                    distance_result);
      fcl::CollisionRequestd collision_request;
      fcl::CollisionResultd collision_result;
      fcl::collide(scene[i].object.get(), scene[j].object.get(), collision_request,
                   collision_result);
      const Vector3d& p = distance_result.nearest_points[0];
      const Vector3d& q = distance_result.nearest_points[1];
      std::printf("%-14s %-14s %12.6f %9s   (%.3f %.3f %.3f) (%.3f %.3f %.3f)\n",
                  scene[i].name.c_str(), scene[j].name.c_str(), distance_result.min_distance,
                  collision_result.isCollision() ? "yes" : "no", p.x(), p.y(), p.z(), q.x(),
                  q.y(), q.z());
    }
  }

  // The report's algorithm on the same tilted coin / plate pair, for contrast.
  const auto exact = fcl_disk::exactDiskDistance(0.5, scene[0].object->getTransform(), 1.0,
                                                 scene[1].object->getTransform());
  const auto report = fcl_disk::almohamadSelimDiskDistance(
      0.5, scene[0].object->getTransform(), 1.0, scene[1].object->getTransform());
  std::printf("\ncoin-plate: exact %.9f (certified gap %.1e), Almohamad-Selim 1994 %.9f\n",
              exact.distance, exact.certifiedGap(), report.distance);

  // Broadphase: all colliding pairs and the nearest pair of the scene (without
  // the ground, which FCL's own shapes cannot be queried against).
  fcl::DynamicAABBTreeCollisionManagerd manager;
  for (auto& entry : scene) {
    if (entry.name != "ground") manager.registerObject(entry.object.get());
  }
  manager.setup();
  fcl::DefaultCollisionData<double> collision_data;
  collision_data.request.num_max_contacts = 1000;
  manager.collide(&collision_data, fcl::DefaultCollisionFunction);
  fcl::DefaultDistanceData<double> distance_data;
  manager.distance(&distance_data, fcl::DefaultDistanceFunction);
  auto name_of = [&](const fcl::CollisionGeometryd* geometry) -> std::string {
    for (auto& entry : scene)
      if (entry.object->collisionGeometry().get() == geometry) return entry.name;
    return "?";
  };
  std::printf("broadphase collide: %zu contact(s)\n", collision_data.result.numContacts());
  std::printf("broadphase distance: min %.6f between %s and %s\n",
              distance_data.result.min_distance, name_of(distance_data.result.o1).c_str(),
              name_of(distance_data.result.o2).c_str());
  return 0;
}
