// A fixed disk-shape workload for instruction counts (docs/performance.md,
// "Instructions"): fcl_disk::diskShapeDistance on the first 2000 cases of one
// shape of bench/disk_shape_cases.h (the report's cases, seed 20240601), ten
// passes, nothing else timed or printed but the sum of the distances. Run it
// under callgrind and divide the entry's inclusive count by 20000:
//
//   valgrind --tool=callgrind --callgrind-out-file=cg.out ./build/bench/disk_shape_calls box
//   callgrind_annotate --inclusive=yes cg.out | grep -m1 'diskShapeDistance<double, fcl::Box'
//
// Instruction counts are not moved by the load of a shared machine, so they
// compare commits where wall-clock medians cannot. `float` runs the same cases
// on Disk<float> (shapes and poses rounded to float), and a pass count makes
// the queries outweigh the set-up, for timing whole processes side by side
// (the convex shapes repeat each case PASSES times before the next, as the
// report times them: a hull's planes are computed on its first query on a
// thread and kept for the next ones, which a planner querying one hull pays):
//
//   B="env LD_LIBRARY_PATH=OTHER ./build/bench/disk_shape_calls box float 2000"
//   farm-bench -n 10 --vs "$B" -- ./build/bench/disk_shape_calls box float 2000
//
// `hullN [PASSES]` (hull100, hull1000, ...) runs the 2000 poses against one
// Convex of N random points on a sphere instead, in double: the scaling of the
// Convex pair with the hull's size.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "disk_shape_cases.h"
#include "disk_shape_fcl.h"
#include "fcl_disk/fcl_disk.h"

namespace {
constexpr int kCases = 2000;
constexpr int kDefaultPasses = 10;
constexpr std::uint64_t kSeed = 20240601;

namespace dsc = fcl_disk_shape_cases;

/// diskShapeDistance on `shape` as its FCL class.
template <typename S>
double distanceTo(const fcl::ShapeBase<S>& shape, const fcl::Transform3<S>& X_WD,
                  const fcl::Transform3<S>& X_WS) {
  return fcl_disk_test::oracle::withShapeClass(shape, [&](const auto& typed) {
    return double(fcl_disk::diskShapeDistance(S(dsc::kDiskRadius), X_WD, typed, X_WS).distance);
  });
}

/// The sum of the distances of `passes` passes over the cases, in S.
template <typename S>
double sumOfDistances(const dsc::ShapeKind& kind, int passes) {
  struct Query {
    std::shared_ptr<fcl::ShapeBase<S>> shape;
    fcl::Transform3<S> X_WD, X_WS;
  };
  std::vector<Query> queries;
  for (const dsc::CaseSpec& c : dsc::makeCases(kind, kCases, kSeed)) {
    queries.push_back({dsc::makeShape<S>(c.shape), dsc::toS<S>(c.X_WD), dsc::toS<S>(c.X_WS)});
  }
  double sum = 0.0;
  const auto start = std::chrono::steady_clock::now();
  if (kind == dsc::ShapeKind::convex8 || kind == dsc::ShapeKind::convex40) {
    std::vector<double> per_case;  // ns a call, each case's passes timed together
    for (const Query& q : queries) {
      const auto case_start = std::chrono::steady_clock::now();
      for (int pass = 0; pass < passes; ++pass) sum += distanceTo<S>(*q.shape, q.X_WD, q.X_WS);
      const std::chrono::duration<double, std::nano> spent =
          std::chrono::steady_clock::now() - case_start;
      per_case.push_back(spent.count() / passes);
    }
    std::nth_element(per_case.begin(), per_case.begin() + per_case.size() / 2, per_case.end());
    std::printf("%.1f ns a call (median over the cases)\n", per_case[per_case.size() / 2]);
  } else {
    for (int pass = 0; pass < passes; ++pass) {
      for (const Query& q : queries) sum += distanceTo<S>(*q.shape, q.X_WD, q.X_WS);
    }
  }
  const std::chrono::duration<double, std::nano> elapsed = std::chrono::steady_clock::now() - start;
  std::printf("%.1f ns a call (mean, wall clock)\n", elapsed.count() / (double(queries.size()) * passes));
  return sum;
}
/// `hullN`: the sum of the distances of `passes` passes over kCases random
/// disk poses against one Convex of N random points on the sphere of radius
/// 0.45 (bench/disk_shape_cases.h's hull) at random poses: the same hull
/// queried again and again, as a planner does; its geometry is built on the
/// first query.
double sumOfHullDistances(int vertex_count, int passes) {
  fcl_disk_test::Random random(kSeed + std::uint64_t(vertex_count));
  const auto hull = dsc::makeShape<double>(dsc::detail::sphereHull(vertex_count, random));
  std::vector<std::pair<fcl::Transform3<double>, fcl::Transform3<double>>> poses;
  for (int k = 0; k < kCases; ++k) {
    const fcl::Transform3<double> X_WD = dsc::detail::randomPose(random);
    poses.emplace_back(X_WD, dsc::detail::randomPose(random));
  }
  double sum = 0.0;
  const auto start = std::chrono::steady_clock::now();
  for (int pass = 0; pass < passes; ++pass) {
    for (const auto& [X_WD, X_WS] : poses) sum += distanceTo<double>(*hull, X_WD, X_WS);
  }
  const std::chrono::duration<double, std::nano> elapsed = std::chrono::steady_clock::now() - start;
  std::printf("%.1f ns a call (mean, wall clock)\n", elapsed.count() / (double(kCases) * passes));
  return sum;
}
}  // namespace

int main(int argc, char** argv) {
  const int hull_size = argc >= 2 && std::string(argv[1]).rfind("hull", 0) == 0
                            ? std::atoi(argv[1] + 4) : 0;
  if (hull_size >= 4) {
    const int passes = argc >= 3 ? std::atoi(argv[2]) : kDefaultPasses;
    if (passes < 1) return 2;
    std::printf("%d calls, sum of distances %.17g\n", kCases * passes,
                sumOfHullDistances(hull_size, passes));
    return 0;
  }
  const dsc::ShapeKind* kind = nullptr;
  for (const dsc::ShapeKind& k : dsc::allShapeKinds()) {
    if (argc >= 2 && std::string(argv[1]) == dsc::shapeName(k)) kind = &k;
  }
  const bool in_float = argc >= 3 && std::string(argv[2]) == "float";
  const int passes = argc >= 4 ? std::atoi(argv[3]) : kDefaultPasses;
  if (kind == nullptr || argc > 4 || (argc >= 3 && !in_float && std::string(argv[2]) != "double") ||
      passes < 1) {
    std::fprintf(stderr, "usage: %s SHAPE [double|float [PASSES]] | hullN [PASSES]\nshapes:", argv[0]);
    for (const dsc::ShapeKind k : dsc::allShapeKinds()) std::fprintf(stderr, " %s", dsc::shapeName(k));
    std::fprintf(stderr, "\n");
    return 2;
  }
  const double sum = in_float ? sumOfDistances<float>(*kind, passes)
                              : sumOfDistances<double>(*kind, passes);
  std::printf("%d calls, sum of distances %.17g\n", kCases * passes, sum);
  return 0;
}
