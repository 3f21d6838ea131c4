// Checks shared by every consumer binary of the installed fcl_disk package:
// consumer_disk_first, consumer_fcl_first, planner_plugin and consumer_dlopen_host.
//
// consumer_checks.cpp uses FCL only (no fcl_disk header), so the dlopen host, which
// links libfcl alone, compiles it too. Everything fcl_disk-specific reaches it
// through DiskApi: consumer_disk_api.cpp fills one in binaries that link fcl_disk,
// and the host gets the plugin's through dlsym.
#pragma once

#include <fcl/common/types.h>

#include <memory>
#include <string>
#include <vector>

namespace fcl {
template <typename S>
class CollisionGeometry;
}  // namespace fcl

namespace consumer {

/// exactDiskDistance()'s answer, in plain types.
template <typename S>
struct ExactAnswer {
  S distance{0};
  fcl::Vector3<S> p1{fcl::Vector3<S>::Zero()}, p2{fcl::Vector3<S>::Zero()};
};

/// intersectDisks()'s answer, in plain types.
template <typename S>
struct IntersectAnswer {
  bool intersect{false};
  fcl::Vector3<S> pos{fcl::Vector3<S>::Zero()}, normal{fcl::Vector3<S>::Zero()};
  S depth{0};
};

/// What a binary that links fcl_disk provides. Disks are created by the provider
/// (constructing a Disk registers fcl_disk's functions); queries on them are made
/// by whichever binary runs the checks.
struct DiskApi {
  const char* provider;  ///< which binary filled this in (for messages)
  std::shared_ptr<fcl::CollisionGeometry<double>> (*make_disk_d)(double radius);
  std::shared_ptr<fcl::CollisionGeometry<float>> (*make_disk_f)(float radius);
  ExactAnswer<double> (*exact_d)(double r1, const fcl::Transform3<double>& X_W1, double r2,
                                 const fcl::Transform3<double>& X_W2);
  ExactAnswer<float> (*exact_f)(float r1, const fcl::Transform3<float>& X_W1, float r2,
                                const fcl::Transform3<float>& X_W2);
  IntersectAnswer<double> (*intersect_d)(double r1, const fcl::Transform3<double>& X_W1,
                                         double r2, const fcl::Transform3<double>& X_W2);
  IntersectAnswer<float> (*intersect_f)(float r1, const fcl::Transform3<float>& X_W1, float r2,
                                        const fcl::Transform3<float>& X_W2);
  /// diskShapeDistance() against `shape` (a real fcl::Cylinder, a Box or a
  /// Halfspace): p1 on the disk, p2 on the shape.
  ExactAnswer<double> (*disk_shape_d)(double r, const fcl::Transform3<double>& X_WD,
                                      const fcl::CollisionGeometry<double>& shape,
                                      const fcl::Transform3<double>& X_WS);
  ExactAnswer<float> (*disk_shape_f)(float r, const fcl::Transform3<float>& X_WD,
                                     const fcl::CollisionGeometry<float>& shape,
                                     const fcl::Transform3<float>& X_WS);
};

/// The DiskApi of the binary this is linked into (consumer_disk_api.cpp; only in
/// binaries that link fcl_disk).
const DiskApi& linkedDiskApi();

/// One number produced by FCL on real fcl::Cylinder pairs.
struct LabeledValue {
  std::string label;
  double value;
  double tolerance;
};

/// FCL's answers on real cylinders (thick ones, and plain fcl::Cylinder(r, 0),
/// which is not a Disk) through every query path the checks use. Computed once
/// before any Disk exists: fcl_disk must leave all of them unchanged.
struct CylinderBaseline {
  std::vector<LabeledValue> values;
};
CylinderBaseline computeCylinderBaseline();

/// Runs every check, printing one line per check; returns the number of failures.
/// `baseline` must come from computeCylinderBaseline() before any Disk existed.
int runAllChecks(const std::string& label, const DiskApi& api, const CylinderBaseline& baseline,
                 bool float_tables_shared = true);

/// Shared objects loaded in this process, in link-map (= symbol lookup) order.
std::vector<std::string> loadedObjects();
/// Index in loadedObjects() of the first object whose file name starts with
/// `prefix` (e.g. "libfcl.so", "libfcl_disk.so"), or -1.
int loadedIndex(const std::vector<std::string>& objects, const std::string& prefix);
/// Prints the load order of libfcl and libfcl_disk, and which object plain
/// fcl::distance<double> / fcl::collide<double> bind to from this binary.
void printBindings(const std::string& label);

/// Prints "[PASS] what" or "[FAIL] what" and returns 0 / 1.
int report(bool ok, const std::string& what);

}  // namespace consumer
