// Internal names of the BLAS-core rule, whose one home is the public spdfit/blas.hpp (the command
// line restarts itself on it, the Python module warns with it).
#pragma once

#include "spdfit/blas.hpp"

namespace spdfit::detail {

using spdfit::BlasCoreCheck;
using spdfit::blas_core_name;
using spdfit::check_blas_core;
using spdfit::idle_blas_threads;
using spdfit::is_generic_blas_core;
using spdfit::kOpenBlasCoreVariable;
using spdfit::kTestBlasCoreVariable;
using spdfit::set_blas_threads;

}  // namespace spdfit::detail
