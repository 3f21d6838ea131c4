// FCL's float templates, compiled once for every user of fcl_disk: the
// geometry-level entry points fcl::distance / fcl::collide and the dispatch
// tables of both GJK solvers (declared in fcl_disk/fcl_templates.h, which
// explains why). The object-level entry points, declared there too, are the
// hook's own (src/fcl_hook.cpp, section 5). Float
// and double live in separate files so that a parallel build compiles them side
// by side: each is one of the two longest compilations in the project.
#include "fcl_disk/fcl_templates.h"

namespace fcl {

template float distance(const CollisionGeometry<float>* o1, const Transform3<float>& tf1,
                        const CollisionGeometry<float>* o2, const Transform3<float>& tf2,
                        const DistanceRequest<float>& request, DistanceResult<float>& result);

template std::size_t collide(const CollisionGeometry<float>* o1, const Transform3<float>& tf1,
                             const CollisionGeometry<float>* o2, const Transform3<float>& tf2,
                             const CollisionRequest<float>& request,
                             CollisionResult<float>& result);

FCL_DISK_FCL_TABLES(, detail::GJKSolver_libccd<float>)
FCL_DISK_FCL_TABLES(, detail::GJKSolver_indep<float>)

}  // namespace fcl
