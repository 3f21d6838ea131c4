// FCL's double dispatch tables as code compiled against FCL's headers sees them
// (libfcl.so keeps its own copies private), for both GJK solvers: declared in
// fcl_disk/fcl_templates.h, which explains why. The double entry points come
// from libfcl itself. See fcl_templates_float.cpp for why this is its own file.
#include "fcl_disk/fcl_templates.h"

namespace fcl {

FCL_DISK_FCL_TABLES(, detail::GJKSolver_libccd<double>)
FCL_DISK_FCL_TABLES(, detail::GJKSolver_indep<double>)

}  // namespace fcl
