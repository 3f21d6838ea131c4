// Internal: the certified disk-triangle and disk-box solvers as the mesh and
// octree traversals call them, on a disk already posed in the leaf's frame (a
// DiskInShape, double): the same solver runs as diskShapeDistance /
// diskShapeIntersect with fcl::TriangleP and fcl::Box, without re-validating
// the poses or changing frames per leaf. The disk's axes must be orthonormal
// to double rounding (orthonormalDiskInShape), as the closed forms need. Defined
// in src/pairs/disk_triangle.cpp and src/pairs/disk_box.cpp.
#pragma once

#include "disk_shape_solver.h"

namespace fcl_disk {
namespace internal {

/// The triangle a, b, c (the disk's frame): the generic solver's solution (the
/// caller has tried triangleToDisk), a NaN distance for vertices outside
/// fcl_disk's length range.
DiskShapeSolution solveDiskTriangle(const DiskInShape& disk, const Vec3& a, const Vec3& b,
                                    const Vec3& c);
/// Whether the disk meets the triangle; if so, `contact` (when given) in that frame.
/// For a mesh's leaf, whose volume met the disk's: without diskShapeIntersect's
/// early exit (apartTowardsCentre), which seldom proves such pairs apart.
bool intersectDiskTriangle(const DiskInShape& disk, const Vec3& a, const Vec3& b, const Vec3& c,
                           FrameContact* contact);

/// The box centred at the frame's origin, axis-aligned, half-extents `half`
/// (solveDiskBox: the generic solver's solution; the caller has tried
/// alignedBoxToDisk).
DiskShapeSolution solveDiskBox(const DiskInShape& disk, const Vec3& half);
/// Whether the disk meets that box (an octree's occupied cell, whose bounds met
/// the disk's: without the early exit, as intersectDiskTriangle).
bool intersectDiskBox(const DiskInShape& disk, const Vec3& half, FrameContact* contact);

/// The capsule of radius `radius` about the segment {(0, 0, z) : |z| <=
/// half_length}: the generic solver's solution (the cylinder's side wall,
/// src/pairs/disk_cylinder.cpp).
DiskShapeSolution solveDiskCapsule(const DiskInShape& disk, double radius, double half_length);

}  // namespace internal
}  // namespace fcl_disk
