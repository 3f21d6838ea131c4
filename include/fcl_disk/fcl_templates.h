// FCL templates that libfcl_disk compiles once, so that files using disks need not.
//
// Debian's libfcl instantiates fcl::distance and fcl::collide for double only
// (its headers declare them `extern template`). Every translation unit that
// calls them in float therefore instantiates FCL's whole float dispatch (every
// shape pair and BVH traversal, for both GJK solvers): about 50 s of GCC -O2
// per entry point (docs/fcl_hook.md, "Build time"). The same holds, in float
// and double, for the lookup tables behind the overloads that take a solver.
// libfcl_disk compiles all of these anyway (its hook patches those tables), so
// it provides explicit instantiations (src/fcl_templates_float.cpp,
// src/fcl_templates_double.cpp) and this header declares them, as FCL does for
// its double entry points; fcl_disk/disk.h includes it.
//
// Include it before a translation unit's first use of these templates (C++
// requires the declaration to precede the implicit instantiation); including
// fcl_disk's headers first does that. Behaviour is unchanged: the same code,
// compiled once; the object-level fcl::distance / fcl::collide are the hook's
// own, FCL's entry with a shortcut for pairs of Disks that gives the same
// answers (docs/fcl_hook.md, "The object-level entry points").
#pragma once

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <cstddef>

namespace fcl {

extern template float distance(const CollisionObject<float>* o1,
                               const CollisionObject<float>* o2,
                               const DistanceRequest<float>& request,
                               DistanceResult<float>& result);

extern template float distance(const CollisionGeometry<float>* o1, const Transform3<float>& tf1,
                               const CollisionGeometry<float>* o2, const Transform3<float>& tf2,
                               const DistanceRequest<float>& request,
                               DistanceResult<float>& result);

extern template std::size_t collide(const CollisionObject<float>* o1,
                                    const CollisionObject<float>* o2,
                                    const CollisionRequest<float>& request,
                                    CollisionResult<float>& result);

extern template std::size_t collide(const CollisionGeometry<float>* o1,
                                    const Transform3<float>& tf1,
                                    const CollisionGeometry<float>* o2,
                                    const Transform3<float>& tf2,
                                    const CollisionRequest<float>& request,
                                    CollisionResult<float>& result);

// The lookup tables (FCL's dispatch matrices) and their accessors, per solver.
// One macro for the declarations here and the definitions in src/ (`storage`
// is `extern` here and empty there), so the two lists cannot drift apart.
#define FCL_DISK_FCL_TABLES(storage, Solver)                                       \
  storage template struct detail::DistanceFunctionMatrix<Solver>;                  \
  storage template struct detail::CollisionFunctionMatrix<Solver>;                 \
  storage template detail::DistanceFunctionMatrix<Solver>&                         \
  getDistanceFunctionLookTable<Solver>();                                          \
  storage template detail::CollisionFunctionMatrix<Solver>&                        \
  getCollisionFunctionLookTable<Solver>();

FCL_DISK_FCL_TABLES(extern, detail::GJKSolver_libccd<float>)
FCL_DISK_FCL_TABLES(extern, detail::GJKSolver_indep<float>)
FCL_DISK_FCL_TABLES(extern, detail::GJKSolver_libccd<double>)
FCL_DISK_FCL_TABLES(extern, detail::GJKSolver_indep<double>)

}  // namespace fcl
