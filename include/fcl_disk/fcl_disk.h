// fcl_disk: zero-thickness disks for FCL 0.7. Include this one header.
#pragma once

#include <fcl_disk/almohamad_selim.h>
#include <fcl_disk/disk.h>
#include <fcl_disk/disk_aabb.h>
#include <fcl_disk/disk_bv.h>
#include <fcl_disk/disk_intersection.h>
#include <fcl_disk/disk_pair.h>
#include <fcl_disk/disk_penetration.h>
#include <fcl_disk/disk_shape_distance.h>
#include <fcl_disk/exact_distance.h>
#include <fcl_disk/fcl_templates.h>
#include <fcl_disk/registration.h>

/// @namespace fcl_disk
/// Zero-thickness circular disks for FCL 0.7: the shape (Disk), the disk-disk and
/// disk-shape solvers (exactDiskDistance(), diskShapeDistance(), ...) and the hook
/// that answers fcl::distance and fcl::collide with them (registerDiskFunctions()).
