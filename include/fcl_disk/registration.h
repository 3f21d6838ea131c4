// Selecting fcl_disk's disk-disk method and installing it into FCL's dispatch.
#pragma once

namespace fcl_disk {

/// The solver behind fcl::distance for disk-disk pairs.
enum class DiskDistanceMethod {
  exact,            ///< exactDiskDistance(): certified, the default.
  almohamad_selim,  ///< almohamadSelimDiskDistance(): the 1994 report, an upper bound.
};

/// Installs fcl_disk's disk-disk distance and collision functions into FCL's
/// dispatch and selects `method` for fcl::distance on disk pairs.
///
/// Covers every way FCL dispatches a query: the tables that code compiled
/// against FCL's headers uses (float, double; libccd and indep solvers) and the
/// private copies inside Debian's libfcl.so that plain fcl::distance<double> /
/// fcl::collide<double> and the broadphase default callbacks use (see
/// docs/fcl_hook.md). Every other pair, real fcl::Cylinder pairs included, keeps
/// FCL's own function.
///
/// Installation happens once, when libfcl_disk is loaded (before main(), or
/// inside dlopen() for a plugin), so it never overlaps a query: FCL reads its
/// tables without synchronisation. This function (and a Disk's constructor)
/// only makes sure it happened and, here, stores the method: an atomic store,
/// safe while other threads query, seen by queries that start afterwards.
/// The one unsynchronised window left: dlopen()ing a plugin that links
/// fcl_disk while other threads are inside FCL queries (docs/robustness.md).
/// @throws std::runtime_error if the hook could not take effect in this process
///         (e.g. an FCL build whose private tables cannot be found); the message
///         says how to fix it. Queries never silently fall back to GJK.
void registerDiskFunctions(DiskDistanceMethod method = DiskDistanceMethod::exact);

/// The method fcl::distance currently uses for disk pairs.
DiskDistanceMethod registeredDiskDistanceMethod();

}  // namespace fcl_disk
