// Chain.manipulability and Chain.ellipsoid (added to the Chain class made in chain.cpp).
#include "arrays.hpp"
#include "bindings.hpp"
#include "chain_parts.hpp"
#include "chain_args.hpp"
#include "fastcall.hpp"
#include "progress.hpp"

#include "robokin/manipulability.hpp"

#include <string>
#include <string_view>

namespace robokin::bind {
namespace {

Measure measure_of(py::handle obj) {
  if (!PyUnicode_Check(obj.ptr()))
    throw py::type_error("measure: expected a string, one of 'yoshikawa', 'condition', 'min_singular'");
  Py_ssize_t len = 0;
  const char* s = PyUnicode_AsUTF8AndSize(obj.ptr(), &len);
  if (!s) throw py::error_already_set();
  return parse_measure(std::string(s, static_cast<size_t>(len)));  // std::invalid_argument -> ValueError
}

py::object manipulability(const Chain& c, ArrayLike q_obj, MeasureName measure_obj, TaskName task_obj) {
  const Measure measure = measure_of(measure_obj);
  const Task task = task_of(task_obj, c);
  Array holder;
  const Float64View q = q_view(q_obj, holder);
  const long count = check_q(c, q);
  if (count < 0) {
    const double v = robokin::manipulability(c, q.data, task, measure);
    require_finite_result(&v, 1);
    return py::float_(v);
  }
  const py::ssize_t shape[1] = {count};
  py::array out = new_array(1, shape);
  double* dst = float64_data(out);
  PythonProgress progress("Chain.manipulability");
  {
    py::gil_scoped_release release;
    manipulability_batch(c, q.data, count, task, measure, dst, &progress);
  }
  require_finite_result(dst, count);
  return std::move(out);
}

py::tuple ellipsoid(const Chain& c, ArrayLike q_obj, const std::string& part) {
  if (part != "translation" && part != "rotation")
    fail("part: expected 'translation' or 'rotation', got '" + part + "'");
  const Vector q = as_vector(q_obj, "q", c.dof());
  Eigen::Matrix3d axes;
  Eigen::Vector3d lengths;
  robokin::ellipsoid(c, q.data(), part == "rotation", axes, lengths);
  require_finite_result(lengths.data(), 3);
  require_finite_result(axes.data(), 9);
  return py::make_tuple(to_numpy(axes), to_numpy(Eigen::VectorXd(lengths)));
}

// Chain.manipulability(q, measure='yoshikawa', task=None) through fastcall.hpp (a call costs
// about as much as one Chain.jacobian call, whose dispatch it shares).
constexpr const char* kMeasure = "yoshikawa";  // Chain.manipulability's default measure

PyObject* manipulability_fast(PyObject* self, PyObject* const* args, Py_ssize_t nargs, PyObject* kwnames) {
  return guarded([&]() -> py::object {
    static const char* const names[] = {"q", "measure", "task"};
    static PyObject* const measure = interned(kMeasure);  // kept for the process
    PyObject* a[3];
    parse_args("manipulability", args, nargs, kwnames, names, 3, 3, a);
    if (!a[0]) missing("manipulability", "q");
    return manipulability(self_of<Chain>(self), py::reinterpret_borrow<ArrayLike>(a[0]),
                          py::reinterpret_borrow<MeasureName>(a[1] ? a[1] : measure),
                          py::reinterpret_borrow<TaskName>(a[2] ? a[2] : Py_None));
  });
}

}  // namespace

void def_chain_manipulability(py::class_<Chain>& cls) {
  add_fast_method(  // without pybind11's dispatcher (fastcall.hpp)
      cls,
      fast_def("manipulability", &manipulability_fast,
               "(self: robokin._core.Chain, q: " + type_text<ArrayLike>() + ", measure: " + type_text<MeasureName>() +
                   " = '" + kMeasure + "', task: " + type_text<TaskName>() +
                   " = None) -> float | numpy.typing.NDArray[numpy.float64]",
               "Manipulability at q from the singular values of the task's Jacobian rows: 'yoshikawa' their\n"
               "product (sqrt(det(J J^T)) when rows <= dof), 'condition' sigma_min / sigma_max (the inverse\n"
               "condition number, 1 isotropic, 0 singular), 'min_singular' sigma_min. A float for q (dof,),\n"
               "an array (N,) for a batch (N, dof) (GIL released, every core). task None: the chain's\n"
               "natural_task (a planar arm's 'pose' rows would always give 0).\n"));
  cls.def("ellipsoid", &ellipsoid, py::arg("q"), py::arg("part") = "translation",
      "Velocity ellipsoid of the translational ('translation': rows v) or rotational ('rotation': rows w)\n"
      "Jacobian at q: (axes, lengths), axes (3, 3) unit columns in the base frame (a right-handed\n"
      "frame), lengths (3,) the singular values in decreasing order (0 for missing directions).");
}

}  // namespace robokin::bind
