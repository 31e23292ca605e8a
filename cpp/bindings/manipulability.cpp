// Chain.manipulability and Chain.ellipsoid (added to the Chain class made in chain.cpp).
#include "arrays.hpp"
#include "bindings.hpp"
#include "chain_parts.hpp"
#include "chain_args.hpp"
#include "progress.hpp"

#include "robokin/manipulability.hpp"

#include <string>

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

}  // namespace

// Chain.manipulability, bound as a fast method (fast_calls.cpp).
py::object chain_manipulability(const Chain& c, ArrayLike q_obj, MeasureName measure_obj, TaskName task_obj) {
  const Measure measure = measure_of(measure_obj);
  const Task task = task_of(task_obj, c);
  const QView q(q_obj);
  const long count = check_q(c, q);
  if (count < 0) {
    const double v = robokin::manipulability(c, q.data, task, measure);
    require_finite_result(&v, 1);
    return py::float_(v);
  }
  const py::ssize_t shape[1] = {count};
  py::array out = new_array(1, shape);
  double* dst = float64_data(out);
  released("Chain.manipulability",
           [&](Progress* progress) { manipulability_batch(c, q.data, count, task, measure, dst, progress); });
  require_finite_result(dst, count);
  return std::move(out);
}

namespace {

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

}  // namespace

void def_chain_manipulability(py::class_<Chain>& cls) {
  cls.def("ellipsoid", &ellipsoid, py::arg("q"), py::arg("part") = "translation",
      "Velocity ellipsoid of the translational (part 'translation': rows v) or rotational ('rotation':\n"
      "rows w) Jacobian at q: (axes, lengths), axes (3, 3) unit columns in the base frame (a right-handed\n"
      "frame), lengths (3,) the singular values in decreasing order (0 for missing directions).");
}

}  // namespace robokin::bind
