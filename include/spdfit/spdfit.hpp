// spdfit: estimating symmetric positive definite matrices from imperfect measurements.
// The umbrella header: includes the whole public API.
#pragma once

#include "spdfit/area_criterion.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/fit_options.hpp"
#include "spdfit/fit_result.hpp"
#include "spdfit/io.hpp"
#include "spdfit/least_squares.hpp"
#include "spdfit/linear_system.hpp"
#include "spdfit/linkage/analysis.hpp"
#include "spdfit/linkage/synthesis.hpp"
#include "spdfit/method.hpp"
#include "spdfit/nearest_spd.hpp"
#include "spdfit/reduction.hpp"
#include "spdfit/spde.hpp"
#include "spdfit/symmetric_procrustes.hpp"
#include "spdfit/total_least_squares.hpp"
#include "spdfit/triangular_factor.hpp"
#include "spdfit/version.hpp"
