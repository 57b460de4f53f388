// Outcome codes: the table is complete and consistent, each front end's form follows from the code,
// errors carry their code and subject through the library, and warnings carry theirs.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include <Eigen/Core>

#include "interface/tables.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/io.hpp"
#include "spdfit/noise_model.hpp"
#include "spdfit/outcome.hpp"

namespace spdfit {
namespace {

TEST(Outcome, EveryCodeHasOneRowInTheEnumsOrder) {
  std::set<std::string_view> names;
  const auto& codes = outcome_codes();
  for (std::size_t k = 0; k < codes.size(); ++k) {
    EXPECT_EQ(static_cast<std::size_t>(codes[k].code), k) << codes[k].name;
    EXPECT_TRUE(names.insert(codes[k].name).second) << codes[k].name;
    EXPECT_FALSE(codes[k].meaning.empty()) << codes[k].name;
    EXPECT_EQ(code_named(codes[k].name), codes[k].code);
    // snake_case names: the stable form the front ends derive theirs from.
    for (char c : codes[k].name) EXPECT_TRUE((c >= 'a' && c <= 'z') || c == '_') << codes[k].name;
  }
  EXPECT_EQ(static_cast<std::size_t>(Code::DiagonalChanged) + 1, codes.size()) << "a code without its row (the last)";
  EXPECT_FALSE(code_named("no_such_code").has_value());
}

TEST(Outcome, FrontEndFormsFollowFromTheTier) {
  for (const CodeInfo& info : outcome_codes()) {
    const std::string python = python_class(info.code), matlab = matlab_identifier(info.code);
    EXPECT_EQ(matlab.rfind("spdfit:", 0), 0u) << info.name;
    switch (info.tier) {
      case Tier::Usage:
        EXPECT_EQ(exit_status(info.code), 2) << info.name;
        EXPECT_EQ(matlab, "spdfit:UsageError");
        EXPECT_TRUE(python == "TypeError" || python == "ValueError") << python;
        break;
      case Tier::Data:
        EXPECT_EQ(exit_status(info.code), 1) << info.name;
        EXPECT_EQ(matlab, "spdfit:DataError");
        EXPECT_EQ(python, "DataError");
        break;
      case Tier::Numerical:
        EXPECT_EQ(exit_status(info.code), 1);
        EXPECT_EQ(matlab, "spdfit:NumericalError");
        EXPECT_EQ(python, "NumericalError");
        break;
      case Tier::Internal:
        EXPECT_EQ(exit_status(info.code), 1);
        break;
      case Tier::Warning:
        EXPECT_EQ(exit_status(info.code), 0);
        EXPECT_EQ(python.size() > 7 ? python.substr(python.size() - 7) : "", "Warning") << python;
        break;
    }
  }
  // The identifiers MATLAB users silence today are kept.
  EXPECT_EQ(matlab_identifier(Code::RankDeficient), "spdfit:rankDeficient");
  EXPECT_EQ(matlab_identifier(Code::NotPositiveDefinite), "spdfit:notPositiveDefinite");
  EXPECT_EQ(matlab_identifier(Code::NoiseModelNotice), "spdfit:noiseModel");
  EXPECT_EQ(matlab_identifier(Code::BootstrapNotice), "spdfit:bootstrap");
  EXPECT_EQ(matlab_identifier(Code::Warning), "spdfit:warning");
  EXPECT_EQ(python_class(Code::RankDeficient), "RankDeficientWarning");
  EXPECT_EQ(python_class(Code::Warning), "SpdfitWarning");
  EXPECT_EQ(python_class(Code::OptionType), "TypeError");
}

TEST(Outcome, ExceptionsCarryTheirCode) {
  EXPECT_EQ(code_of(OptionError("x")), Code::OptionValue);
  EXPECT_EQ(code_of(OptionError("x", Code::OptionConflict, "seed")), Code::OptionConflict);
  EXPECT_EQ(subject_of(OptionError("x", Code::OptionConflict, "seed")), "seed");
  EXPECT_EQ(code_of(io::DataError("a.csv", 3, 1, "bad")), Code::File);
  EXPECT_EQ(subject_of(io::DataError("a.csv", 3, 1, "bad")), "a.csv");
  EXPECT_EQ(code_of(io::ColumnSelectionError("x", "a_cols")), Code::ColumnSelection);
  EXPECT_EQ(code_of(InputError("x", Code::NoiseModel, "noise_cov_a")), Code::NoiseModel);
  // A plain std::invalid_argument is the library refusing input; anything else is spdfit's fault.
  EXPECT_EQ(code_of(std::invalid_argument("x")), Code::DataValue);
  EXPECT_EQ(code_of(std::runtime_error("x")), Code::Internal);
  EXPECT_EQ(code_of(std::bad_alloc()), Code::OutOfMemory);
  EXPECT_THROW((Problem{Code::OptionConflict, "m", "s"}.raise()), OptionError);
  EXPECT_THROW((Problem{Code::NoiseModel, "m", "s"}.raise()), InputError);
}

TEST(Outcome, NoiseModelRefusalsAreDataErrorsNamingTheOption) {
  Eigen::MatrixXd indefinite(2, 2);
  indefinite << 1, 2, 2, 1;
  try {
    NoiseModel::from_cov(indefinite, Eigen::MatrixXd::Identity(2, 2));
    FAIL() << "an indefinite covariance was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.code(), Code::NoiseModel);
    EXPECT_EQ(e.subject(), "noise_cov_a");
    EXPECT_EQ(tier(e.code()), Tier::Data);
  }
  // A negative standard deviation is an option's value out of range: a usage error.
  try {
    NoiseModel::from_std(Eigen::VectorXd::Constant(1, -1.0), Eigen::VectorXd::Constant(1, 1.0));
    FAIL() << "a negative standard deviation was accepted";
  } catch (const OptionError& e) {
    EXPECT_EQ(tier(e.code()), Tier::Usage);
    EXPECT_EQ(e.subject(), "noise_std_a");
  }
}

TEST(Outcome, WarningsCarryTheirCode) {
  // A rank-deficient A: ls warns so, with the code front ends map.
  Eigen::MatrixXd A(4, 2), B(4, 2);
  A << 1, 2, 2, 4, 3, 6, 4, 8;
  B << 1, 0, 0, 1, 1, 1, 2, 1;
  const FitResult r = fit(A, B, Method::LeastSquares);
  bool found = false;
  for (const Warning& w : r.warnings) found = found || w.code == Code::RankDeficient;
  EXPECT_TRUE(found);
  for (const Warning& w : r.warnings) EXPECT_EQ(tier(w.code), Tier::Warning) << w.text;
}

TEST(Outcome, OptionCheckingGivesUsageCodes) {
  const auto code_of_check = [](const std::function<void()>& check) {
    try {
      check();
    } catch (const OptionError& e) {
      return e.code();
    }
    return Code::Internal;
  };
  const auto& spec = *find_option(fit_option_table(), "max_iterations");
  EXPECT_EQ(code_of_check([&] { checked_value(spec, OptionValue{std::string("ten")}); }), Code::OptionType);
  EXPECT_EQ(code_of_check([&] { checked_value(spec, OptionValue{std::int64_t{0}}); }), Code::OptionValue);
  EXPECT_EQ(code_of_check([] { check_option_combination(fit_option_table(), {"confidence"}); }),
            Code::OptionConflict);
}

// Every table's spellings are unique within the table and every entry can be set.
TEST(Outcome, EveryTableIsWellFormed) {
  detail::for_each_option_table([](const auto& table) {
    std::set<std::string_view> names, cli, python;
    for (const auto& spec : table) {
      EXPECT_TRUE(names.insert(spec.name).second) << spec.name;
      if (!spec.cli.empty()) {
        EXPECT_TRUE(cli.insert(spec.cli).second) << spec.cli;
      }
      if (!spec.python.empty() && !spec.positional) {
        EXPECT_TRUE(python.insert(spec.python).second) << spec.python;
      }
      EXPECT_TRUE(static_cast<bool>(spec.set)) << spec.name;
      EXPECT_FALSE(spec.help.empty()) << spec.name;
      if (spec.type == OptionType::Choice) {
        EXPECT_FALSE(spec.choices.empty()) << spec.name;
      }
      for (std::string_view other : spec.excludes) EXPECT_TRUE(find_option(table, other) != nullptr) << other;
      for (std::string_view other : spec.needs) EXPECT_TRUE(find_option(table, other) != nullptr) << other;
    }
  });
}

}  // namespace
}  // namespace spdfit
