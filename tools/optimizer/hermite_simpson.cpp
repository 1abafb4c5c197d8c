#include "hermite_simpson.hpp"

#include <cstdlib>
#include <string>

namespace reentry::optimal {

const char* to_string(SolveStatus s) {
  switch (s) {
    case SolveStatus::kOptimal: return "optimal";
    case SolveStatus::kAcceptable: return "acceptable";
    case SolveStatus::kInfeasible: return "infeasible";
    case SolveStatus::kIterationLimit: return "iteration_limit";
    case SolveStatus::kTimeLimit: return "time_limit";
    case SolveStatus::kFailure: return "failure";
  }
  return "unknown";
}

Mesh Mesh::uniform(int segments) {
  Mesh m;
  const int n = segments < 1 ? 1 : segments;
  m.tau.resize(static_cast<size_t>(n) + 1);
  for (int k = 0; k <= n; ++k) m.tau[static_cast<size_t>(k)] = static_cast<double>(k) / n;
  m.tau.back() = 1.0;
  return m;
}

Mesh Mesh::of_points(const std::vector<double>& point_tau) {
  Mesh m;
  for (size_t j = 0; j < point_tau.size(); j += 2) m.tau.push_back(point_tau[j]);
  return m;
}

std::vector<double> Mesh::point_tau() const {
  std::vector<double> t;
  const int n = segments();
  t.reserve(static_cast<size_t>(2 * n + 1));
  for (int k = 0; k < n; ++k) {
    t.push_back(tau[static_cast<size_t>(k)]);
    t.push_back(0.5 * (tau[static_cast<size_t>(k)] + tau[static_cast<size_t>(k) + 1]));
  }
  t.push_back(tau.back());
  return t;
}

namespace detail {

const char* ipopt_status_name(Ipopt::SolverReturn s) {
  switch (s) {
    case Ipopt::SUCCESS: return "success";
    case Ipopt::MAXITER_EXCEEDED: return "maxiter_exceeded";
    case Ipopt::CPUTIME_EXCEEDED: return "cputime_exceeded";
    case Ipopt::STOP_AT_TINY_STEP: return "stop_at_tiny_step";
    case Ipopt::STOP_AT_ACCEPTABLE_POINT: return "stop_at_acceptable_point";
    case Ipopt::LOCAL_INFEASIBILITY: return "local_infeasibility";
    case Ipopt::USER_REQUESTED_STOP: return "user_requested_stop";
    case Ipopt::FEASIBLE_POINT_FOUND: return "feasible_point_found";
    case Ipopt::DIVERGING_ITERATES: return "diverging_iterates";
    case Ipopt::RESTORATION_FAILURE: return "restoration_failure";
    case Ipopt::ERROR_IN_STEP_COMPUTATION: return "error_in_step_computation";
    case Ipopt::INVALID_NUMBER_DETECTED: return "invalid_number_detected";
    case Ipopt::TOO_FEW_DEGREES_OF_FREEDOM: return "too_few_degrees_of_freedom";
    case Ipopt::INVALID_OPTION: return "invalid_option";
    case Ipopt::OUT_OF_MEMORY: return "out_of_memory";
    case Ipopt::INTERNAL_ERROR: return "internal_error";
    case Ipopt::UNASSIGNED: return "unassigned";
  }
  return "unknown";
}

SolveStatus map_status(Ipopt::SolverReturn s) {
  switch (s) {
    case Ipopt::SUCCESS: return SolveStatus::kOptimal;
    case Ipopt::STOP_AT_ACCEPTABLE_POINT: return SolveStatus::kAcceptable;
    case Ipopt::LOCAL_INFEASIBILITY: return SolveStatus::kInfeasible;
    case Ipopt::MAXITER_EXCEEDED: return SolveStatus::kIterationLimit;
    case Ipopt::CPUTIME_EXCEEDED:
    case Ipopt::USER_REQUESTED_STOP: return SolveStatus::kTimeLimit;
    default: return SolveStatus::kFailure;
  }
}

namespace {
// One IPOPT option from its text, by the type IPOPT registered for it. false: unknown option or
// a value of the wrong kind.
bool set_option(Ipopt::IpoptApplication& app, const std::string& name, const std::string& value) {
  Ipopt::SmartPtr<const Ipopt::RegisteredOption> reg = app.RegOptions()->GetOption(name);
  if (!Ipopt::IsValid(reg)) return false;
  Ipopt::OptionsList& op = *app.Options();
  char* stop = nullptr;
  switch (reg->Type()) {
    case Ipopt::OT_Number: {
      const double v = std::strtod(value.c_str(), &stop);
      return !value.empty() && *stop == '\0' && op.SetNumericValue(name, v);
    }
    case Ipopt::OT_Integer: {
      const long v = std::strtol(value.c_str(), &stop, 10);
      return !value.empty() && *stop == '\0' && op.SetIntegerValue(name, static_cast<Ipopt::Index>(v));
    }
    default: return op.SetStringValue(name, value);
  }
}
}  // namespace

bool configure(Ipopt::IpoptApplication& app, const SolverOptions& o, bool warm_duals) {
  Ipopt::OptionsList& op = *app.Options();
  bool ok = true;
  op.SetIntegerValue("print_level", o.print_level);
  op.SetStringValue("sb", "yes");  // no banner
  op.SetIntegerValue("max_iter", o.max_iterations);
  op.SetNumericValue("tol", o.tol);
  op.SetNumericValue("constr_viol_tol", o.constr_viol_tol);
  op.SetNumericValue("acceptable_tol", o.acceptable_tol);
  op.SetIntegerValue("acceptable_iter", 10);
  op.SetStringValue("linear_solver", "mumps");
  op.SetStringValue("nlp_scaling_method", "user-scaling");
  op.SetStringValue("hessian_approximation", o.exact_hessian ? "exact" : "limited-memory");
  op.SetStringValue("mu_strategy", o.monotone_mu ? "monotone" : "adaptive");
  op.SetNumericValue("theta_max_fact", o.theta_max_fact);
  op.SetNumericValue("mu_init", o.mu_init);
  op.SetNumericValue("bound_push", o.bound_push);
  op.SetNumericValue("bound_frac", o.bound_push);
  op.SetNumericValue("constr_mult_init_max", o.constr_mult_init_max);
  if (warm_duals) {  // primal and dual start from a solve of the same NLP: stay there
    op.SetStringValue("warm_start_init_point", "yes");
    op.SetNumericValue("warm_start_bound_push", o.bound_push);
    op.SetNumericValue("warm_start_bound_frac", o.bound_push);
    op.SetNumericValue("warm_start_mult_bound_push", o.bound_push);
  }
  for (const auto& [name, value] : o.ipopt_options) ok = set_option(app, name, value) && ok;
  if (!o.derivative_test.empty()) {  // IPOPT's own derivative checker
    op.SetStringValue("derivative_test", o.derivative_test);
    op.SetNumericValue("derivative_test_perturbation", 1e-7);
    op.SetNumericValue("derivative_test_tol", 1e-3);
  }
  return ok;
}

}  // namespace detail
}  // namespace reentry::optimal
