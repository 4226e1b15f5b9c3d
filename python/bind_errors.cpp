#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "ssrcl/error.hpp"

namespace ssrcl::python {
namespace {

// One Python class per ErrorCode, under ssrcl.Error, each also deriving from the builtin a Python
// caller would catch for it (a bad parameter is a ValueError, an unreadable file an OSError).
struct ErrorClass {
  ErrorCode code;
  const char* codeName;  // the enumerator's name, the exception's .code
  const char* name;
  PyObject* builtin;  // nullptr: only ssrcl.Error
};

// ssrcl.Error and the class made for each code; the module's attributes own them (raw pointers,
// so nothing is released after the interpreter has gone).
PyObject* baseClass = nullptr;
std::vector<std::pair<ErrorClass, PyObject*>>& classes() {
  static std::vector<std::pair<ErrorClass, PyObject*>> all;
  return all;
}

void raise(PyObject* cls, const Error& e, const char* codeName) {
  py::object error = py::handle(cls)(e.what());
  error.attr("code") = codeName;
  error.attr("buildLog") = e.buildLog();
  PyErr_SetObject(cls, error.ptr());
}

}  // namespace

void bindErrors(py::module_& m) {
  py::object base = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(
      "ssrcl.Error", "Any ssrcl failure; .code names the C++ ErrorCode, .buildLog holds the OpenCL compiler's text.",
      PyExc_RuntimeError, nullptr));
  m.attr("Error") = base;
  baseClass = base.ptr();
  const ErrorClass table[] = {
      {ErrorCode::InvalidArgument, "InvalidArgument", "InvalidArgumentError", PyExc_ValueError},
      {ErrorCode::InvalidOperation, "InvalidOperation", "InvalidOperationError", nullptr},
      {ErrorCode::Cancelled, "Cancelled", "CancelledError", nullptr},
      {ErrorCode::InvalidInput, "InvalidInput", "InvalidInputError", PyExc_ValueError},
      {ErrorCode::IoError, "IoError", "IoError", PyExc_OSError},
      {ErrorCode::NoDevice, "NoDevice", "NoDeviceError", nullptr},
      {ErrorCode::KernelBuild, "KernelBuild", "KernelBuildError", nullptr},
      {ErrorCode::OpenCL, "OpenCL", "OpenCLError", nullptr},
      {ErrorCode::OutOfMemory, "OutOfMemory", "OutOfMemoryError", PyExc_MemoryError},
  };
  for (const ErrorClass& c : table) {
    py::tuple bases = c.builtin ? py::make_tuple(base, py::handle(c.builtin)) : py::make_tuple(base);
    const std::string qualified = std::string("ssrcl.") + c.name;
    py::object cls = py::reinterpret_steal<py::object>(
        PyErr_NewExceptionWithDoc(qualified.c_str(), errorCodeName(c.code), bases.ptr(), nullptr));
    m.attr(c.name) = cls;
    classes().emplace_back(c, cls.ptr());
  }

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      for (const auto& [c, cls] : classes())
        if (c.code == e.code()) return raise(cls, e, c.codeName);
      raise(baseClass, e, errorCodeName(e.code()));  // a code newer than this table
    }
  });
}

}  // namespace ssrcl::python
