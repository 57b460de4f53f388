// The hexapod's physical fit on the shared solver of physically consistent identification
// (physical/cone_solver.hpp): its criterion (physical_criterion.cpp) as a physical::detail::Criterion
// over one body's pseudo-inertia and the estimated strut masses (nonnegative scalars).
#include "hexapod/physical_solver.hpp"

#include "physical/cone_solver.hpp"

namespace spdfit::hexapod::detail {

namespace {

namespace shared = spdfit::physical::detail;

shared::ConeLayout layout_of(const PhysicalModel& model) {
  shared::ConeLayout layout;
  layout.bodies = 1;
  layout.nonnegative = model.parameters - kPayloadParameters;
  return layout;
}

class HexapodCriterion : public shared::Criterion {
 public:
  HexapodCriterion(const PhysicalData& data, const PhysicalModel& model) : data_(data), model_(model) {}

  bool evaluate(const Eigen::VectorXd& theta, int order, shared::Evaluation& out) const override {
    Evaluation ev;
    if (!detail::evaluate(data_, model_, ParamVector(theta), order, ev)) return false;
    out.f = ev.f;
    if (order >= 1) out.g = ev.g;
    if (order >= 2) out.H = ev.H;
    return true;
  }

 private:
  const PhysicalData& data_;
  const PhysicalModel& model_;
};

SolveResult result_of(const shared::SolveResult& r) {
  SolveResult out;
  out.theta = r.theta;
  out.f = r.f;
  out.iterations = r.iterations;
  out.converged = r.converged;
  out.message = r.message;
  return out;
}

}  // namespace

bool strictly_feasible(const PhysicalModel& model, const ParamVector& theta) {
  return shared::strictly_feasible(layout_of(model), Eigen::VectorXd(theta));
}

ParamVector pushed_inside(const PhysicalModel& model, const ParamVector& theta, double fraction) {
  return shared::pushed_inside(layout_of(model), Eigen::VectorXd(theta), fraction);
}

SolveResult solve_constrained(const PhysicalData& data, const PhysicalModel& model, const ParamVector& theta0,
                              int max_iterations) {
  return result_of(
      shared::solve_constrained(HexapodCriterion(data, model), layout_of(model), Eigen::VectorXd(theta0), max_iterations));
}

std::optional<SolveResult> solve_on_face(const PhysicalData& data, const PhysicalModel& model, const ParamVector& guess,
                                         int max_steps, int* steps_taken) {
  const std::optional<shared::SolveResult> r =
      shared::solve_on_face(HexapodCriterion(data, model), layout_of(model), Eigen::VectorXd(guess), max_steps,
                            steps_taken);
  if (!r) return std::nullopt;
  return result_of(*r);
}

SolveResult solve_unconstrained(const PhysicalData& data, const PhysicalModel& model, const ParamVector& theta0,
                                int max_iterations) {
  return result_of(shared::solve_unconstrained(HexapodCriterion(data, model), Eigen::VectorXd(theta0), max_iterations));
}

PhysicalCertificate kkt_certificate(const PhysicalData& data, const PhysicalModel& model, const ParamVector& theta) {
  const shared::ConeCertificate c =
      shared::kkt_certificate(HexapodCriterion(data, model), layout_of(model), Eigen::VectorXd(theta));
  PhysicalCertificate out;
  out.stationarity = c.stationarity;
  out.dual_min_eig = c.dual_min_eig;
  out.primal_min_eig = c.primal_min_eig / data.theta_scale;
  out.complementarity = c.complementarity;
  return out;
}

}  // namespace spdfit::hexapod::detail
