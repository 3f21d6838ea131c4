// consumer_disk_first / consumer_fcl_first: the same program, linked with
// fcl_disk before or after libfcl (CONSUMER_EXPECT_FIRST says which).
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "consumer_checks.h"

int main() {
  try {
    // FCL's answers on real cylinders, before any Disk exists in this process.
    const consumer::CylinderBaseline baseline = consumer::computeCylinderBaseline();

    int failures = 0;
    // The link order this binary was built to test must be the load order.
    const auto objects = consumer::loadedObjects();
    const int fcl = consumer::loadedIndex(objects, "libfcl.so");
    const int disk = consumer::loadedIndex(objects, "libfcl_disk.so");
    const std::string expect = CONSUMER_EXPECT_FIRST;
    const bool order_ok = fcl >= 0 && disk >= 0 && (expect == "fcl_disk" ? disk < fcl : fcl < disk);
    failures += consumer::report(
        order_ok, std::string(CONSUMER_BINARY_NAME) + ": link map has libfcl_disk at " +
                      std::to_string(disk) + ", libfcl at " + std::to_string(fcl) + " (want " +
                      expect + " first)");
    // It must be the installed fcl_disk, not the build tree's.
    auto real = [](const std::string& path) {
      char buffer[PATH_MAX];
      return realpath(path.c_str(), buffer) ? std::string(buffer) : std::string();
    };
    const std::string lib = disk >= 0 ? real(objects[disk]) : std::string();
    const std::string want_dir = real(CONSUMER_FCL_DISK_LIBDIR);
    failures += consumer::report(!want_dir.empty() && lib.rfind(want_dir + "/", 0) == 0,
                                 "libfcl_disk loaded from " + lib + " (installed: " + want_dir + ")");

    failures += consumer::runAllChecks(CONSUMER_BINARY_NAME, consumer::linkedDiskApi(), baseline);
    std::printf("%s: %s\n", CONSUMER_BINARY_NAME, failures == 0 ? "ALL CHECKS PASSED" : "FAILED");
    return failures == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::printf("%s: FAILED with exception: %s\n", CONSUMER_BINARY_NAME, e.what());
    return 2;
  }
}
