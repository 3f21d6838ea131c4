// The tests' portable random numbers: std::mt19937_64 is specified exactly, the
// standard distributions are not, so uniform/normal draws are written out here
// and every test sees the same poses on every standard library.
#pragma once

#include <Eigen/Dense>

#include <cmath>
#include <cstdint>
#include <random>

namespace fcl_disk_test {

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}

  double uniform01() { return double(engine_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }
  double logUniform(double lo, double hi) {
    return std::exp(uniform(std::log(lo), std::log(hi)));
  }
  bool chance(double probability) { return uniform01() < probability; }
  double normal() {  // Box-Muller
    const double u1 = 1.0 - uniform01();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * uniform01());
  }
  Eigen::Vector3d unitVector() {
    for (;;) {
      const Eigen::Vector3d v(normal(), normal(), normal());
      if (v.norm() > 1e-6) return v.normalized();
    }
  }
  Eigen::Vector3d inBall(double radius) {
    return radius * std::cbrt(uniform01()) * unitVector();
  }
  /// Uniformly distributed rotation: a normalised Gaussian quaternion.
  Eigen::Matrix3d rotation() {
    Eigen::Quaterniond q(normal(), normal(), normal(), normal());
    q.normalize();
    return q.toRotationMatrix();
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace fcl_disk_test
