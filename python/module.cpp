// The extension module nsbridge._nsbridge: the C++ API seen from Python. It converts and
// forwards; every computation is the C++ one (docs/python.md).
//   InputError        std::invalid_argument (bad input: a file, line, key or argument), a
//                     ValueError; numerical outcomes are statuses, never exceptions.
//   OSError           io::WriteError (an output that could not be written: a full disk).
#include "io/files.hpp"
#include "python/bindings.hpp"

#include <pybind11/pybind11.h>

#include <stdexcept>

namespace py = pybind11;

PYBIND11_MODULE(_nsbridge, m) {
  m.doc() = "nsbridge: nonsmooth seismic response of bridges with pounding (C++ engine)";
  // Every std::invalid_argument the engine throws is bad input: the caller's mistake.
  static py::exception<std::invalid_argument> input_error(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const std::invalid_argument& e) {
      input_error(e.what());  // sets the Python error (pybind11 2.10, Debian 12)
    } catch (const nsb::io::WriteError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    }
  });
  nsb::python::bind_lcp(m);
  nsb::python::bind_runs(m);
  nsb::python::bind_sweep(m);
}
