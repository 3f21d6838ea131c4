// Internal: candidate directions of the penetration depth shared by the shapes
// built around their z axis (capsule, cylinder): where the disk's support point
// is normal to the axis. docs/penetration_depth.md, section 7.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "../disk_shape_solver.h"
#include "../trig_roots.h"

namespace fcl_disk {
namespace internal {

/// A rim point closer than this (relative to r + |c|) to the axis has no
/// horizontal direction of its own: the candidate is normal to the axis and
/// the rim tangent instead (what the horizontal part tends to as it vanishes).
constexpr double kRimPointOnAxis = 1e-9;

/// Appends the horizontal directions w (w . z = 0) at which h_disk, restricted
/// to the circle of such directions, is stationary: the disk's support point
/// b has its horizontal part along w and normal to the rim tangent, i.e.
/// K(theta) = b_xy . b'_xy = 0 along the rim b(theta) = c + r (cos u + sin v)
/// (a trigonometric polynomial of degree 2; every root, trig_roots.h), and w =
/// b_xy / |b_xy|.
inline void addRimPointsNormalToTheAxis(const DiskInShape& disk, std::vector<Vec3>* directions) {
  using namespace trig_roots;
  static const AngleTable<kSamples> angles;
  std::array<double, kSamples> samples;
  double terms = 0.0;
  for (int j = 0; j < kSamples; ++j) {
    const Vec3 b = disk.c + disk.r * (angles.cos[j] * disk.u + angles.sin[j] * disk.v);
    const Vec3 db = disk.r * (angles.cos[j] * disk.v - angles.sin[j] * disk.u);
    samples[j] = b.x() * db.x() + b.y() * db.y();
    terms = std::max(terms, std::hypot(b.x(), b.y()) * std::hypot(db.x(), db.y()));
  }
  forEachRootAngle(TrigPolynomial::fromSamples(samples), kBernsteinNoise * terms,
                   [&](double cos_theta, double sin_theta) {
                     const Vec3 b = disk.c + disk.r * (cos_theta * disk.u + sin_theta * disk.v);
                     const double rho = std::hypot(b.x(), b.y());
                     if (rho > kRimPointOnAxis * (disk.r + disk.c.norm())) {
                       directions->emplace_back(b.x(), b.y(), 0.0);
                     } else {
                       const Vec3 tangent = cos_theta * disk.v - sin_theta * disk.u;
                       directions->push_back(Vec3::UnitZ().cross(tangent));
                     }
                   });
}

}  // namespace internal
}  // namespace fcl_disk
