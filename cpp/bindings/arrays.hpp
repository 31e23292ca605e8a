// numpy <-> Eigen at the binding boundary: every argument is checked here (shape, finiteness) and
// a bad one raises ValueError naming it, before any numerics run.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Dense>

#include <string>
#include <vector>

namespace robokin::bind {

namespace py = pybind11;
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

[[noreturn]] inline void fail(const std::string& message) { throw py::value_error(message); }

inline std::string shape_of(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

// A C-contiguous float64 view of obj (no copy when it already is one).
inline Array as_array(py::handle obj, const char* name) {
  if (obj.is_none()) fail(std::string(name) + ": expected an array of numbers, got None");
  if (py::isinstance<py::str>(obj) || py::isinstance<py::bytes>(obj))
    fail(std::string(name) + ": expected an array of numbers, got a string");
  // Complex numbers would lose their imaginary part silently under a float64 cast.
  if (py::isinstance<py::array>(obj) && py::reinterpret_borrow<py::array>(obj).dtype().kind() == 'c')
    fail(std::string(name) + ": expected real numbers, got a complex array");
  Array a = Array::ensure(obj);
  if (!a) {
    PyErr_Clear();
    fail(std::string(name) + ": expected an array of numbers");
  }
  return a;
}

inline void require_finite(const double* data, py::ssize_t size, const char* name) {
  for (py::ssize_t i = 0; i < size; ++i)
    if (!std::isfinite(data[i])) fail(std::string(name) + ": contains NaN or inf");
}

// A finite vector of length n (any length when n < 0).
inline Eigen::VectorXd as_vector(py::handle obj, const char* name, long n = -1, bool finite = true) {
  Array a = as_array(obj, name);
  if (a.ndim() != 1 || (n >= 0 && a.shape(0) != n))
    fail(std::string(name) + ": expected shape (" + (n >= 0 ? std::to_string(n) : "n") + ",), got " +
         shape_of(a));
  if (finite) require_finite(a.data(), a.size(), name);
  return Eigen::Map<const Eigen::VectorXd>(a.data(), a.shape(0));
}

// A finite 4x4 homogeneous rigid transform (orthonormal rotation, last row 0 0 0 1).
inline Eigen::Matrix4d as_transform(py::handle obj, const char* name) {
  Array a = as_array(obj, name);
  if (a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4)
    fail(std::string(name) + ": expected a (4, 4) homogeneous matrix, got shape " + shape_of(a));
  require_finite(a.data(), a.size(), name);
  const Eigen::Matrix4d m = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(a.data());
  const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
  if (!m.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1), 1e-12) ||
      (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-9 || R.determinant() < 0)
    fail(std::string(name) + ": not a rigid transform (rotation must be orthonormal, last row 0 0 0 1)");
  return m;
}

// A new (d0, ..., dk) float64 array.
inline py::array_t<double> new_array(std::vector<py::ssize_t> shape) { return py::array_t<double>(shape); }

// Copies a column-major Eigen matrix into a new row-major numpy array.
template <class M>
py::array_t<double> to_numpy(const M& m) {
  py::array_t<double> out({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      out.mutable_data(), m.rows(), m.cols()) = m;
  return out;
}

inline py::array_t<double> to_numpy(const Eigen::VectorXd& v) {
  py::array_t<double> out(static_cast<py::ssize_t>(v.size()));
  Eigen::Map<Eigen::VectorXd>(out.mutable_data(), v.size()) = v;
  return out;
}

}  // namespace robokin::bind
