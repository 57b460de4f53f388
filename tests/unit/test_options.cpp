// The option tables and their rules: types and ranges, which methods take which option, the
// combinations, and the spelling of option names per front end.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "spdfit/fit_request.hpp"
#include "spdfit/nearest_request.hpp"
#include "spdfit/options.hpp"

namespace spdfit {
namespace {

const OptionSpec<FitRequest>& fit_spec(std::string_view name) {
  const OptionSpec<FitRequest>* spec = find_option(fit_option_table(), name);
  if (spec == nullptr) throw std::logic_error("no option " + std::string(name));
  return *spec;
}

std::string message_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const OptionError& e) {
    return e.what();
  }
  return "";
}

TEST(OptionTable, EveryEntryIsComplete) {
  std::set<std::string_view> names, cli, python;
  for (const auto& spec : fit_option_table()) {
    EXPECT_TRUE(names.insert(spec.name).second) << spec.name;
    if (!spec.cli.empty()) {
      EXPECT_TRUE(cli.insert(spec.cli).second) << spec.cli;
    }
    if (!spec.python.empty()) {
      EXPECT_TRUE(python.insert(spec.python).second) << spec.python;
    }
    EXPECT_NE(spec.set, nullptr) << spec.name;
    EXPECT_NE(spec.get, nullptr) << spec.name;
    EXPECT_FALSE(spec.help.empty()) << spec.name;
    EXPECT_FALSE(spec.cli.empty() && spec.python.empty()) << spec.name << " is offered nowhere";
    for (std::string_view need : spec.needs) EXPECT_NE(find_option(fit_option_table(), need), nullptr) << need;
    for (std::string_view other : spec.excludes) EXPECT_NE(find_option(fit_option_table(), other), nullptr) << other;
  }
  for (const auto& spec : nearest_option_table()) {
    EXPECT_NE(spec.set, nullptr) << spec.name;
    for (std::string_view need : spec.needs) EXPECT_NE(find_option(nearest_option_table(), need), nullptr) << need;
  }
}

TEST(OptionTable, TheDefaultsAreTheLibrarysAndInRange) {
  // Each getter reads the request's own default, and every default passes its own range check.
  const FitRequest request;
  std::string error;
  EXPECT_TRUE(request.is_valid(&error)) << error;
  EXPECT_EQ(std::get<std::int64_t>(*fit_spec("max_iterations").get(request)), FitOptions{}.max_iterations);
  EXPECT_EQ(std::get<std::int64_t>(*fit_spec("block_rows").get(request)), StreamOptions{}.block_rows);
  EXPECT_EQ(std::get<double>(*fit_spec("confidence").get(request)), FitOptions{}.confidence);
  EXPECT_FALSE(fit_spec("rank_tolerance").get(request).has_value());  // the default is a rule, not a number
}

TEST(OptionTable, ValuesAreCheckedForTypeAndRange) {
  FitRequest request;
  set_option(request, fit_spec("max_iterations"), std::int64_t{7});
  EXPECT_EQ(request.options.max_iterations, 7);
  set_option(request, fit_spec("noise_ratio"), std::int64_t{2});  // an integer is a real number
  EXPECT_EQ(request.options.noise_ratio, 2.0);
  set_option(request, fit_spec("rank_tolerance"), 0.25);
  EXPECT_EQ(request.options.rank_tolerance, 0.25);
  EXPECT_EQ(message_of([&] { set_option(request, fit_spec("max_iterations"), std::int64_t{0}); }),
            "`max_iterations` must be an integer in [1, 1000000], got 0");
  EXPECT_EQ(message_of([&] { set_option(request, fit_spec("max_iterations"), 2.5); }),
            "`max_iterations` must be an integer, got 2.5");
  EXPECT_EQ(message_of([&] { set_option(request, fit_spec("noise_ratio"), 0.0); }),
            "`noise_ratio` must be a finite number > 0, got 0");
  EXPECT_EQ(message_of([&] { set_option(request, fit_spec("rank_tolerance"), 1.0); }),
            "`rank_tolerance` must be a number in [0, 1), got 1");
  EXPECT_EQ(message_of([&] { set_option(request, fit_spec("confidence"), 1.0); }),
            "`confidence` must be a fraction strictly between 0 and 1, got 1");
  EXPECT_FALSE(message_of([&] { set_option(request, fit_spec("min_eig"), std::nan("")); }).empty());
  EXPECT_FALSE(message_of([&] { set_option(request, fit_spec("min_eig"), HUGE_VAL); }).empty());
  // A value refused leaves the request as it was.
  EXPECT_EQ(request.options.max_iterations, 7);
}

TEST(OptionTable, AnOptionGivenWhereItDoesNotApplyNamesWhoTakesIt) {
  FitRequest request;
  request.method = Method::Spde;
  EXPECT_EQ(message_of([&] { check_fit_request(request, {"noise_ratio"}); }),
            "`noise_ratio` applies to the total least-squares methods and auto (tls, tls-sym, tls-psd, spd-tls, "
            "auto), not to spde");
  EXPECT_EQ(message_of([&] { check_fit_request(request, {"min_eig"}); }), "`min_eig` applies to psd-ls, not to spde");
  request.method = Method::PsdLeastSquares;
  EXPECT_EQ(message_of([&] { check_fit_request(request, {"min_eig", "max_iterations"}); }), "");
  // Every method takes the options without a rule.
  for (Method m : kSelectableMethods) {
    request.method = m;
    EXPECT_EQ(message_of([&] { check_fit_request(request, {"rank_tolerance", "bootstrap"}); }), "");
  }
}

TEST(OptionTable, CombinationRules) {
  FitRequest request;
  EXPECT_EQ(message_of([&] { check_fit_request(request, {"seed"}); }),
            "`seed` applies to the bootstrap: give `bootstrap` N as well");
  EXPECT_EQ(message_of([&] { check_fit_request(request, {"seed", "bootstrap"}); }), "");
  EXPECT_EQ(message_of([&] { check_fit_request(request, {"block_rows"}); }), "`block_rows` needs `stream`");
  EXPECT_EQ(message_of([&] { check_fit_request(request, {"threads", "stream"}); }), "");
  EXPECT_EQ(message_of([&] { check_nearest_request({"min_eig", "min_eig_rel"}); }),
            "give `min_eig` or `min_eig_rel`, not both");
  EXPECT_EQ(message_of([&] { check_nearest_request({"weights"}); }), "`weights` needs `corr`, `keep_diag`, `via_corr` or `fixed`");
  EXPECT_EQ(message_of([&] { check_nearest_request({"weights"}, {"corr"}); }), "`weights` needs `keep_diag`, `via_corr` or `fixed`");
  EXPECT_EQ(message_of([&] { check_nearest_request({"weights", "keep_diag"}); }), "");
}

TEST(OptionTable, TheNoiseModelsSourcesArePairsThatExcludeEachOtherAndTheRatio) {
  FitRequest request;
  request.method = Method::SpdTotalLeastSquares;
  set_option(request, fit_spec("noise_std_a"), std::vector<double>{0.5});
  set_option(request, fit_spec("noise_std_b"), std::vector<double>{1.0, 2.0});
  check_fit_request(request, {"noise_std_a", "noise_std_b"});
  const FitOptions options = request.resolved_options(3, 2);
  ASSERT_TRUE(options.noise.has_value());
  EXPECT_EQ(options.noise->source(), NoiseSource::Std);
  // One standard deviation for every column, one per column: diag(std^2), exactly.
  EXPECT_EQ(options.noise->cov_a(), Eigen::MatrixXd(0.25 * Eigen::MatrixXd::Identity(3, 3)));
  EXPECT_EQ(options.noise->cov_b(), Eigen::MatrixXd(Eigen::Vector2d(1.0, 4.0).asDiagonal()));
  EXPECT_NE(message_of([&] { set_option(request, fit_spec("noise_std_a"), std::vector<double>{0.1, -1.0}); })
                .find("`noise_std_a` must be a list of numbers, each a finite number >= 0"),
            std::string::npos);
  EXPECT_EQ(message_of([&] { check_fit_request(request, {"noise_std_a", "noise_std_b", "noise_ratio"}); }),
            "give `noise_std_a` or `noise_ratio`, not both");
  EXPECT_EQ(message_of([&] { check_fit_request(request, {"rest_a", "rest_b", "noise_std_a", "noise_std_b"}); }),
            "give `rest_a` or `noise_std_a`, not both");
  EXPECT_EQ(message_of([&] { check_fit_request(request, {"rest_a"}); }),
            "`rest_a` and `rest_b` come together: the rows of A and of B recorded at rest");
  request.method = Method::Spde;
  const std::string spde = message_of([&] { check_fit_request(request, {"noise_std_a", "noise_std_b"}); });
  EXPECT_NE(spde.find("auto or spd-tls"), std::string::npos) << spde;
  EXPECT_NE(spde.find("not to spde"), std::string::npos) << spde;
  // The model's sizes against the data's, naming the option.
  request.method = Method::SpdTotalLeastSquares;
  EXPECT_NE(message_of([&] { request.resolved_options(3, 3); }).find("`noise_std_b`"), std::string::npos);
}

TEST(OptionSpelling, EachFrontEndHasItsOwn) {
  const std::string message = "`max_iterations` must be at least 1; see `block_rows` and `dial_zero`";
  EXPECT_EQ(spell_options(message, Frontend::Cli), "--max-iter must be at least 1; see --block-rows and --dial-zero");
  EXPECT_EQ(spell_options(message, Frontend::Python), "max_iter must be at least 1; see block_rows and dial_zero");
  EXPECT_EQ(spell_options(message, Frontend::Matlab), "MaxIterations must be at least 1; see BlockRows and DialZero");
  EXPECT_EQ(spell_options(message, Frontend::Library),
            "max_iterations must be at least 1; see block_rows and dial_zero");
  EXPECT_EQ(spell_options("a lone ` stays", Frontend::Cli), "a lone ` stays");
  EXPECT_EQ(spell_option("tolerance", Frontend::Cli), "--tol");
  EXPECT_EQ(camel_case("min_eig_rel"), "MinEigRel");
}

TEST(OptionSpelling, RangesReadAsPeopleWriteThem) {
  EXPECT_EQ((NumberRange{0.0, 1e6}.describe(true)), "integer in [0, 1000000]");
  EXPECT_EQ((NumberRange{0.0, HUGE_VAL, true, true}.describe(false)), "finite number > 0");
  EXPECT_EQ((NumberRange{0.0, HUGE_VAL}.describe(false)), "finite number >= 0");
  EXPECT_EQ((NumberRange{0.0, 1.0, false, true}.describe(false)), "number in [0, 1)");
}

TEST(NearestRequest, ChoosesTheRepairTheOptionsName) {
  const Eigen::MatrixXd C = (Eigen::MatrixXd(3, 3) << 2, 1.9, 0, 1.9, 2, 1.9, 0, 1.9, 2).finished();  // indefinite
  NearestRequest request;
  request.min_eig = 0.0;
  EXPECT_TRUE(nearest(C, request).X.isApprox(nearest_spd(C, 0.0).X, 0.0));
  request.keep_diag = true;
  const NearestResult kept = nearest(C, request);
  EXPECT_EQ(kept.X.diagonal(), C.diagonal());
  NearestCorrelationOptions options;
  options.floor = EigenvalueFloor::absolute(0.0);
  EXPECT_TRUE(kept.X.isApprox(nearest_keep_diagonal(C, options).X, 0.0));
}

}  // namespace
}  // namespace spdfit
