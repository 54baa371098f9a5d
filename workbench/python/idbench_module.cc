// The Python module `idbench` (pybind11): the library calls the command line
// makes, on numpy arrays. Options are keyword arguments named as the options'
// fields, or as the command line's flags (--total-mass → total_mass); errors
// are raised with the library's messages, their fields spelled as keywords
// (ValueError: bad input or options; RuntimeError: it ran and failed).
// docs/python.md. Each part is bound in its own file (bindings.h).
#include <exception>
#include <stdexcept>

#include "bindings.h"
#include "idbench/workbench/commands/design_command.h"
#include "idbench/workbench/commands/field_spelling.h"
#include "idbench/workbench/version.h"

namespace {

// The option fields whose keyword argument has another name.
constexpr idbench::FieldSpelling kKeywordSpellings[] = {
    {"locked_joints", "lock"},
    {"tip_link", "tip"},
    {"csv_rate_hz", "rate"},
    {"max_seconds", "max_time"},
    {"ramp_seconds", "ramp"},
    {"paper_accel_deg_s2", "paper_accel"},
    {"max_gap_s", "max_gap"},
    {"tau_noise_bandwidth_hz", "tau_noise_bandwidth"},
    {"filter.cutoff_hz", "filter_cutoff"},
    {"filter.order", "filter_order"},
    {"filter.decimation", "decimate"},
    {"plausibility.com_in_geometry = false", "com_bound='none'"},
    {"plausibility.mass_factor_min, plausibility.mass_factor_max", "mass_range"},
    {"plausibility.total_mass_tolerance", "total_mass_tolerance"},
    {"plausibility.total_mass", "total_mass"},
    {"plausibility.prior_weight", "prior_weight"},
    {"plausibility.cost_tolerance", "cost_tolerance"},
    {"write_unverified", "write_unverified=True"}};

}  // namespace

namespace idbench::python {

std::string KeywordSpelling(const std::string& message) { return SpellFields(message, kKeywordSpellings); }

}  // namespace idbench::python

PYBIND11_MODULE(idbench, m) {
  using namespace idbench;
  namespace py = pybind11;
  m.doc() = "idbench: excitation design and dynamic parameter identification of serial robots";
  m.attr("__version__") = Version();
  m.attr("__git_revision__") = GitRevision();
  // As the command line's exit codes: std::invalid_argument → ValueError
  // (exit 2), std::runtime_error → RuntimeError (exit 1), their fields
  // spelled as keywords.
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const py::builtin_exception&) {
      throw;  // pybind11's own (TypeError, ...): its translator
    } catch (const py::error_already_set&) {
      throw;
    } catch (const std::invalid_argument& e) {
      PyErr_SetString(PyExc_ValueError, python::KeywordSpelling(e.what()).c_str());
    } catch (const std::runtime_error& e) {
      PyErr_SetString(PyExc_RuntimeError, python::KeywordSpelling(e.what()).c_str());
    }
  });
  python::BindRobot(m);
  python::BindIdentify(m);
  python::BindPayload(m);
  python::BindLog(m);
  python::BindDesign(m);
  python::BindRender(m);
}
