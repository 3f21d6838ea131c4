// Internal: the lower bounds of a hierarchy node's two children at once, one
// child per lane of a 2-wide double vector (SSE2, every x86-64), for the mesh
// distance traversal (src/mesh_distance.h). The arithmetic is volumeBound's
// for an OBB, an RSS and an AABB, operation for operation, so each lane's bound is the
// same bound (rounded alike up to the order of a sum, well inside the
// traversal's rounding pad); NaN in a volume gives a NaN or zero bound, which
// the traversal searches. docs/meshes_and_octrees.md, "Distance traversal".
//
// Why: a node's children are always bounded together, and with 3-vectors GCC
// keeps each bound half scalar and spends many of its ~200 instructions moving
// lanes; two volumes in the two lanes share every instruction.
#pragma once

#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/bv/kIOS.h>

#include <array>
#include <type_traits>

#include "disk_shape_solver.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#define FCL_DISK_PAIRED_VOLUME_BOUNDS 1
#else
#define FCL_DISK_PAIRED_VOLUME_BOUNDS 0
#endif

namespace fcl_disk {
namespace internal {

/// A lower bound on the distance from the disk to a volume, unpadded, and the
/// magnitude its rounding pad scales with (but for the disk's share).
struct VolumeBound {
  double bound;
  double magnitude;
};

#if FCL_DISK_PAIRED_VOLUME_BOUNDS

namespace lanes {
using V = __m128d;
/// (first, second): lane 0 holds the first child's value.
template <typename A, typename B>
inline V of(A first, B second) { return _mm_set_pd(double(second), double(first)); }
inline V all(double x) { return _mm_set1_pd(x); }
// + - * / are GCC's and Clang's vector arithmetic, lane by lane.
inline V abs(V a) { return _mm_andnot_pd(_mm_set1_pd(-0.0), a); }
inline V sqrt(V a) { return _mm_sqrt_pd(a); }
/// std::max(a, b) lane by lane: b if a < b, else a (a NaN a stays).
inline V max(V a, V b) {
  const V b_larger = _mm_cmplt_pd(a, b);
  return _mm_or_pd(_mm_and_pd(b_larger, b), _mm_andnot_pd(b_larger, a));
}
/// x where `mask` holds, else +0.
inline V where(V mask, V x) { return _mm_and_pd(mask, x); }
inline V greaterThanZero(V a) { return _mm_cmpgt_pd(a, _mm_setzero_pd()); }
inline std::array<double, 2> split(V a) {
  std::array<double, 2> out;
  _mm_storeu_pd(out.data(), a);
  return out;
}
}  // namespace lanes

/// diskBoxLowerBound (src/environment_bounds.h) for two boxes, lane by lane:
/// centres o, axes A (A[i][k]: component i of axis k), half-extents e.
/// Returns max(ball, along); `d_box` the centres' offsets in box coordinates.
inline lanes::V diskBoxLowerBoundLanes(const DiskInShape& disk, const lanes::V (&o)[3],
                                       const lanes::V (&A)[3][3], const lanes::V (&e)[3],
                                       lanes::V (&d_box)[3]) {
  using namespace lanes;
  const V d[3] = {o[0] - all(disk.c.x()), o[1] - all(disk.c.y()), o[2] - all(disk.c.z())};
  const auto along_frame = [&](const Vec3& w) {  // w.d for a frame vector w
    return all(w.x()) * d[0] + all(w.y()) * d[1] + all(w.z()) * d[2];
  };
  V n_box[3];
  for (int k = 0; k < 3; ++k) {
    d_box[k] = A[0][k] * d[0] + A[1][k] * d[1] + A[2][k] * d[2];
    n_box[k] = A[0][k] * all(disk.n.x()) + A[1][k] * all(disk.n.y()) + A[2][k] * all(disk.n.z());
  }
  const V a_o = along_frame(disk.n), x = along_frame(disk.u), y = along_frame(disk.v);
  const V rho = lanes::sqrt(x * x + y * y);
  const V rim_gap = lanes::max(rho - all(disk.r), _mm_setzero_pd());
  // From o's nearest disk point to o, in box coordinates (see diskBoxLowerBound).
  const V beyond_rim = greaterThanZero(rim_gap);
  const V to_rim = where(beyond_rim, rim_gap / rho);
  V extent = _mm_setzero_pd();
  for (int k = 0; k < 3; ++k) {
    const V from_disk = a_o * n_box[k] + where(beyond_rim, to_rim * (d_box[k] - a_o * n_box[k]));
    extent = extent + e[k] * lanes::abs(from_disk);
  }
  const V centre_distance = lanes::sqrt(a_o * a_o + rim_gap * rim_gap);
  const V along = where(greaterThanZero(centre_distance),
                        centre_distance - extent / centre_distance);
  V outside_squared = _mm_setzero_pd();
  for (int k = 0; k < 3; ++k) {
    const V outside = lanes::max(lanes::abs(d_box[k]) - e[k], _mm_setzero_pd());
    outside_squared = outside_squared + outside * outside;
  }
  const V ball = lanes::sqrt(outside_squared) - all(disk.r);
  return lanes::max(ball, along);
}

/// boxBoundMagnitude for two boxes: max |o_i| + max e_k.
inline lanes::V boxBoundMagnitudeLanes(const lanes::V (&o)[3], const lanes::V (&e)[3]) {
  using namespace lanes;
  return lanes::max(lanes::max(lanes::abs(o[0]), lanes::abs(o[1])), lanes::abs(o[2])) +
         lanes::max(lanes::max(e[0], e[1]), e[2]);
}

inline std::array<VolumeBound, 2> splitBounds(lanes::V bound, lanes::V magnitude) {
  const auto b = lanes::split(bound), m = lanes::split(magnitude);
  return {VolumeBound{b[0], m[0]}, VolumeBound{b[1], m[1]}};
}

/// The bounds of two boxes whose axes, centres and half-extents `fill(i, A_i,
/// o_i, e_i)` sets coordinate by coordinate (A_i[k]: component i of axis k).
template <typename Fill>
[[gnu::always_inline]] inline std::array<VolumeBound, 2> boxBounds(const DiskInShape& disk,
                                                                   Fill&& fill) {
  lanes::V A[3][3], o[3], e[3], d_box[3];
  for (int i = 0; i < 3; ++i) fill(i, A[i], o[i], e[i]);
  return splitBounds(diskBoxLowerBoundLanes(disk, o, A, e, d_box), boxBoundMagnitudeLanes(o, e));
}

/// volumeBound for two OBBs.
template <typename S>
std::array<VolumeBound, 2> volumeBounds(const DiskInShape& disk, const fcl::OBB<S>& first,
                                        const fcl::OBB<S>& second) {
  return boxBounds(disk, [&](int i, lanes::V(&axes_i)[3], lanes::V& o_i, lanes::V& e_i) {
    for (int k = 0; k < 3; ++k) axes_i[k] = lanes::of(first.axis(i, k), second.axis(i, k));
    o_i = lanes::of(first.To[i], second.To[i]);
    e_i = lanes::of(first.extent[i], second.extent[i]);
  });
}
template <typename S>
std::array<VolumeBound, 2> volumeBounds(const DiskInShape& disk, const fcl::OBBRSS<S>& first,
                                        const fcl::OBBRSS<S>& second) {
  return volumeBounds(disk, first.obb, second.obb);
}
template <typename S>
std::array<VolumeBound, 2> volumeBounds(const DiskInShape& disk, const fcl::kIOS<S>& first,
                                        const fcl::kIOS<S>& second) {
  return volumeBounds(disk, first.obb, second.obb);
}

/// volumeBound for two RSSs: the rectangle's box bound raised to the gap along
/// its normal axis_2 (d_box[2], the centre's offset along it), less r.
template <typename S>
std::array<VolumeBound, 2> volumeBounds(const DiskInShape& disk, const fcl::RSS<S>& first,
                                        const fcl::RSS<S>& second) {
  using namespace lanes;
  V A[3][3], o[3], d_box[3];
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) A[i][k] = of(first.axis(i, k), second.axis(i, k));
  }
  const V half0 = all(0.5) * of(first.l[0], second.l[0]);
  const V half1 = all(0.5) * of(first.l[1], second.l[1]);
  for (int i = 0; i < 3; ++i) {
    o[i] = of(first.To[i], second.To[i]) + half0 * A[i][0] + half1 * A[i][1];
  }
  const V e[3] = {half0, half1, _mm_setzero_pd()};
  const V box = diskBoxLowerBoundLanes(disk, o, A, e, d_box);
  const V u_n = all(disk.u.x()) * A[0][2] + all(disk.u.y()) * A[1][2] + all(disk.u.z()) * A[2][2];
  const V v_n = all(disk.v.x()) * A[0][2] + all(disk.v.y()) * A[1][2] + all(disk.v.z()) * A[2][2];
  const V normal_gap = lanes::abs(d_box[2]) - all(disk.r) * lanes::sqrt(u_n * u_n + v_n * v_n);
  const V radius = of(first.r, second.r);
  return splitBounds(lanes::max(box, normal_gap) - radius,
                     boxBoundMagnitudeLanes(o, e) + radius);
}

/// volumeBound for two AABBs: centres and half-extents formed in S as
/// alignedBoxOf forms them, the frame's axes as the boxes'.
template <typename S>
std::array<VolumeBound, 2> volumeBounds(const DiskInShape& disk, const fcl::AABB<S>& first,
                                        const fcl::AABB<S>& second) {
  return boxBounds(disk, [&](int i, lanes::V(&axes_i)[3], lanes::V& o_i, lanes::V& e_i) {
    for (int k = 0; k < 3; ++k) axes_i[k] = lanes::all(i == k ? 1.0 : 0.0);
    o_i = lanes::of(S((first.min_[i] + first.max_[i]) / 2),
                    S((second.min_[i] + second.max_[i]) / 2));
    e_i = lanes::of(S((first.max_[i] - first.min_[i]) / 2),
                    S((second.max_[i] - second.min_[i]) / 2));
  });
}

/// Whether volumeBounds pairs BV's volumes.
template <typename BV>
constexpr bool kPairedVolumeBounds = std::is_same_v<BV, fcl::OBB<typename BV::S>> ||
                                     std::is_same_v<BV, fcl::RSS<typename BV::S>> ||
                                     std::is_same_v<BV, fcl::OBBRSS<typename BV::S>> ||
                                     std::is_same_v<BV, fcl::kIOS<typename BV::S>> ||
                                     std::is_same_v<BV, fcl::AABB<typename BV::S>>;

#else

template <typename BV>
constexpr bool kPairedVolumeBounds = false;

#endif

}  // namespace internal
}  // namespace fcl_disk
