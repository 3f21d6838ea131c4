// Tight bounding volumes of a Disk for fcl::computeBV, the function FCL's mesh and
// octree traversals call on the shape of a shape-mesh or shape-octree pair.
//
// FCL's defaults for a Cylinder(r, 0) fit its bound vertices (a hexagonal prism
// around the circle) or use the rotated axis-aligned extents |R| (r, r, 0), so
// they stick out of the disk by up to 15 % of r; traversals then open nodes a
// tighter volume would prune. Here, for a disk of radius r, centre c, in-plane
// axes u, v (the first two columns of its rotation) and normal n:
//   AABB      the smallest box: half-extent r sqrt(u_i^2 + v_i^2) along axis i
//             (diskWorldAABB, disk_aabb.h);
//   OBB       the flat square c + [-r, r] u + [-r, r] v (extent (r, r, 0));
//   RSS       the same square as a rectangle swept by a sphere of radius 0;
//   OBBRSS    both;
//   kIOS      the ball of radius r about c, intersected with the flat square:
//             every point of it within r of c in the disk's plane, so exact
//             in the plane, and flat;
//   KDOP<N>   the smallest k-DOP: along each of FCL's N/2 directions d, the
//             disk's support c.d -+ r |(u.d, v.d)|.
// Each contains the disk, padded outward by kDiskBvPadUlps relative (the
// rounding of the products above), so rounding never leaves a disk point
// outside, and thickened by kDiskBvTouchingPad of r + |c| on every side: the
// solvers count pairs closer than 1e-13 of their scene as touching
// (disk_shape_distance.h), and a volume test that rounding puts a hair apart
// must not prune such a pair before the leaf says it touches. Frame: the `tf`
// passed to computeBV (the world, or the mesh's or octree's frame).
#pragma once

#include <fcl/geometry/shape/utility.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/bv/kDOP.h>
#include <fcl/math/bv/kIOS.h>
#include <fcl_disk/disk_aabb.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace fcl_disk {

template <typename S>
class Disk;

// Defined in disk_aabb.h (which includes this header through disk.h).
template <typename S>
fcl::AABB<S> diskWorldAABB(S radius, const fcl::Transform3<S>& X_WD);

/// Relative outward padding of the extents below, in ulps: each extent is a
/// product and a square root of a few rounded terms (4 roundings), as
/// kDiskAabbExtentPadUlps.
inline constexpr int kDiskBvPadUlps = 4;

/// Thickening of every bounding volume, relative to r + |c| (c the centre in
/// the frame of the volume): ten times the solvers' touching tolerance (1e-13
/// of the scene), which the scene's size r + |c| bounds for a disk against a
/// piece near it in that frame.
inline constexpr double kDiskBvTouchingPad = 1e-12;

namespace detail {

template <typename S>
constexpr S diskBvPad() {
  return 1 + kDiskBvPadUlps * std::numeric_limits<S>::epsilon();
}

/// The thickening kDiskBvTouchingPad (r + |c|), at least the rounding of S.
template <typename S>
S diskBvThickness(S radius, const fcl::Transform3<S>& tf) {
  return std::max(S(kDiskBvTouchingPad), 4 * std::numeric_limits<S>::epsilon()) *
         (radius + tf.translation().norm());
}

/// The flat square c + [-r, r] u + [-r, r] v as an OBB.
template <typename S>
fcl::OBB<S> diskSquareObb(S radius, const fcl::Transform3<S>& tf) {
  fcl::OBB<S> obb;
  obb.axis = tf.linear();
  obb.To = tf.translation();
  const S thickness = diskBvThickness(radius, tf);
  const S half = diskBvPad<S>() * radius + thickness;
  obb.extent << half, half, thickness;
  return obb;
}

/// The same square as an RSS with radius 0 (FCL's RSS keeps its rectangle's
/// minimum corner in To).
template <typename S>
fcl::RSS<S> diskSquareRss(S radius, const fcl::Transform3<S>& tf) {
  fcl::RSS<S> rss;
  rss.axis = tf.linear();
  rss.l[0] = rss.l[1] = 2 * diskBvPad<S>() * radius;
  rss.r = diskBvThickness(radius, tf);
  rss.setToFromCenter(tf.translation());
  return rss;
}

}  // namespace detail
}  // namespace fcl_disk

namespace fcl {
namespace detail {

template <typename S>
struct ComputeBVImpl<S, AABB<S>, fcl_disk::Disk<S>> {
  static void run(const fcl_disk::Disk<S>& disk, const Transform3<S>& tf, AABB<S>& bv) {
    bv = fcl_disk::diskWorldAABB(disk.radius, tf);
    const S thickness = fcl_disk::detail::diskBvThickness(disk.radius, tf);
    bv.min_ -= Vector3<S>::Constant(thickness);
    bv.max_ += Vector3<S>::Constant(thickness);
  }
};

template <typename S>
struct ComputeBVImpl<S, OBB<S>, fcl_disk::Disk<S>> {
  static void run(const fcl_disk::Disk<S>& disk, const Transform3<S>& tf, OBB<S>& bv) {
    bv = fcl_disk::detail::diskSquareObb(disk.radius, tf);
  }
};

template <typename S>
struct ComputeBVImpl<S, RSS<S>, fcl_disk::Disk<S>> {
  static void run(const fcl_disk::Disk<S>& disk, const Transform3<S>& tf, RSS<S>& bv) {
    bv = fcl_disk::detail::diskSquareRss(disk.radius, tf);
  }
};

template <typename S>
struct ComputeBVImpl<S, OBBRSS<S>, fcl_disk::Disk<S>> {
  static void run(const fcl_disk::Disk<S>& disk, const Transform3<S>& tf, OBBRSS<S>& bv) {
    bv.obb = fcl_disk::detail::diskSquareObb(disk.radius, tf);
    bv.rss = fcl_disk::detail::diskSquareRss(disk.radius, tf);
  }
};

template <typename S>
struct ComputeBVImpl<S, kIOS<S>, fcl_disk::Disk<S>> {
  static void run(const fcl_disk::Disk<S>& disk, const Transform3<S>& tf, kIOS<S>& bv) {
    bv.num_spheres = 1;
    bv.spheres[0].o = tf.translation();
    bv.spheres[0].r = fcl_disk::detail::diskBvPad<S>() * disk.radius +
                      fcl_disk::detail::diskBvThickness(disk.radius, tf);
    bv.obb = fcl_disk::detail::diskSquareObb(disk.radius, tf);
  }
};

template <typename S, std::size_t N>
struct ComputeBVImpl<S, KDOP<S, N>, fcl_disk::Disk<S>> {
  static void run(const fcl_disk::Disk<S>& disk, const Transform3<S>& tf, KDOP<S, N>& bv) {
    // FCL's k-DOP directions d_k, read off the k-DOPs of the unit vectors
    // (KDOP(v).dist(k) = d_k . v).
    const KDOP<S, N> along_x(Vector3<S>::UnitX()), along_y(Vector3<S>::UnitY()),
        along_z(Vector3<S>::UnitZ());
    const Vector3<S> u = tf.linear().col(0), v = tf.linear().col(1);
    const Vector3<S>& c = tf.translation();
    constexpr S kInfinity = std::numeric_limits<S>::infinity();
    const S thickness = fcl_disk::detail::diskBvThickness(disk.radius, tf);
    for (std::size_t k = 0; k < N / 2; ++k) {
      const Vector3<S> d(along_x.dist(k), along_y.dist(k), along_z.dist(k));
      const S centre = c.dot(d);
      const S extent = fcl_disk::detail::diskBvPad<S>() * disk.radius * std::hypot(u.dot(d), v.dot(d)) +
                       thickness * d.norm();
      bv.dist(k) = std::nextafter(centre - extent, -kInfinity);
      bv.dist(k + N / 2) = std::nextafter(centre + extent, kInfinity);
    }
  }
};

}  // namespace detail
}  // namespace fcl
