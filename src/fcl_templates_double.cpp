// FCL's double dispatch tables as code compiled against FCL's headers sees them
// (libfcl.so keeps its own copies private), for both GJK solvers: declared in
// fcl_disk/fcl_templates.h, which explains why. The double entry points come
// from libfcl itself. See fcl_templates_float.cpp for why this is its own file.
#include "fcl_disk/fcl_templates.h"

namespace fcl {

template struct detail::DistanceFunctionMatrix<detail::GJKSolver_libccd<double>>;
template struct detail::CollisionFunctionMatrix<detail::GJKSolver_libccd<double>>;
template detail::DistanceFunctionMatrix<detail::GJKSolver_libccd<double>>&
getDistanceFunctionLookTable<detail::GJKSolver_libccd<double>>();
template detail::CollisionFunctionMatrix<detail::GJKSolver_libccd<double>>&
getCollisionFunctionLookTable<detail::GJKSolver_libccd<double>>();

template struct detail::DistanceFunctionMatrix<detail::GJKSolver_indep<double>>;
template struct detail::CollisionFunctionMatrix<detail::GJKSolver_indep<double>>;
template detail::DistanceFunctionMatrix<detail::GJKSolver_indep<double>>&
getDistanceFunctionLookTable<detail::GJKSolver_indep<double>>();
template detail::CollisionFunctionMatrix<detail::GJKSolver_indep<double>>&
getCollisionFunctionLookTable<detail::GJKSolver_indep<double>>();

}  // namespace fcl
