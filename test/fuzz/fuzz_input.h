// Arbitrary fuzzer bytes -> two disks and their poses, shared by every target
// in test/fuzz/ (docs/fuzzing.md describes the modes and the byte layout).
//
// Random bytes almost never produce coplanar, coaxial, touching or nearly
// parallel disks, yet those are where the solvers branch and lose digits; so
// the first byte picks a mode, and most modes build such a configuration from
// the remaining bytes (with the true distance where the geometry gives it in
// closed form). The raw mode instead reads IEEE bit patterns straight from the
// bytes: NaN, infinities, denormals, huge values, non-orthonormal rotations.
//
// Every field has a fixed byte length whatever its value, so that
// test/fuzz/make_corpus.py can write seeds field by field, and reads past the
// end of the input yield zeros, so every input decodes.
#pragma once

#include <fcl/common/types.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <type_traits>

namespace fcl_disk_fuzz {

/// Reads the input front to back; zeros past its end.
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  std::uint8_t byte() { return position_ < size_ ? data_[position_++] : std::uint8_t(0); }

  std::uint16_t u16() {
    const std::uint16_t low = byte();
    return std::uint16_t(low | (std::uint16_t(byte()) << 8));
  }

  /// In [0, 1], from two bytes.
  double fraction() { return u16() / 65535.0; }

  /// The next sizeof(T) bytes as a T (little-endian bit pattern, any value).
  template <typename T>
  T raw() {
    std::array<std::uint8_t, sizeof(T)> bytes{};
    for (auto& b : bytes) b = byte();
    T value;
    std::memcpy(&value, bytes.data(), sizeof(T));
    return value;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t position_ = 0;
};

// ----------------------------------------------------------------------------
// The decoded input.

enum class Mode : std::uint8_t {
  generic,        ///< two independent poses (disk 2's centre relative to disk 1's).
  coplanar,       ///< same plane, centres D apart, D = |r1 + r2 + gap| (gap may be 0, tiny, negative).
  parallel,       ///< parallel planes at height h, centres D apart laterally.
  coaxial,        ///< parallel planes, disk 2's centre on disk 1's axis.
  near_parallel,  ///< disk 2 tilted by 1e-12 .. 0.1 rad from disk 1's plane.
  shared_point,   ///< the disks share a point of a rim or a face (touching or crossing).
  rim_on_face,    ///< disk 2's lowest rim point at height gap over a point of disk 1.
  centre_on_rim,  ///< disk 2's centre on disk 1's rim.
  raw,            ///< IEEE bit patterns from the bytes (see decodeRaw()).
};
constexpr int kModeCount = 9;

inline const char* modeName(Mode mode) {
  static const char* const kNames[kModeCount] = {
      "generic",      "coplanar",    "parallel",      "coaxial", "near_parallel",
      "shared_point", "rim_on_face", "centre_on_rim", "raw"};
  return kNames[static_cast<int>(mode)];
}

/// The valid range of radii and coordinates in the structured modes (radii
/// positive, coordinates signed or 0): the scales a planner meets, 18 decades.
constexpr double kMinMagnitude = 1e-9;
constexpr double kMaxMagnitude = 1e9;

template <typename S>
struct DiskPairInput {
  Mode mode{Mode::generic};
  S r1{1}, r2{1};  ///< in raw mode possibly NaN, infinite, <= 0.
  fcl::Transform3<S> X_W1{fcl::Transform3<S>::Identity()};
  fcl::Transform3<S> X_W2{fcl::Transform3<S>::Identity()};
  /// Both rotations built as rotations (quaternions, signed permutations):
  /// orthonormal to rounding. False for raw, injected or perturbed matrices.
  bool rotations_orthonormal{true};
  /// The true distance of the configuration as built in double (before the
  /// poses were rounded to S), where the mode gives it in closed form.
  std::optional<double> known_distance;

  /// The library's range (disk_pair.h): radii in [kMinDiskRadius, kMaxDiskLength],
  /// translations within kMaxDiskLength; out of range is no disk pair (NaN).
  static bool radiusValid(S r) { return fcl_disk::isValidDiskRadius(r); }
  bool radiiValid() const { return radiusValid(r1) && radiusValid(r2); }
  bool posesFinite() const { return X_W1.matrix().allFinite() && X_W2.matrix().allFinite(); }
  bool translationsInRange() const {
    const double limit = fcl_disk::kMaxDiskLength<S>;
    return X_W1.translation().template cast<double>().cwiseAbs().maxCoeff() <= limit &&
           X_W2.translation().template cast<double>().cwiseAbs().maxCoeff() <= limit;
  }
};

// ----------------------------------------------------------------------------
// Field decoders (double). Each reads a fixed number of bytes.

/// A length in [kMinMagnitude, kMaxMagnitude]; 3 bytes. Exponent byte e < 32
/// gives the exact binary fractions (e + 1) / 8 (0.125 .. 4), so that exact
/// arithmetic (coplanar sums, touching radii) happens; otherwise a mantissa in
/// [1, 2) times 2^-30 .. 2^30, clamped to the range.
inline double magnitude(ByteReader& in) {
  const int exponent_byte = in.byte();
  const double mantissa = 1.0 + in.u16() / 65536.0;
  if (exponent_byte < 32) return (exponent_byte + 1) / 8.0;
  const int exponent = -30 + (exponent_byte - 32) * 61 / 224;  // -30 .. 30
  return std::clamp(std::ldexp(mantissa, exponent), kMinMagnitude, kMaxMagnitude);
}

/// A coordinate: 0 (a quarter of the sign bytes: axis-aligned configurations),
/// else +-magnitude(); 4 bytes.
inline double coordinate(ByteReader& in) {
  const int sign_byte = in.byte();
  const double value = magnitude(in);
  if (sign_byte < 64) return 0.0;
  return (sign_byte & 1) ? -value : value;
}

inline Eigen::Vector3d point(ByteReader& in) {
  const double x = coordinate(in), y = coordinate(in), z = coordinate(in);
  return {x, y, z};
}

constexpr double kPi = 3.141592653589793;

/// An angle in [0, 2 pi]; 2 bytes.
inline double angle(ByteReader& in) { return 2 * kPi * in.fraction(); }

/// A signed length that is 0 for a quarter of the first bytes, else
/// +-10^(-16 .. 9): touching (0), rounding-level gaps, overlaps; 3 bytes.
inline double signedGap(ByteReader& in) {
  const int sign_byte = in.byte();
  const double value = std::pow(10.0, -16.0 + 25.0 * in.fraction());
  if (sign_byte < 64) return 0.0;
  return (sign_byte & 1) ? -value : value;
}

/// A tilt angle +-10^(-12 .. -1) rad (nearly parallel planes); 3 bytes.
constexpr double kMinTilt = 1e-12;
constexpr double kMaxTilt = 0.1;
inline double tilt(ByteReader& in) {
  const int sign_byte = in.byte();
  const double exponent = std::log10(kMinTilt) + (std::log10(kMaxTilt) - std::log10(kMinTilt)) * in.fraction();
  const double value = std::pow(10.0, exponent);
  return (sign_byte & 1) ? -value : value;
}

/// Quaternions shorter than this (components in [-1, 1] from 16 bits) are
/// rejected: their direction would be mostly the 2^-15 quantisation.
constexpr double kMinQuaternionNorm = 1e-2;

/// A proper rotation; 9 bytes. Kind byte % 4 == 0: one of the 24 signed
/// permutation matrices with det +1 (exact 0 / +-1 entries: axis-aligned and
/// perpendicular disks), from the next byte; otherwise a normalised quaternion
/// from four 16-bit components. nullopt for a near-zero quaternion.
inline std::optional<Eigen::Matrix3d> rotation(ByteReader& in) {
  const int kind = in.byte();
  std::array<double, 4> q{};
  std::array<std::uint16_t, 4> bits{};
  for (auto& b : bits) b = in.u16();
  if (kind % 4 == 0) {
    static const int kPermutations[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                            {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    const int index = bits[0] % 48;
    const int* permutation = kPermutations[index / 8];
    Eigen::Matrix3d R = Eigen::Matrix3d::Zero();
    for (int row = 0; row < 3; ++row) R(row, permutation[row]) = (index >> row) & 1 ? -1.0 : 1.0;
    if (R.determinant() < 0) R.col(2) *= -1.0;  // proper: exact sign flip
    return R;
  }
  for (int i = 0; i < 4; ++i) q[i] = std::int16_t(bits[i]) / 32768.0;
  Eigen::Quaterniond quaternion(q[0], q[1], q[2], q[3]);
  if (!(quaternion.norm() >= kMinQuaternionNorm)) return std::nullopt;
  quaternion.normalize();
  return quaternion.toRotationMatrix();
}

inline Eigen::Matrix3d aboutZ(double theta) {
  return Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

/// diag(1, -1, -1): turns a disk over (normal -n), exactly.
inline Eigen::Matrix3d flipped(bool flip) {
  return flip ? Eigen::Vector3d(1, -1, -1).asDiagonal().toDenseMatrix() : Eigen::Matrix3d::Identity();
}

inline fcl::Transform3<double> makePose(const Eigen::Matrix3d& R, const Eigen::Vector3d& c) {
  fcl::Transform3<double> X = fcl::Transform3<double>::Identity();
  X.linear() = R;
  X.translation() = c;
  return X;
}

// ----------------------------------------------------------------------------
// Structured modes: disk 1 anywhere (radius, rotation, centre up to 1e9 from the
// origin), disk 2 built in disk 1's frame (X_12), then X_W2 = X_W1 X_12.

/// Decodes the structured modes in double; nullopt rejects the input.
inline std::optional<DiskPairInput<double>> decodeStructured(Mode mode, ByteReader& in) {
  DiskPairInput<double> pair;
  pair.mode = mode;
  pair.r1 = magnitude(in);
  pair.r2 = magnitude(in);
  const double r1 = pair.r1, r2 = pair.r2;
  const auto R_W1 = rotation(in);
  if (!R_W1) return std::nullopt;
  pair.X_W1 = makePose(*R_W1, point(in));

  Eigen::Matrix3d R_12 = Eigen::Matrix3d::Identity();
  Eigen::Vector3d c_12 = Eigen::Vector3d::Zero();
  switch (mode) {
    case Mode::generic: {
      const auto R = rotation(in);
      if (!R) return std::nullopt;
      R_12 = *R;
      c_12 = point(in);
      break;
    }
    case Mode::coplanar:
    case Mode::parallel: {
      const double direction = angle(in);
      const double D = std::abs(r1 + r2 + signedGap(in));
      R_12 = aboutZ(angle(in)) * flipped(in.byte() & 1);
      const double height = mode == Mode::parallel ? signedGap(in) : 0.0;
      c_12 = Eigen::Vector3d(D * std::cos(direction), D * std::sin(direction), height);
      const double lateral = std::max(0.0, std::hypot(c_12.x(), c_12.y()) - r1 - r2);
      pair.known_distance = std::hypot(height, lateral);
      break;
    }
    case Mode::coaxial: {
      const double height = coordinate(in);
      R_12 = aboutZ(angle(in)) * flipped(in.byte() & 1);
      c_12 = Eigen::Vector3d(0, 0, height);
      pair.known_distance = std::abs(height);
      break;
    }
    case Mode::near_parallel: {
      const double tilt_angle = tilt(in);
      const double axis_angle = angle(in);
      const Eigen::Vector3d axis(std::cos(axis_angle), std::sin(axis_angle), 0.0);
      R_12 = Eigen::AngleAxisd(tilt_angle, axis).toRotationMatrix() * aboutZ(angle(in));
      const double direction = angle(in);
      const double D = std::abs(r1 + r2 + signedGap(in));
      c_12 = Eigen::Vector3d(D * std::cos(direction), D * std::sin(direction), signedGap(in));
      break;
    }
    case Mode::shared_point: {
      // A point of disk 1 (rim or face) is also a point of disk 2 (rim or face).
      const int kind = in.byte();
      const double rho1 = (kind & 1) ? r1 : r1 * in.fraction();
      if (kind & 1) in.fraction();  // fixed layout
      const double alpha = angle(in);
      const auto R = rotation(in);
      if (!R) return std::nullopt;
      R_12 = *R;
      const double rho2 = (kind & 2) ? r2 : r2 * in.fraction();
      if (kind & 2) in.fraction();
      const double beta = angle(in);
      const Eigen::Vector3d shared(rho1 * std::cos(alpha), rho1 * std::sin(alpha), 0.0);
      c_12 = shared - R_12 * Eigen::Vector3d(rho2 * std::cos(beta), rho2 * std::sin(beta), 0.0);
      pair.known_distance = 0.0;
      break;
    }
    case Mode::rim_on_face: {
      // Disk 2 = Rz(a) Rx(t): u = (cos a, sin a, 0), v = (-sin a cos t, cos a cos t, sin t);
      // its lowest rim point is -r2 v (t in [0, pi/2]), placed at (rho, alpha, gap).
      const int kind = in.byte();
      const double tilt_or_fraction = std::abs(tilt(in));
      const double t = (kind & 1) ? tilt_or_fraction : 0.5 * kPi * in.fraction();
      if (kind & 1) in.fraction();
      const double a = angle(in);
      const double rho = (kind & 2) ? r1 : r1 * in.fraction();
      if (kind & 2) in.fraction();
      const double alpha = angle(in);
      const double gap = signedGap(in);
      R_12 = aboutZ(a) * Eigen::AngleAxisd(t, Eigen::Vector3d::UnitX()).toRotationMatrix();
      const Eigen::Vector3d lowest(rho * std::cos(alpha), rho * std::sin(alpha), gap);
      c_12 = lowest + r2 * R_12.col(1);
      // All of disk 2 is at height >= gap and its lowest point projects into
      // disk 1, so for gap >= 0 the distance is the gap.
      if (gap >= 0) pair.known_distance = gap;
      break;
    }
    case Mode::centre_on_rim: {
      const double alpha = angle(in);
      const auto R = rotation(in);
      if (!R) return std::nullopt;
      R_12 = *R;
      c_12 = Eigen::Vector3d(r1 * std::cos(alpha), r1 * std::sin(alpha), 0.0);
      pair.known_distance = 0.0;
      break;
    }
    case Mode::raw:
      return std::nullopt;  // not a structured mode
  }
  pair.X_W2 = pair.X_W1 * makePose(R_12, c_12);
  return pair;
}

// ----------------------------------------------------------------------------
// Raw mode.

/// Values the raw mode can inject into one slot of a valid input, so that "a
/// single NaN somewhere" does not depend on the mutator finding its bit pattern.
template <typename S>
S specialValue(int index) {
  using L = std::numeric_limits<S>;
  const S values[] = {L::quiet_NaN(), L::infinity(), -L::infinity(), S(-0.0),
                      L::denorm_min(), L::max(),     L::lowest(),    L::min()};
  return values[index % 8];
}

/// Raw mode, layout: a flags byte, then the fields in order r1, r2, R_W1, R_W2,
/// c1, c2, each either raw S bit patterns (flag bits 0..5 respectively; 1, 1,
/// 9, 9, 3, 3 values of sizeof(S) bytes) or decoded as a valid field (radius:
/// magnitude(), 3 bytes; rotation: rotation(), 9 bytes; centre: point(), 12
/// bytes). Bit 6: then one slot (byte % 26 over r1, r2, R_W1, R_W2 row-major,
/// c1, c2) is replaced by specialValue(next byte). Bit 7: then a rotation
/// (next byte & 1) gets R += eps E, eps = 10^(-16 .. -2) from the next byte,
/// E's entries in [-1, 1] from 9 bytes: nearly orthonormal, around the
/// tolerance of the non-orthonormal policy.
template <typename S>
std::optional<DiskPairInput<S>> decodeRaw(ByteReader& in) {
  DiskPairInput<S> pair;
  pair.mode = Mode::raw;
  const int flags = in.byte();
  auto radius = [&](int bit) { return (flags >> bit) & 1 ? in.raw<S>() : S(magnitude(in)); };
  auto rotation_field = [&](int bit) -> std::optional<fcl::Matrix3<S>> {
    fcl::Matrix3<S> R;
    if ((flags >> bit) & 1) {
      for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) R(row, col) = in.raw<S>();
      return R;
    }
    const auto valid = rotation(in);
    if (!valid) return std::nullopt;
    return valid->template cast<S>();
  };
  auto centre_field = [&](int bit) -> fcl::Vector3<S> {
    if ((flags >> bit) & 1) {
      const S x = in.raw<S>(), y = in.raw<S>(), z = in.raw<S>();
      return {x, y, z};
    }
    return point(in).template cast<S>();
  };
  pair.r1 = radius(0);
  pair.r2 = radius(1);
  const auto R_W1 = rotation_field(2);
  const auto R_W2 = rotation_field(3);
  if (!R_W1 || !R_W2) return std::nullopt;
  pair.X_W1.linear() = *R_W1;
  pair.X_W2.linear() = *R_W2;
  pair.X_W1.translation() = centre_field(4);
  pair.X_W2.translation() = centre_field(5);
  pair.rotations_orthonormal = (flags & 0b1100) == 0;

  if (flags & 0x40) {
    const int slot = in.byte() % 26;
    const S value = specialValue<S>(in.byte());
    if (slot == 0) pair.r1 = value;
    else if (slot == 1) pair.r2 = value;
    else if (slot < 20) {
      auto& X = slot < 11 ? pair.X_W1 : pair.X_W2;
      const int entry = (slot - 2) % 9;
      X.linear()(entry / 3, entry % 3) = value;
      pair.rotations_orthonormal = false;
    } else {
      auto& X = slot < 23 ? pair.X_W1 : pair.X_W2;
      X.translation()((slot - 20) % 3) = value;
    }
  }
  if (flags & 0x80) {
    auto& X = (in.byte() & 1) ? pair.X_W2 : pair.X_W1;
    const double eps = std::pow(10.0, -16.0 + 14.0 * in.byte() / 255.0);
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 3; ++col)
        X.linear()(row, col) += S(eps * (std::int8_t(in.byte()) / 128.0));
    pair.rotations_orthonormal = false;
  }
  return pair;
}

// ----------------------------------------------------------------------------

template <typename S>
DiskPairInput<S> castTo(const DiskPairInput<double>& pair) {
  DiskPairInput<S> out;
  out.mode = pair.mode;
  out.r1 = S(pair.r1);
  out.r2 = S(pair.r2);
  out.X_W1 = pair.X_W1.template cast<S>();
  out.X_W2 = pair.X_W2.template cast<S>();
  out.rotations_orthonormal = pair.rotations_orthonormal;
  out.known_distance = pair.known_distance;
  return out;
}

/// The whole decoder: mode byte, then the mode's fields. Structured modes are
/// built in double and rounded to S (as a caller holding float poses would);
/// the raw mode reads S bit patterns. nullopt: reject the input.
template <typename S>
std::optional<DiskPairInput<S>> decodeDiskPair(ByteReader& in) {
  const Mode mode = static_cast<Mode>(in.byte() % kModeCount);
  if (mode == Mode::raw) return decodeRaw<S>(in);
  const auto pair = decodeStructured(mode, in);
  if (!pair) return std::nullopt;
  return castTo<S>(*pair);
}

/// FCL_DISK_FUZZ_PRINT=1 in the environment prints every decoded input (to
/// read a reproducer or check a seed: `FCL_DISK_FUZZ_PRINT=1 ./fuzz_x file`).
inline bool printInputs() {
  static const bool print = [] {
    const char* value = std::getenv("FCL_DISK_FUZZ_PRINT");
    return value && *value && *value != '0';
  }();
  return print;
}

}  // namespace fcl_disk_fuzz
