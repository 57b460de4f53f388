// The physical fit's option table (hexapod/physical_request.hpp): what each option sets, its
// spelling per front end (the library's messages name `strut_masses`), the options shared with
// the fit's table, and the physical experiment's judgments (compare_to_generic, set_estimators).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "spdfit/experiment/physical.hpp"
#include "spdfit/hexapod/physical_request.hpp"
#include "spdfit/options.hpp"

namespace spdfit {
namespace {

using hexapod::PhysicalOptions;

const OptionSpec<PhysicalOptions>& spec(std::string_view name) {
  const OptionSpec<PhysicalOptions>* found = find_option(hexapod::physical_option_table(), name);
  if (found == nullptr) throw std::logic_error("no physical option " + std::string(name));
  return *found;
}

TEST(PhysicalOptionTable, SetsTheFieldsAndRefusesUnknownValues) {
  PhysicalOptions options;
  set_option(options, spec("strut_masses"), OptionValue{std::string("each")});
  EXPECT_EQ(options.strut_masses, hexapod::StrutMasses::Each);
  set_option(options, spec("criterion"), OptionValue{std::string("ls")});
  EXPECT_EQ(options.criterion, hexapod::PhysicalCriterion::LeastSquares);
  set_option(options, spec("consistent"), OptionValue{false});
  EXPECT_FALSE(options.consistent);
  PhysicalOptions flagged;
  set_option(flagged, spec("unconstrained"), OptionValue{true});
  EXPECT_FALSE(flagged.consistent);
  try {
    set_option(options, spec("strut_masses"), OptionValue{std::string("some")});
    FAIL() << "an unknown strut-mass source was accepted";
  } catch (const OptionError& e) {
    EXPECT_EQ(spell_options(e.what(), Frontend::Cli),
              "--fit-strut-mass must be one of 'geometry', 'common' or 'each', got 'some'");
    EXPECT_EQ(e.code(), Code::OptionValue);
  }
  EXPECT_THROW(set_option(options, spec("criterion"), OptionValue{std::string("tls")}), OptionError);
  EXPECT_THROW(set_option(options, spec("consistent"), OptionValue{std::string("yes")}), OptionError);
}

TEST(PhysicalOptionTable, DefaultsAreTheLibrarysAndEveryOptionIsOffered) {
  const PhysicalOptions defaults;
  EXPECT_EQ(std::get<std::string>(*spec("strut_masses").get(defaults)), "geometry");
  EXPECT_EQ(std::get<std::string>(*spec("criterion").get(defaults)), "eiv");
  EXPECT_TRUE(std::get<bool>(*spec("consistent").get(defaults)));
  for (const auto& s : hexapod::physical_option_table()) {
    EXPECT_FALSE(s.cli.empty() && s.python.empty()) << s.name << " is offered by no front end";
  }
}

TEST(PhysicalOptionTable, MessagesNameStrutMassesAsEachFrontEndSpellsIt) {
  const std::string message = "`strut_masses` = common cannot be estimated on this geometry";
  EXPECT_EQ(spell_options(message, Frontend::Cli),
            "--fit-strut-mass = common cannot be estimated on this geometry");
  EXPECT_EQ(spell_options(message, Frontend::Python),
            "fit_strut_mass = common cannot be estimated on this geometry");
  EXPECT_EQ(spell_option("criterion", Frontend::Cli), "--physical-criterion");
}

TEST(PhysicalOptionTable, SharesTheFitsBootstrapAndGivenLimits) {
  FitOptions fit;
  fit.bootstrap = 40;
  fit.confidence = 0.9;
  fit.seed = 7;
  fit.threads = 3;
  fit.max_iterations = 12;
  fit.rank_tolerance = 1e-6;
  PhysicalOptions options;
  hexapod::apply_fit_options(fit, {}, options);
  EXPECT_EQ(options.bootstrap, 40);
  EXPECT_EQ(options.confidence, 0.9);
  EXPECT_EQ(options.seed, 7u);
  EXPECT_EQ(options.threads, 3u);
  EXPECT_EQ(options.max_iterations, PhysicalOptions{}.max_iterations);  // not given: the physical default
  EXPECT_FALSE(options.rank_tolerance.has_value());
  hexapod::apply_fit_options(fit, {"max_iterations", "rank_tolerance"}, options);
  EXPECT_EQ(options.max_iterations, 12);
  EXPECT_EQ(options.rank_tolerance, 1e-6);
}

experiment::PhysicalMethodErrors errors(const std::string& name, double mean) {
  experiment::PhysicalMethodErrors m;
  m.name = name;
  m.summary = experiment::summarize({mean - 0.1, mean + 0.1});
  return m;
}

TEST(PhysicalExperiment, ComparesPhysicalWithTheBestGenericMethod) {
  experiment::PhysicalExperimentResult result;
  result.options.methods = {Method::Spde, Method::SpdTotalLeastSquares};
  result.options.variants = {"grey-box-ls", "physical"};
  experiment::PhysicalExperimentRow row;
  row.samples = 30;
  row.methods = {errors("spde", 1.5), errors("spd-tls", 1.2), errors("grey-box-ls", 0.3),
                 errors("physical", 0.6)};
  const auto c = experiment::compare_to_generic(result, row);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->best_generic, "spd-tls");  // grey-box-ls is lower but not a generic method
  EXPECT_DOUBLE_EQ(c->ratio, 0.6 / 1.2);
  row.methods.pop_back();
  EXPECT_FALSE(experiment::compare_to_generic(result, row).has_value());
}

TEST(PhysicalExperiment, SetEstimatorsSplitsMethodsAndVariants) {
  experiment::PhysicalExperimentOptions options;
  experiment::set_estimators(options, {"physical", "ls", "grey-box-tls:each", "spde"});
  EXPECT_EQ(options.methods, (std::vector<Method>{Method::LeastSquares, Method::Spde}));
  EXPECT_EQ(options.variants, (std::vector<std::string>{"physical", "grey-box-tls:each"}));
  try {
    experiment::set_estimators(options, {"spde", "nonsense"});
    FAIL() << "an unknown name was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("unknown method 'nonsense'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace spdfit
