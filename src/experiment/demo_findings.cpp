// The demo's explanation. Every statement is chosen by comparing the numbers just computed
// (paired differences and their standard errors); none is fixed text about which method wins.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "experiment/demo_report.hpp"
#include "render/experiment_render.hpp"
#include "spdfit/format.hpp"

namespace spdfit::experiment::demo {

namespace {

using experiment::EntryExperimentResult;
using experiment::PairedComparison;
using experiment::ThesisExperimentResult;

using experiment::order_of;
using experiment::Order;

const char* const kEntryNames[] = {"x11", "x12", "x22"};

// The seed documents' three main methods, which the conclusion ranks.
const std::vector<Method> kCompared = {Method::SymmetricProcrustes, Method::TotalLeastSquaresSymmetric,
                                       Method::Spde};

// What the statements found, for the conclusion.
struct Facts {
  bool spde_below_procrustes = false;  ///< at every thesis level, significantly
  bool spde_wins_somewhere = false;    ///< SPDE wins every 2x2 entry at the top levels
  std::string procrustes_better;       ///< entries where Procrustes wins at std_a = 0
  Method best_large = Method::Spde;    ///< the most accurate at the largest sample size
  Eigen::Index most_samples = 0;
};

// The thesis' experiments: SPDE against Procrustes level by level, least squares, TLS.
std::string thesis_statements(const std::vector<ThesisExperimentResult>& thesis, Facts& facts) {
  std::ostringstream out;
  // SPDE against Procrustes at each level, trial by trial.
  std::vector<PairedComparison> c;
  for (const ThesisExperimentResult& r : thesis) {
    c.push_back(r.compare(Method::Spde, Method::SymmetricProcrustes));
  }
  bool all_lower = true, growing = true;  // SPDE below Procrustes at every level; gain growing
  double previous_gain = -1, weakest = INFINITY;
  std::string gains, losses;
  for (std::size_t i = 0; i < thesis.size(); ++i) {
    const double procrustes = thesis[i].of(Method::SymmetricProcrustes).summary.mean;
    const double gain = -c[i].mean_difference / procrustes;
    all_lower = all_lower && order_of(c[i]) == Order::Lower;
    growing = growing && gain > previous_gain;
    previous_gain = gain;
    weakest = std::min(weakest, -c[i].mean_difference / c[i].standard_error);
    gains += std::string(i ? ", " : "") + percent(gain) +
             " at V = " + format_number(thesis[i].options.simulation.noise_var);
    losses += std::string(i ? ", " : "") + percent(1.0 - c[i].fraction_lower);
  }
  std::string text;
  if (all_lower) {
    text =
        "Hexapod, thesis set-up: SPDE's mean error is below symmetric Procrustes' at all three noise levels, "
        "by " +
        gains + (growing ? ", growing with the noise" : "") + ". The smallest of these differences is " +
        format_fixed(weakest, 0) + " standard errors of the trial-by-trial difference: far beyond chance.";
  } else {
    text = "Hexapod, thesis set-up, SPDE against symmetric Procrustes:";
    for (std::size_t i = 0; i < thesis.size(); ++i) {
      const Order o = order_of(c[i]);
      text += std::string(i ? ";" : "") + " at V = " + format_number(thesis[i].options.simulation.noise_var) + " " +
              (o == Order::Lower    ? "SPDE's mean error is lower"
               : o == Order::Higher ? "SPDE's mean error is higher"
                                    : "no significant difference");
    }
    text += ".";
  }
  text +=
      " Yet Procrustes is closer to the truth in " + losses +
      " of the single runs, so one run like the thesis' tables can show either order; the averages are what "
      "carries over to new data.";
  out << bullet(text);

  bool ls_worse = true;
  for (const ThesisExperimentResult& r : thesis) {
    ls_worse =
        ls_worse && order_of(r.compare(Method::LeastSquares, Method::SymmetricProcrustes)) == Order::Higher;
  }
  if (ls_worse) {
    out << bullet(
        "Ignoring symmetry costs accuracy: unconstrained least squares (ls) is worse than Procrustes at "
        "every level.");
  }
  const experiment::Summary& tls = thesis.back().of(Method::TotalLeastSquaresSymmetric).summary;
  const experiment::Summary& spde_high = thesis.back().of(Method::Spde).summary;
  if (tls.mean > 1.1 * tls.median && tls.max > 5.0 * tls.median) {
    out << bullet(
        "TLS made symmetric (eq. 4.38) is erratic: at V = " +
        format_number(thesis.back().options.simulation.noise_var) + " its mean error " + format_number(tls.mean) +
        " is pulled far above its median " + format_number(tls.median) + " by a few runs with errors up to " +
        format_number(tls.max) + " (SPDE's largest: " + format_number(spde_high.max) +
        "): its formula -V12 V22^-1 divides by V22, which is nearly singular in a few runs, and nothing "
        "guards against that.");
  }

  facts.spde_below_procrustes = all_lower;
  return out.str();
}

// The 2x2 example: from which level SPDE wins every entry, std_a = 0, TLS's stability.
std::string paper_statements(const std::vector<EntryExperimentResult>& paper, Facts& facts) {
  std::ostringstream out;
  std::vector<std::vector<PairedComparison>> entry(paper.size());
  for (std::size_t l = 0; l < paper.size(); ++l) entry[l] = paper[l].compare(Method::Spde, Method::SymmetricProcrustes);
  std::size_t from = paper.size();
  for (std::size_t l = paper.size(); l-- > 0;) {
    bool wins = true;
    for (const PairedComparison& e : entry[l]) wins = wins && order_of(e) == Order::Lower;
    if (!wins) break;
    from = l;
  }
  std::string text;
  if (from < paper.size()) {
    const EntryExperimentResult& last = paper.back();
    text = "2x2 example: from std_a = " + format_number(levels_2x2()[from]) +
           " on, SPDE's mean absolute error is below Procrustes' for x11, x12 and x22; at std_a = " +
           format_number(levels_2x2().back()) + " it is";
    for (Eigen::Index e = 0; e < 3; ++e) {
      text += std::string(e ? "," : "") + " " + format_number(last.of(Method::Spde).mae(e)) + " against " +
              format_number(last.of(Method::SymmetricProcrustes).mae(e)) + " for " + kEntryNames[e];
    }
    text += ".";
  } else {
    text = "2x2 example: SPDE does not beat Procrustes on every entry at any of the levels run.";
  }
  std::string procrustes_better, spde_better;  // at std_a = 0 (levels_2x2() starts there)
  for (std::size_t e = 0; e < 3; ++e) {
    const Order o = order_of(entry.front()[e]);
    std::string& list = o == Order::Higher ? procrustes_better : spde_better;
    if (o != Order::Tie) list += std::string(list.empty() ? "" : ", ") + kEntryNames[e];
  }
  if (spde_better.empty()) {
    text += " With no noise in A (std_a = 0) " +
            (procrustes_better.empty() ? std::string("the two are within noise of each other")
                                       : "Procrustes is the better one, for " + procrustes_better) +
            ": least squares assumes exactly that A is exact, and SPDE's area criterion, which allows for "
            "noise in "
            "A, has nothing to gain.";
  } else {
    text += " Even with no noise in A (std_a = 0) SPDE is better for " + spde_better + ".";
  }
  out << bullet(text);

  const experiment::EntryStatistics& tls_2x2 = paper.back().of(Method::TotalLeastSquares);
  const experiment::EntryStatistics& spde_2x2 = paper.back().of(Method::Spde);
  Eigen::Index worst = 0;
  (tls_2x2.std.array() / spde_2x2.std.array()).maxCoeff(&worst);
  if (tls_2x2.std(worst) > 5.0 * spde_2x2.std(worst)) {
    out << bullet(
        "TLS allows for noise in A too, but is unstable: at std_a = " + format_number(levels_2x2().back()) +
        " the standard deviation of its " + kEntryNames[worst] + " error is " + format_number(tls_2x2.std(worst)) +
        " against SPDE's " + format_number(spde_2x2.std(worst)) +
        " (the paper attributes this to TLS not enforcing positive definiteness).");
  }

  facts.spde_wins_somewhere = from < paper.size();
  facts.procrustes_better = procrustes_better;
  return out.str();
}

// Experiment 2 with more samples: how the errors fall, and who is most accurate at the end.
std::string samples_statements(const std::vector<ThesisExperimentResult>& samples, Facts& facts) {
  const ThesisExperimentResult& most = samples.back();
  const Method best_large = most.best_of(kCompared);
  const ThesisExperimentResult& middle = samples.front();
  auto fall = [&](Method method) {
    const double from_mean = middle.of(method).summary.mean, to_mean = most.of(method).summary.mean;
    const std::string name(to_string(method));
    return name + (name.back() == 's' ? "' by " : "'s by ") + percent(1.0 - to_mean / from_mean) + " (" +
           format_number(from_mean) + " to " + format_number(to_mean) + ")";
  };
  auto fall_fraction = [&](Method method) {
    return 1.0 - most.of(method).summary.mean / middle.of(method).summary.mean;
  };
  std::string text = "More samples: from m = " + std::to_string(middle.options.simulation.samples) + " to " +
                     std::to_string(most.options.simulation.samples) + " the mean error falls " +
                     fall(Method::Spde) + ", " + fall(Method::TotalLeastSquaresSymmetric) + ", " +
                     fall(Method::SymmetricProcrustes) + ".";
  if (best_large != Method::Spde) {
    const PairedComparison edge = most.compare(best_large, Method::Spde);
    text += " At m = " + std::to_string(most.options.simulation.samples) + " " +
            std::string(to_string(best_large)) + " is the most accurate" +
            (order_of(edge) == Order::Lower ? " (" + format_fixed(-edge.mean_difference / edge.standard_error, 0) +
                                                  " standard errors below spde)"
                                            : std::string(", though not significantly below spde")) +
            ".";
    bool others_slower = true;
    for (Method method : kCompared) {
      others_slower =
          others_slower && (method == best_large || fall_fraction(method) < fall_fraction(best_large));
    }
    if (others_slower) text += " The others' errors fall more slowly with more data.";
    if (best_large == Method::TotalLeastSquaresSymmetric) {
      text +=
          " TLS models noise of the same variance in A and B, which is what is simulated here; with real "
          "sensors, scale A and B to equal noise levels first (docs/hexapod.md).";
    }
  } else {
    text += " spde stays the most accurate at m = " + std::to_string(most.options.simulation.samples) + ".";
  }
  facts.best_large = best_large;
  facts.most_samples = most.options.simulation.samples;
  return bullet(text);
}

}  // namespace

// Section 5: where spd-tls overtakes spde, and how close auto stays to the best.
std::string beyond_statements(const std::vector<ThesisExperimentResult>& beyond) {
  std::ostringstream out;
  double worst_ratio = 0.0;
  std::string worst_point;
  std::string crossover;
  std::size_t i = 0;
  for (double width : beyond_widths()) {
    Eigen::Index first_tls = -1;
    bool tls_stays = true;
    for (Eigen::Index m : beyond_sizes()) {
      const ThesisExperimentResult& r = beyond[i++];
      const double best = r.of(r.best_of(beyond_estimators())).summary.mean;
      const double ratio = r.of(Method::Auto).summary.mean / best;
      if (ratio > worst_ratio) {
        worst_ratio = ratio;
        worst_point = "nm = " + format_number(width) + ", m = " + std::to_string(m);
      }
      const bool tls_better = r.of(Method::SpdTotalLeastSquares).summary.mean < r.of(Method::Spde).summary.mean;
      if (tls_better && first_tls < 0) first_tls = m;
      if (!tls_better && first_tls >= 0) tls_stays = false;
    }
    crossover += std::string(crossover.empty() ? "" : "; ") + "at nm = " + format_number(width) + ", " +
                 (first_tls < 0 ? std::string("spde is lower at every m")
                                : "spd-tls is lower than spde from m = " + std::to_string(first_tls) +
                                      (tls_stays ? " on" : " (not at every larger m)"));
  }
  out << bullet("Section 5: spde's error stops falling as m grows (it is biased), spd-tls's keeps falling; " +
                crossover + ". auto's mean error is at most " + percent(worst_ratio - 1.0) +
                " above the best method's (worst at " + worst_point + ").");
  return out.str();
}

namespace {

// Section 6: how much closer the physical estimate is than the best generic one, and whether
// every physical estimate could be a body.
std::string physical_statements(const std::optional<experiment::PhysicalExperimentResult>& physical) {
  if (!physical) return "";
  double low = std::numeric_limits<double>::infinity(), high = 0.0;
  std::size_t inconsistent = 0;
  for (const experiment::PhysicalExperimentRow& row : physical->rows) {
    if (const auto c = experiment::compare_to_generic(*physical, row)) {
      low = std::min(low, c->ratio);
      high = std::max(high, c->ratio);
    }
    for (const experiment::PhysicalMethodErrors& m : row.methods) {
      if (m.name == "physical") inconsistent += m.inconsistent;
    }
  }
  if (!(high > 0.0)) return "";
  std::string text =
      "Section 6: with the geometry known, fitting the payload's mass, centre of mass and inertia gives M_p "
      "with " +
      format_fixed(low, 2) + (high > low ? " to " + format_fixed(high, 2) : std::string()) +
      " times the error of the best generic method at every m, and " +
      (inconsistent == 0 ? std::string("every physical estimate is a body that can exist")
                         : std::to_string(inconsistent) + " physical estimates are not consistent") +
      ".";
  return bullet(text);
}

}  // namespace

// Section 7: what the rest segment gains when the units and sensors differ.
std::string units_statements(const ThesisExperimentResult& units) {
  const double assumed = units.of(Method::Auto, experiment::FitNoise::None).summary.mean;
  const double rest = units.of(Method::Auto, experiment::FitNoise::Rest).summary.mean;
  std::string text = "Section 7: with forces in kN and sensors of different noise, auto assuming equal noise errs by " +
                     format_fixed(assumed, 3) + "; given the rest segment's covariances it errs by " +
                     format_fixed(rest, 3);
  if (rest < assumed) {
    text += " (" + format_number(assumed / rest, Precision::Brief) +
            " times less), whatever the units: record a few seconds at rest and give them with "
            "--rest-a and --rest-b.";
  } else {
    text += ": here the noise model does not help.";
  }
  return bullet(text);
}

std::string findings(const Results& results) {
  Facts facts;
  std::string out = "== What the numbers show\n\n";
  out += thesis_statements(results.thesis, facts);
  out += paper_statements(results.paper, facts);
  out += samples_statements(results.samples, facts);
  out += beyond_statements(results.beyond);
  out += physical_statements(results.physical);
  out += units_statements(results.units);

  // The conclusion follows from the statements above.
  bool spde_best_small = true;
  for (const ThesisExperimentResult& r : results.thesis) {
    spde_best_small = spde_best_small && r.best_of(kCompared) == Method::Spde;
  }
  std::string conclusion = "In short:";
  if (spde_best_small && facts.spde_below_procrustes && facts.spde_wins_somewhere) {
    conclusion +=
        " with few samples (m = 12, as in the thesis) and noise in both the accelerations and the forces, "
        "spde is the most accurate estimate;";
  } else {
    conclusion += " at m = 12 no method is the most accurate at every noise level (see the tables);";
  }
  conclusion += std::string(" when A is exact, symmetric Procrustes is ") +
                (facts.procrustes_better.empty() ? "as good" : "as good or better");
  if (facts.best_large != Method::Spde) {
    conclusion += "; with many samples (m = " + std::to_string(facts.most_samples) + ") " +
                  std::string(to_string(facts.best_large)) + " overtakes spde.";
  } else {
    conclusion += ", and spde keeps its lead with many samples.";
  }
  // Section 5's largest m: spd-tls against the best of the others.
  bool spd_tls_best_large = true;
  for (std::size_t w = 0; w < beyond_widths().size(); ++w) {
    const ThesisExperimentResult& r = results.beyond[(w + 1) * beyond_sizes().size() - 1];
    if (r.of(r.best_of(beyond_estimators())).summary.mean < r.of(Method::SpdTotalLeastSquares).summary.mean) {
      spd_tls_best_large = false;
    }
  }
  if (spd_tls_best_large) {
    conclusion += " Beyond the seeds, spd-tls is the most accurate at m = " +
                  std::to_string(beyond_sizes().back()) +
                  " at both noise levels, and positive definite: with many samples use it, or auto.";
  }
  out += '\n' + wrap(conclusion);
  return out;
}

}  // namespace spdfit::experiment::demo
