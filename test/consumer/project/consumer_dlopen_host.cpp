// consumer_dlopen_host: links libfcl only. It uses FCL first (so libfcl is loaded
// and its dispatch tables built in the global scope before fcl_disk exists), then
// dlopen()s planner_plugin, which links fcl_disk, and:
//   1. calls the plugin's checks (queries made by plugin code);
//   2. runs the same checks itself on the plugin's disks (queries made by host code,
//      which never linked fcl_disk), as a planner core does with plugin geometry.
//      Double queries go through libfcl's tables; float queries through the host's
//      own instances of FCL's float tables, which the plugin can only reach if the
//      host exports them (the same objects are linked with ENABLE_EXPORTS as
//      consumer_dlopen_host_exports).
// Usage: consumer_dlopen_host local|global [path/to/planner_plugin.so]
#include <dlfcn.h>

#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include "consumer_checks.h"

int main(int argc, char** argv) {
  if (argc < 2 || (std::strcmp(argv[1], "local") != 0 && std::strcmp(argv[1], "global") != 0)) {
    std::fprintf(stderr, "usage: %s local|global [plugin]\n", argv[0]);
    return 64;
  }
  const bool global = std::strcmp(argv[1], "global") == 0;
  const std::string mode = global ? "RTLD_NOW|RTLD_GLOBAL" : "RTLD_NOW|RTLD_LOCAL";
  const char* plugin = argc > 2 ? argv[2] : PLANNER_PLUGIN_PATH;
  try {
    int failures = 0;
    failures += consumer::report(
        consumer::loadedIndex(consumer::loadedObjects(), "libfcl_disk.so") < 0,
        "host before dlopen: libfcl_disk is not loaded");
    // The host's own FCL queries on real cylinders, before the plugin exists.
    const consumer::CylinderBaseline baseline = consumer::computeCylinderBaseline();
    consumer::printBindings("host before dlopen");

    void* handle = dlopen(plugin, RTLD_NOW | (global ? RTLD_GLOBAL : RTLD_LOCAL));
    if (!handle) {
      std::printf("consumer_dlopen_host: dlopen(%s, %s) failed: %s\n", plugin, mode.c_str(),
                  dlerror());
      return 3;
    }
    using RunChecks = int (*)(const char*, const consumer::CylinderBaseline*);
    using GetApi = const consumer::DiskApi* (*)();
    auto run_checks = reinterpret_cast<RunChecks>(dlsym(handle, "planner_plugin_run_checks"));
    auto get_api = reinterpret_cast<GetApi>(dlsym(handle, "planner_plugin_disk_api"));
    if (!run_checks || !get_api) {
      std::printf("consumer_dlopen_host: plugin entry points missing: %s\n", dlerror());
      return 3;
    }
    const int plugin_failures =
        run_checks(("plugin code, plugin loaded with " + mode).c_str(), &baseline);
    // Same objects, two links: only consumer_dlopen_host_exports (-rdynamic)
    // shares its float tables with the plugin.
    const bool host_float_tables_shared = std::strstr(argv[0], "_exports") != nullptr;
    const int host_failures = consumer::runAllChecks(
        "host code on plugin disks, plugin loaded with " + mode, *get_api(), baseline,
        host_float_tables_shared);
    failures += plugin_failures + host_failures;
    std::printf("consumer_dlopen_host (%s): %s (queries by plugin code: %d failure(s), by "
                "host code: %d failure(s))\n",
                mode.c_str(), failures == 0 ? "ALL CHECKS PASSED" : "FAILED", plugin_failures,
                host_failures);
    // The plugin stays loaded: its Disks' vtables live there and FCL's tables
    // point into fcl_disk.
    return failures == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::printf("consumer_dlopen_host: FAILED with exception: %s\n", e.what());
    return 2;
  }
}
