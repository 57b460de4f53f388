// The one compilation of linalg.hpp's helpers for the kernels' matrix types (declared extern
// there): Eigen's eigensolver, the one-sided Jacobi SVD and the bounded-size products, which every
// estimator's file would otherwise compile again for each size.
#include "numerics/linalg.hpp"

namespace spdfit::detail {

#define SPDFIT_LINALG_DEFINE template
SPDFIT_LINALG_INSTANCES(SPDFIT_LINALG_DEFINE)
#undef SPDFIT_LINALG_DEFINE

}  // namespace spdfit::detail
