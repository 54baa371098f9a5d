// The Python module `idbench` (pybind11): the library calls the command line
// makes, on numpy arrays. Options are keyword arguments named as the command
// line's (--total-mass → total_mass); errors are raised with the command
// line's messages (ValueError: bad input or options; RuntimeError: it ran and
// failed). docs/python.md. Each part is bound in its own file (bindings.h).
#include <exception>

#include "bindings.h"
#include "idbench/workbench/commands/design_command.h"
#include "idbench/workbench/version.h"

PYBIND11_MODULE(idbench, m) {
  using namespace idbench;
  namespace py = pybind11;
  m.doc() = "idbench: excitation design and dynamic parameter identification of serial robots";
  m.attr("__version__") = Version();
  m.attr("__git_revision__") = GitRevision();
  // As the command line's exit codes: settings that admit no motion are wrong
  // input (ValueError, exit 2); a search that found nothing feasible failed
  // (RuntimeError, exit 1). Other exceptions: pybind11's mapping
  // (std::invalid_argument → ValueError, std::runtime_error → RuntimeError).
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const InfeasibleDesign& e) {
      PyErr_SetString(e.before_search() ? PyExc_ValueError : PyExc_RuntimeError, e.what());
    }
  });
  python::BindRobot(m);
  python::BindIdentify(m);
  python::BindPayload(m);
  python::BindLog(m);
  python::BindDesign(m);
  python::BindRender(m);
}
