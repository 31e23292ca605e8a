// numpy <-> Eigen at the binding boundary: every argument is checked here (shape, finiteness) and
// a bad one raises ValueError naming it, before any numerics run.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "internals.hpp"

#include "robokin/chain.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

namespace robokin::bind {

namespace py = pybind11;

// The texts that signatures and stubs show for the Typed<Text> parameters (internals.hpp).
inline constexpr char kLimitsLikeText[] = "tuple[numpy.typing.ArrayLike, numpy.typing.ArrayLike] | None";
using LimitsLike = Typed<kLimitsLikeText>;  // limits_arg
inline constexpr char kChainLimitsLikeText[] =
    "typing.Literal['default'] | tuple[numpy.typing.ArrayLike, numpy.typing.ArrayLike] | None";
using ChainLimitsLike = Typed<kChainLimitsLikeText>;  // limits_or_default
inline constexpr char kModeLikeText[] = "tuple[int, int, int]";
using ModeLike = Typed<kModeLikeText>;  // the 3-RRR's working mode
inline constexpr char kSeedLikeText[] = "int | None";
using SeedLike = Typed<kSeedLikeText>;
inline constexpr char kTaskNameText[] = "typing.Literal['pose', 'position', 'xy', 'xyphi'] | None";
using TaskName = Typed<kTaskNameText>;  // task_of: a task's name, or None for the chain's natural task
inline constexpr char kOutArrayText[] = "numpy.typing.NDArray[numpy.float64] | None";
using OutArray = Typed<kOutArrayText>;  // output_array: the caller's array to write into, or None for a new one
inline constexpr char kFkPartText[] = "typing.Literal['frame', 'position']";
using FkPart = Typed<kFkPartText>;
inline constexpr char kMeasureNameText[] = "typing.Literal['yoshikawa', 'condition', 'min_singular']";
using MeasureName = Typed<kMeasureNameText>;
inline constexpr char kNullspaceLikeText[] = "typing.Literal['joint_limits'] | numpy.typing.ArrayLike | None";
using NullspaceLike = Typed<kNullspaceLikeText>;
inline constexpr char kLockedLikeText[] = "dict[int, float] | None";
using LockedLike = Typed<kLockedLikeText>;  // a closed form's held joint: {index: value}
inline constexpr char kOptionalArrayLikeText[] = "numpy.typing.ArrayLike | None";
using OptionalArrayLike = Typed<kOptionalArrayLikeText>;

}  // namespace robokin::bind

namespace robokin::bind {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The bindings' two errors, as robokin's Python checks raise them: a value out of range or of the
// wrong shape is a ValueError, a value of the wrong kind (None, a string, complex numbers, objects
// numpy cannot read as numbers where numbers are expected) a TypeError; both name the argument.
[[noreturn]] inline void fail(const std::string& message) { throw py::value_error(message); }
[[noreturn]] inline void fail_kind(const std::string& message) { throw py::type_error(message); }

inline std::string shape_of(py::ssize_t ndim, const py::ssize_t* shape) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < ndim; ++i) s += (i ? ", " : "") + std::to_string(shape[i]);
  return s + (ndim == 1 ? ",)" : ")");
}

inline std::string shape_of(const py::array& a) { return shape_of(a.ndim(), a.shape()); }

// obj as a C-contiguous, aligned array of T (no copy when it already is one); an empty handle with
// the Python error cleared when obj converts to none. ensure() keeps a buffer at any address, and
// one unpickled from a byte stream (a Dask worker's, say) may sit at an odd one: the core reads
// whole numbers, so it gets an aligned copy.
template <class T>
py::array_t<T, py::array::c_style | py::array::forcecast> aligned_array(py::handle obj) {
  using A = py::array_t<T, py::array::c_style | py::array::forcecast>;
  A a = A::ensure(obj);
  if (!a) {
    PyErr_Clear();
    return a;
  }
  if (!has_flags(a, kAligned)) {
    A copy(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim()));
    if (a.size()) std::memcpy(copy.mutable_data(), a.data(), static_cast<std::size_t>(a.size()) * sizeof(T));
    return copy;
  }
  return a;
}

// A C-contiguous, aligned float64 view of obj (no copy when it already is one).
inline Array as_array(py::handle obj, const char* name) {
  if (obj.is_none()) fail_kind(std::string(name) + ": expected an array of numbers, got None");
  if (py::isinstance<py::str>(obj) || py::isinstance<py::bytes>(obj))
    fail_kind(std::string(name) + ": expected an array of numbers, got a string");
  // Complex numbers would lose their imaginary part silently under a float64 cast, a list of
  // complex scalars as well as a complex array: what is not an array yet is made one of its own
  // dtype first (a null handle when numpy cannot: the cast below then says so).
  const py::object own = py::isinstance<py::array>(obj) ? py::reinterpret_borrow<py::object>(obj)
                                                         : py::object(py::array::ensure(obj));
  if (own && py::reinterpret_borrow<py::array>(own).dtype().kind() == 'c')
    fail_kind(std::string(name) + ": expected real numbers, got a complex array");
  Array a = aligned_array<double>(own ? own : py::reinterpret_borrow<py::object>(obj));
  if (!a) fail_kind(std::string(name) + ": expected an array of numbers");
  return a;
}

inline Float64View view_of(const Array& a) {
  Float64View v;
  v.data = a.data();
  v.ndim = static_cast<int>(a.ndim());
  v.shape = a.shape();
  v.size = a.size();
  return v;
}

// Refuses an output array `a` (named out_name) that shares a byte with the input [in, in + n) (named
// in_name): the result is written while the input may still be read.
inline void require_apart(const py::array& a, const double* in, py::ssize_t n, const char* out_name,
                          const char* in_name) {
  const char* o = static_cast<const char*>(a.data());
  const char* i = reinterpret_cast<const char*>(in);
  if (o < i + n * static_cast<py::ssize_t>(sizeof(double)) && i < o + a.nbytes())
    fail(std::string(out_name) + ": shares memory with " + in_name);
}

// The array a batch call writes its result into: a new one when `out` is None, else the caller's
// (numpy's idiom: the caller reuses memory across calls), which must be a writable, aligned,
// C-contiguous float64 ndarray of exactly that shape sharing no byte with the input [in, in + n).
// A value of the wrong kind is a TypeError, a wrong shape or layout a ValueError, naming the output
// (out_name) and, when memory is shared, the input (in_name).
inline py::array output_array(py::handle out, int ndim, const py::ssize_t* shape, const double* in, py::ssize_t n,
                              const char* in_name = "q", const char* out_name = "out") {
  if (out.is_none()) return new_array(ndim, shape);
  if (!py::isinstance<py::array>(out))
    throw py::type_error(std::string(out_name) + ": expected a numpy array or None, got " +
                         py::str(py::type::handle_of(out).attr("__name__")).cast<std::string>());
  const py::array a = py::reinterpret_borrow<py::array>(out);
  if (!a.dtype().equal(py::dtype::of<double>()))
    throw py::type_error(std::string(out_name) + ": expected a float64 array, got " +
                         py::str(a.dtype()).cast<std::string>());
  if (a.ndim() != ndim || !std::equal(shape, shape + ndim, a.shape()))
    fail(std::string(out_name) + ": expected shape " + shape_of(ndim, shape) + ", got " + shape_of(a));
  if (!has_flags(a, kCContiguous | kAligned | kWriteable))
    fail(std::string(out_name) + ": expected a writable, aligned, C-contiguous array (np.empty gives one)");
  require_apart(a, in, n, out_name, in_name);
  return a;
}

// True when no value is NaN or inf: their exponent bits are all ones. Integer operations only, with
// no early exit, so that the loop vectorises (the check stays a small part of a batch call).
inline bool all_finite(const double* data, py::ssize_t size) {
  std::uint64_t bad = 0;
  for (py::ssize_t i = 0; i < size; ++i) {
    std::uint64_t bits;
    std::memcpy(&bits, data + i, sizeof bits);
    const std::uint64_t exponent = (bits >> 32) & 0x7ff00000u;
    bad |= (exponent + 0x00100000u) >> 31;  // 1 only when the exponent is 0x7ff
  }
  return bad == 0;
}

inline void require_finite(const double* data, py::ssize_t size, const char* name) {
  if (!all_finite(data, size)) fail(std::string(name) + ": contains NaN or inf");
}

// A finite vector of length n (any length when n < 0).
inline Eigen::VectorXd as_vector(py::handle obj, const char* name, long n = -1, bool finite = true) {
  Float64View v;  // a float64 ndarray of the right shape is read in place
  if (float64_view(obj, v) && v.ndim == 1 && (n < 0 || v.shape[0] == n)) {
    if (finite) require_finite(v.data, v.size, name);
    return Eigen::Map<const Eigen::VectorXd>(v.data, v.shape[0]);
  }
  Array a = as_array(obj, name);
  if (a.ndim() != 1 || (n >= 0 && a.shape(0) != n))
    fail(std::string(name) + ": expected shape (" + (n >= 0 ? std::to_string(n) : "n") + ",), got " +
         shape_of(a));
  if (finite) require_finite(a.data(), a.size(), name);
  return Eigen::Map<const Eigen::VectorXd>(a.data(), a.shape(0));
}

// One value of shape (width,) or a batch (N, width), finite (unless `finite` is false: a caller that
// checks the values itself). Returns N, or -1 for a single value.
inline long one_or_batch(const Float64View& v, const char* name, long width, bool finite = true) {
  if (!((v.ndim == 1 && v.shape[0] == width) || (v.ndim == 2 && v.shape[1] == width)))
    fail(std::string(name) + ": expected shape (" + std::to_string(width) + ",) or (N, " + std::to_string(width) +
         "), got " + shape_of(v.ndim, v.shape));
  if (finite) require_finite(v.data, v.size, name);
  return v.ndim == 1 ? -1 : static_cast<long>(v.shape[0]);
}

// A finite batch of shape (count, inner...), e.g. "points: expected shape (K, 2), got (2,)".
inline Array rows_arg(py::handle obj, const char* name, std::initializer_list<py::ssize_t> inner,
                      const char* count = "K") {
  Array a = as_array(obj, name);
  const bool fits = a.ndim() == static_cast<py::ssize_t>(inner.size()) + 1 &&
                    std::equal(inner.begin(), inner.end(), a.shape() + 1);
  if (!fits) {
    std::string want = count;
    for (py::ssize_t d : inner) want += ", " + std::to_string(d);
    fail(std::string(name) + ": expected shape (" + want + "), got " + shape_of(a));
  }
  require_finite(a.data(), a.size(), name);
  return a;
}

// Whether the row-major 4x4 at m is a homogeneous rigid transform: an orthonormal rotation of
// determinant +1 (within 1e-9), last row 0 0 0 1 (within 1e-12).
inline bool is_rigid(const double* data) {
  const Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>> m(data);
  const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
  return !(!m.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1), 1e-12) ||
           (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-9 || R.determinant() < 0);
}

// The row-major 4x4 at m (finite), which must be a rigid transform: ValueError naming `name`, and
// the frame's index k in a batch (k >= 0), if not. Every frame argument is checked here.
inline Eigen::Matrix4d rigid_at(const double* m, const char* name, long k = -1) {
  if (!is_rigid(m))
    fail(std::string(name) + (k >= 0 ? ": frame " + std::to_string(k) + " is" : ":") +
         " not a rigid transform (rotation must be orthonormal, last row 0 0 0 1)");
  return Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(m);
}

// Writes T as a row-major 4x4 homogeneous matrix at m.
inline void write_frame(const Rigid& T, double* m) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m[4 * r + c] = T.R(r, c);
    m[4 * r + 3] = T.p(r);
  }
  m[12] = m[13] = m[14] = 0.0;
  m[15] = 1.0;
}

// A finite 4x4 homogeneous rigid transform (orthonormal rotation, last row 0 0 0 1).
inline Eigen::Matrix4d as_transform(py::handle obj, const char* name) {
  // A (4, 4) float64 ndarray is read in place (Float64View); anything else through as_array.
  Float64View v;
  std::optional<Array> a;  // holds the converted array while v points into it
  if (!float64_view(obj, v) || v.ndim != 2 || v.shape[0] != 4 || v.shape[1] != 4) {
    a = as_array(obj, name);
    if (a->ndim() != 2 || a->shape(0) != 4 || a->shape(1) != 4)
      fail(std::string(name) + ": expected a (4, 4) homogeneous matrix, got shape " + shape_of(*a));
    v = view_of(*a);
  }
  require_finite(v.data, 16, name);
  return rigid_at(v.data, name);
}

// The version check of a pickled state tuple (version 1, `size` entries): ValueError naming `what`.
constexpr int kStateVersion = 1;  // of every pickled state but Chain's (its own, in chain.cpp)
inline void check_state(const py::tuple& t, size_t size, const char* what) {
  if (t.size() != size || !py::isinstance<py::int_>(t[0]) || t[0].cast<int>() != kStateVersion)
    fail(std::string(what) + " state: not a state of this robokin (version 1, " + std::to_string(size) + " entries)");
}

// A new array of `shape` holding a copy of the values at data (row-major, as many as shape holds).
template <class T>
py::array_t<T> array_of(const T* data, std::initializer_list<py::ssize_t> shape) {
  py::array_t<T> out = new_array<T>(shape);
  std::copy(data, data + out.size(), out.mutable_data());
  return out;
}

// Copies a column-major Eigen matrix into a new row-major numpy array.
template <class M>
py::array_t<double> to_numpy(const M& m) {
  py::array_t<double> out = new_array({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      out.mutable_data(), m.rows(), m.cols()) = m;
  return out;
}

inline py::array_t<double> to_numpy(const Eigen::VectorXd& v) { return array_of(v.data(), {v.size()}); }

}  // namespace robokin::bind
