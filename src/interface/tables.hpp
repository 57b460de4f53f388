// Every option table of the library, for what needs all of them: the spellings of option names
// in messages (spelling.cpp) and the tests that check the tables. A new command's table is added
// here.
#pragma once

#include "spdfit/compare.hpp"
#include "spdfit/experiment/demo.hpp"
#include "spdfit/experiment/experiment_request.hpp"
#include "spdfit/fit_request.hpp"
#include "spdfit/hexapod/physical_request.hpp"
#include "spdfit/hexapod/identify_request.hpp"
#include "spdfit/hexapod/model_request.hpp"
#include "spdfit/hexapod/simulate_request.hpp"
#include "spdfit/inertia_repair.hpp"
#include "spdfit/linkage/analyze_request.hpp"
#include "spdfit/linkage/synthesize_request.hpp"
#include "spdfit/nearest_request.hpp"
#include "spdfit/output_request.hpp"
#include "spdfit/payload/design.hpp"
#include "spdfit/payload/identify.hpp"
#include "spdfit/physical/regress.hpp"
#include "spdfit/solve_request.hpp"

namespace spdfit::detail {

/// Calls `visit(table)` for every option table, in a fixed order.
template <typename Visit>
void for_each_option_table(Visit&& visit) {
  visit(fit_option_table());
  visit(fit_command_table());
  visit(nearest_option_table());
  visit(hexapod::physical_option_table());
  visit(hexapod::identify_option_table());
  visit(hexapod::physical_fit_table());
  visit(solve_option_table());
  visit(nearest_command_table());
  visit(compare_option_table());
  visit(output_option_table());
  visit(global_option_table());
  visit(payload::identify_option_table());
  visit(payload::design_option_table());
  visit(physical::regress_option_table());
  visit(inertia_repair_option_table());
  visit(hexapod::model_option_table());
  visit(hexapod::simulate_option_table());
  visit(linkage::synthesize_option_table());
  visit(linkage::analyze_option_table());
  visit(experiment::demo_option_table());
  for (experiment::ExperimentKind kind : experiment::kExperimentKinds) visit(experiment::experiment_option_table(kind));
}

}  // namespace spdfit::detail
