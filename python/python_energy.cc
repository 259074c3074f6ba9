// A prototyping hook: an energy written in Python, registered as an effect
// (ipstep.register_energy, docs/python.md). Each term is a Ceres cost over a
// few nodes with the residual r = sqrt(2 e) (so e = r^2 / 2, every ipstep
// term's form: core/term.h), its Jacobian g / r from the Python gradient, and,
// with a Python Hessian H, the analytic residual curvature H / r - g g^T / r^3
// for the Newton models (core/term_hessian.h; without it, central differences
// of the Jacobian). Every evaluation takes the GIL: slow, for prototypes.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>

#include "core/term.h"
#include "energies/term_builder.h"
#include "python/bindings.h"

namespace ipstep::python {
namespace {

struct PythonEnergy {
  std::string name;
  py::object energy, gradient, hessian, terms;
};

// The first exception a Python energy raised (with the GIL).
std::unique_ptr<py::error_already_set>& PendingError() {
  static std::unique_ptr<py::error_already_set> error;
  return error;
}

// Every registered energy: their Python objects are released at the
// interpreter's exit (atexit), before the registry's static destruction,
// which runs after Python is gone.
std::vector<std::shared_ptr<PythonEnergy>>& Registered() {
  static std::vector<std::shared_ptr<PythonEnergy>> energies;
  return energies;
}

void ReleasePythonObjects() {
  for (const auto& e : Registered()) {
    e->energy = e->gradient = e->hessian = e->terms = py::object();
  }
  PendingError().reset();
}

void Keep(py::error_already_set error) {
  if (!PendingError()) PendingError() = std::make_unique<py::error_already_set>(std::move(error));
}

class PythonCost : public ceres::CostFunction {
 public:
  PythonCost(std::shared_ptr<const PythonEnergy> energy, int nodes, int dimension,
             py::object parameters)
      : energy_(std::move(energy)),
        nodes_(nodes),
        dimension_(dimension),
        parameters_(std::move(parameters)) {
    set_num_residuals(1);
    for (int i = 0; i < nodes; ++i) mutable_parameter_block_sizes()->push_back(dimension);
  }
  ~PythonCost() override {
    py::gil_scoped_acquire gil;
    parameters_ = py::object();
  }

  // x as a (nodes, dimension) array; with the GIL.
  py::array_t<double> Positions(const double* const* x) const {
    py::array_t<double> array({nodes_, dimension_});
    double* out = array.mutable_data();
    for (int b = 0; b < nodes_; ++b) {
      for (int k = 0; k < dimension_; ++k) out[b * dimension_ + k] = x[b][k];
    }
    return array;
  }

  // e, and g (n) when asked; false (an infeasible point) if e is not a finite
  // number >= 0 or the Python code raised. With the GIL.
  bool Values(const double* const* x, double* e, std::vector<double>* g,
              std::vector<double>* h) const {
    try {
      const py::array_t<double> positions = Positions(x);
      *e = energy_->energy(positions, parameters_).cast<double>();
      if (!std::isfinite(*e) || *e < 0.0) return false;
      const size_t n = static_cast<size_t>(nodes_ * dimension_);
      if (g != nullptr) {
        const auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(
            energy_->gradient(positions, parameters_));
        if (!array || static_cast<size_t>(array.size()) != n) {
          throw py::value_error("energy '" + energy_->name + "': the gradient must have " +
                                std::to_string(n) + " entries (nodes x dimension)");
        }
        g->assign(array.data(), array.data() + n);
      }
      if (h != nullptr) {
        const auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(
            energy_->hessian(positions, parameters_));
        if (!array || static_cast<size_t>(array.size()) != n * n) {
          throw py::value_error("energy '" + energy_->name + "': the Hessian must be " +
                                std::to_string(n) + " x " + std::to_string(n));
        }
        h->assign(array.data(), array.data() + n * n);
      }
      return true;
    } catch (py::error_already_set& error) {
      Keep(std::move(error));
      return false;
    } catch (const py::cast_error&) {
      Keep(py::error_already_set());
      return false;
    }
  }

  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override {
    py::gil_scoped_acquire gil;
    double e = 0.0;
    std::vector<double> g;
    if (!Values(x, &e, jacobians != nullptr ? &g : nullptr, nullptr)) return false;
    const double r = std::sqrt(2.0 * e);
    residuals[0] = r;
    if (jacobians == nullptr) return true;
    for (int b = 0; b < nodes_; ++b) {
      if (jacobians[b] == nullptr) continue;
      for (int k = 0; k < dimension_; ++k) {
        // At e = 0 (a minimum of e >= 0) the gradient is 0 too.
        jacobians[b][k] = r > 0.0 ? g[b * dimension_ + k] / r : 0.0;
      }
    }
    return true;
  }

  // sum_k c_k Hess(r_k) = c (H / r - g g^T / r^3).
  bool Curvature(const double* const* x, const double* c, double* curvature) const {
    py::gil_scoped_acquire gil;
    double e = 0.0;
    std::vector<double> g, h;
    if (!Values(x, &e, &g, &h)) return false;
    const int n = nodes_ * dimension_;
    const double r = std::sqrt(2.0 * e);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        curvature[i * n + j] =
            r > 0.0 ? c[0] * (h[i * n + j] / r - g[i] * g[j] / (r * r * r)) : 0.0;
      }
    }
    return true;
  }

 private:
  std::shared_ptr<const PythonEnergy> energy_;
  int nodes_, dimension_;
  py::object parameters_;
};

std::string Build(const std::shared_ptr<const PythonEnergy>& energy, TermBuilder& builder,
                  const nlohmann::json& parameters) {
  py::gil_scoped_acquire gil;
  const py::object params = parameters.is_null()
                                ? py::object(py::none())
                                : py::module_::import("json").attr("loads")(parameters.dump());
  std::vector<int> free;
  for (int i = 0; i < builder.state().num_nodes(); ++i) {
    if (builder.state().is_free(i)) free.push_back(i);
  }
  std::vector<std::vector<int>> terms;
  if (energy->terms.is_none()) {
    for (int i : free) terms.push_back({i});
  } else {
    try {
      terms = energy->terms(params, free).cast<std::vector<std::vector<int>>>();
    } catch (py::error_already_set& error) {
      throw InputError(builder.scene().source, energy->name,
                       std::string("the terms callback raised: ") + error.what());
    } catch (const py::cast_error&) {
      throw InputError(builder.scene().source, energy->name,
                       "the terms callback must return a list of lists of node indices");
    }
  }
  const int dimension = builder.dimension();
  const int max_nodes = kMaxTermCoordinates / dimension;
  for (const std::vector<int>& nodes : terms) {
    if (nodes.empty() || static_cast<int>(nodes.size()) > max_nodes) {
      throw InputError(builder.scene().source, energy->name,
                       "a term has 1 to " + std::to_string(max_nodes) + " nodes, got " +
                           std::to_string(nodes.size()));
    }
    for (int node : nodes) {
      if (node < 0 || node >= builder.state().num_nodes()) {
        throw InputError(builder.scene().source, energy->name,
                         "node " + std::to_string(node) + " is not a node of the scene");
      }
    }
    Term term;
    term.kind = TermKind::kPotential;
    term.nodes = nodes;
    auto cost =
        std::make_unique<PythonCost>(energy, static_cast<int>(nodes.size()), dimension, params);
    if (!energy->hessian.is_none()) {
      const PythonCost* raw = cost.get();
      term.curvature = [raw](const double* const* x, const double* c, double* curvature) {
        return raw->Curvature(x, c, curvature);
      };
    }
    term.cost = std::move(cost);
    builder.Add(std::move(term));
  }
  return energy->name + ": " + std::to_string(terms.size()) + " terms (Python)";
}

}  // namespace

void RaisePythonEnergyError() {
  if (!PendingError()) return;
  std::unique_ptr<py::error_already_set> error = std::move(PendingError());
  throw *error;
}

void BindPythonEnergy(py::module_& m) {
  py::module_::import("atexit").attr("register")(py::cpp_function(&ReleasePythonObjects));
  m.def(
      "register_energy",
      [](const std::string& name, py::object energy, py::object gradient, py::object hessian,
         py::object terms, const std::string& description) {
        auto e = std::make_shared<PythonEnergy>();
        e->name = name;
        e->energy = std::move(energy);
        e->gradient = std::move(gradient);
        e->hessian = std::move(hessian);
        e->terms = std::move(terms);
        Registered().push_back(e);
        Effects().Register(name, description.empty() ? "an energy written in Python" : description,
                           [e](TermBuilder& builder, const nlohmann::json& parameters) {
                             return Build(e, builder, parameters);
                           });
      },
      py::arg("name"), py::arg("energy"), py::arg("gradient"), py::arg("hessian") = py::none(),
      py::arg("terms") = py::none(), py::arg("description") = "",
      "register_energy(name, energy, gradient, hessian=None, terms=None): an effect `name` "
      "that scenes list in \"effects\" (parameters: the scene's top-level object `name`, passed "
      "as `params`). Each term: energy(x, params) -> float >= 0, gradient(x, params) -> "
      "(nodes*dim) array, hessian(x, params) -> (nodes*dim, nodes*dim), x the term's positions "
      "(nodes, dim). terms(params, free_nodes) -> list of node lists (default: one term per "
      "free node). Slow (the GIL per evaluation): for prototypes (docs/python.md).");
}

}  // namespace ipstep::python
