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
// compare commits where wall-clock medians cannot.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "disk_shape_cases.h"
#include "disk_shape_fcl.h"
#include "fcl_disk/fcl_disk.h"

namespace {
constexpr int kCases = 2000;
constexpr int kPasses = 10;
constexpr std::uint64_t kSeed = 20240601;

namespace dsc = fcl_disk_shape_cases;

/// diskShapeDistance on `shape` as its FCL class.
double distanceTo(const fcl::ShapeBase<double>& shape, const fcl::Transform3<double>& X_WD,
                  const fcl::Transform3<double>& X_WS) {
  return fcl_disk_test::oracle::withShapeClass(shape, [&](const auto& typed) {
    return fcl_disk::diskShapeDistance(dsc::kDiskRadius, X_WD, typed, X_WS).distance;
  });
}
}  // namespace

int main(int argc, char** argv) {
  const dsc::ShapeKind* kind = nullptr;
  for (const dsc::ShapeKind& k : dsc::allShapeKinds()) {
    if (argc == 2 && std::string(argv[1]) == dsc::shapeName(k)) kind = &k;
  }
  if (kind == nullptr) {
    std::fprintf(stderr, "usage: %s SHAPE\nshapes:", argv[0]);
    for (const dsc::ShapeKind k : dsc::allShapeKinds()) std::fprintf(stderr, " %s", dsc::shapeName(k));
    std::fprintf(stderr, "\n");
    return 2;
  }
  struct Query {
    std::shared_ptr<fcl::ShapeBase<double>> shape;
    fcl::Transform3<double> X_WD, X_WS;
  };
  std::vector<Query> queries;
  for (const dsc::CaseSpec& c : dsc::makeCases(*kind, kCases, kSeed)) {
    queries.push_back({dsc::makeShape<double>(c.shape), dsc::toS<double>(c.X_WD), dsc::toS<double>(c.X_WS)});
  }
  double sum = 0.0;
  for (int pass = 0; pass < kPasses; ++pass) {
    for (const Query& q : queries) sum += distanceTo(*q.shape, q.X_WD, q.X_WS);
  }
  std::printf("%d calls, sum of distances %.17g\n", kCases * kPasses, sum);
  return 0;
}
