// nsbridge.lcp, nsbridge.criterion and nsbridge.end_criterion: the LCP solvers and the rotation
// criterion of eq. (1), of an equal-skew deck and of each end of any plan.
#include "lcp/frictional.hpp"
#include "lcp/siconos_format.hpp"
#include "lcp/solve.hpp"
#include "models/analytic.hpp"
#include "models/criterion.hpp"
#include "python/bindings.hpp"

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <optional>
#include <stdexcept>
#include <string>

namespace py = pybind11;

namespace nsb::python {

namespace {

// The keyword options of lcp.solve, checked by name: an unknown one is bad input.
lcp::SolveOptions solve_options(const py::kwargs& kwargs) {
  lcp::SolveOptions o;
  for (const auto& [key, value] : kwargs) {
    const auto name = key.cast<std::string>();
    if (name == "tolerance") {
      o.tolerance = value.cast<double>();
    } else if (name == "max_iterations") {
      o.max_iterations = value.cast<int>();
    } else if (name == "record_history") {
      o.record_history = value.cast<bool>();
    } else {
      throw std::invalid_argument("lcp.solve: unknown option '" + name +
                                  "'; allowed: tolerance, max_iterations, record_history");
    }
  }
  return o;
}

lcp::Solver solver_named(const std::string& name) {
  const auto s = lcp::parse_solver(name);
  if (!s) {
    throw std::invalid_argument("lcp.solve: solver: must be one of \"lemke\", \"pgs\", \"nfb\", "
                                "\"enum\" (got \"" + name + "\")");
  }
  return *s;
}

lcp::Result solve(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, const std::string& solver,
                  const py::kwargs& kwargs) {
  const lcp::Solver s = solver_named(solver);
  const lcp::SolveOptions options = solve_options(kwargs);
  lcp::Problem problem{M, q};
  problem.validate();
  py::gil_scoped_release release;
  return lcp::solve(problem, s, options);
}

// Eq. (6): the LCP (M, q) of a frictional contact problem.
py::tuple frictional_problem(const Eigen::MatrixXd& delassus, const Eigen::VectorXd& gdot_free,
                             const Eigen::VectorXd& gdot_n_minus,
                             const Eigen::VectorXd& restitution, const Eigen::VectorXd& friction) {
  lcp::FrictionalProblem fp{delassus, gdot_free, gdot_n_minus, restitution, friction};
  fp.validate();
  const lcp::Problem p = lcp::build_eq6(fp);
  return py::make_tuple(p.M, p.q);
}

py::dict criterion(double skew_deg, double width, double length, double friction) {
  const models::analytic::CriterionInput in{
      .skew_deg = skew_deg, .width = width, .length = length, .friction = friction};
  const auto c = models::analytic::checked_rotation_criterion(in);
  py::dict d;
  d["skew_deg"] = skew_deg;
  d["width"] = width;
  d["length"] = length;
  d["friction"] = friction;
  d["eta_plus"] = c.eta_plus;
  d["eta_minus"] = c.eta_minus;
  d["rotation"] = c.rotation;
  d["printed_eta_plus"] = c.printed_eta_plus;
  d["printed_eta_minus"] = c.printed_eta_minus;
  d["printed_rotation"] = c.printed_rotation;
  return d;
}

py::dict end_criterion(double width, double length, double friction, double skew_deg,
                       std::optional<double> skew_left_deg, std::optional<double> skew_right_deg,
                       double radius) {
  const models::DeckGeometry plan{.length = length, .width = width, .skew_deg = skew_deg,
                                  .skew_left_deg = skew_left_deg,
                                  .skew_right_deg = skew_right_deg, .radius = radius};
  return plan_criterion_dict(plan, friction);
}

}  // namespace

py::dict plan_criterion_dict(const models::DeckGeometry& plan, double friction) {
  const auto c = models::analytic::plan_criterion(plan, friction);
  py::dict d;
  d["plan"] = plan.curved() ? "curved" : "straight";
  d["width"] = plan.width;
  d["length"] = plan.length;
  d["radius"] = plan.radius;
  d["friction"] = friction;
  py::list ends;
  for (int i = 0; i < 2; ++i) {
    const auto& e = c.ends[static_cast<std::size_t>(i)];
    py::dict end;
    end["end"] = i == 0 ? "left" : "right";
    end["angle_deg"] = plan.end_skew_deg(i);
    end["eta_plus"] = e.eta_plus;
    end["eta_minus"] = e.eta_minus;
    end["rotation"] = e.rotation;
    ends.append(end);
  }
  d["ends"] = ends;
  d["rotation"] = c.rotation;
  return d;
}

void bind_lcp(py::module_& m) {
  auto l = m.def_submodule("lcp", "Linear complementarity problems: w = M z + q, z >= 0, w >= 0, "
                                  "z'w = 0 (docs/lcp.md)");
  py::class_<lcp::Result>(l, "LcpResult", "The outcome of lcp.solve")
      .def_property_readonly("z", [](const lcp::Result& r) { return r.z; })
      .def_property_readonly("w", [](const lcp::Result& r) { return r.w; })
      .def_property_readonly("status", [](const lcp::Result& r) { return std::string(lcp::to_string(r.status)); })
      .def_readonly("iterations", &lcp::Result::iterations)
      .def_readonly("residual", &lcp::Result::residual)
      .def_readonly("message", &lcp::Result::message)
      .def_readonly("history", &lcp::Result::history)
      .def("__repr__", [](const lcp::Result& r) {
        return "LcpResult(status='" + std::string(lcp::to_string(r.status)) +
               "', iterations=" + std::to_string(r.iterations) + ")";
      });
  l.def("solve", &solve, py::arg("M"), py::arg("q"), py::arg("solver") = "lemke",
        "Solves LCP(M, q) with 'lemke', 'pgs', 'nfb' or 'enum'; options: tolerance, "
        "max_iterations, record_history. A solver that fails returns its status; bad input "
        "raises InputError.");
  l.def("frictional_problem", &frictional_problem, py::arg("delassus"), py::arg("gdot_free"),
        py::arg("gdot_n_minus"), py::arg("restitution"), py::arg("friction"),
        "The LCP (M, q) of eq. (6) for a frictional impact or contact problem (docs/lcp.md)");
  l.def("read_dat", [](const std::string& path) {
        const lcp::Problem p = lcp::read_siconos_lcp(path);
        return py::make_tuple(p.M, p.q);
      }, py::arg("path"),
        "(M, q) of an LCP in Siconos's .dat format (the format `nsbridge lcp` reads)");
  m.def("criterion", &criterion, py::arg("skew_deg"), py::arg("width"), py::arg("length"),
        py::arg("friction"),
        "The rotation criterion eta of eq. (1), derived (docs/criterion.md): the keys of "
        "`nsbridge criterion --json`");
  m.def("end_criterion", &end_criterion, py::arg("width"), py::arg("length"),
        py::arg("friction"), py::arg("skew_deg") = 0.0, py::arg("skew_left_deg") = py::none(),
        py::arg("skew_right_deg") = py::none(), py::arg("radius") = 0.0,
        "The rotation criterion eta of each end of a plan with unequal end angles "
        "(skew_left_deg, skew_right_deg) or of a curved deck (radius; length is the "
        "centreline's arc) (docs/criterion.md): the keys of `nsbridge criterion --width W "
        "--length L --friction MU --skew-left A --skew-right B --json` (or --radius R)");
}

}  // namespace nsb::python
