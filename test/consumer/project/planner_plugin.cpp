// planner_plugin: a module that links fcl_disk, loaded with dlopen() by a host that
// links libfcl only (consumer_dlopen_host), as a planner loads a geometry plugin.
#include <cstdio>
#include <exception>
#include <string>

#include "consumer_checks.h"

extern "C" {

/// Runs every check with queries made by the plugin's own code. `baseline`: FCL's
/// answers on real cylinders computed by the host before the plugin was loaded, or
/// null to compute them here (before any Disk exists). Returns the failure count.
__attribute__((visibility("default"))) int planner_plugin_run_checks(
    const char* label, const consumer::CylinderBaseline* baseline) {
  try {
    consumer::CylinderBaseline own;
    if (!baseline) {
      own = consumer::computeCylinderBaseline();
      baseline = &own;
    }
    return consumer::runAllChecks(label, consumer::linkedDiskApi(), *baseline);
  } catch (const std::exception& e) {
    std::printf("planner_plugin: FAILED with exception: %s\n", e.what());
    return 1000;
  }
}

/// The plugin's Disk factory and fcl_disk solvers, for queries made by the host.
__attribute__((visibility("default"))) const consumer::DiskApi* planner_plugin_disk_api() {
  return &consumer::linkedDiskApi();
}

}  // extern "C"
