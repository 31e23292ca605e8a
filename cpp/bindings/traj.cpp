// robokin.traj's core: planning and evaluation of joint and Cartesian trajectories. The Python
// module (python/robokin/traj.py) wraps the results in dataclasses.
#include "arrays.hpp"
#include "bindings.hpp"
#include "progress.hpp"

#include "robokin/parallel.hpp"
#include "robokin/traj.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace robokin::bind {
namespace {

// At most this many values (samples x joints) per array: 160 MB per array of doubles.
constexpr long kMaxValues = 20'000'000;

Vector positive_vector(py::handle obj, const char* name, long n) {
  const Vector v = as_vector(obj, name, n);
  for (long i = 0; i < n; ++i)
    if (!(v(i) > 0)) fail(std::string(name) + ": every limit must be a positive finite number");
  return v;
}

Vector optional_vector(py::handle obj, const char* name, long n) {
  return obj.is_none() ? Vector(Vector::Zero(n)) : as_vector(obj, name, n);
}

// (q0, q1) of one size n >= 1.
long joint_pair(ArrayLike q0_obj, ArrayLike q1_obj, Vector& q0, Vector& q1) {
  q0 = as_vector(q0_obj, "q0");
  if (q0.size() == 0) fail("q0: expected at least one joint, got shape (0,)");
  q1 = as_vector(q1_obj, "q1", q0.size());
  return q0.size();
}

py::array vector_array(const std::vector<double>& values) {
  return array_of(values.data(), {static_cast<py::ssize_t>(values.size())});
}


// Where a joint law's samples go: the caller's arrays (robokin.traj.quintic's out=; output_array's
// checks, and apart from the caller's times and from each other) or, for None, new ones.
struct SampleOut {
  py::handle q = py::none(), qd = py::none(), qdd = py::none();
  const double* t = nullptr;  // the caller's times as read (a copy unless a C-contiguous float64 array)
  py::ssize_t t_size = 0;
};

// Evaluates a joint law at the times t, in parallel without the GIL; (t, q, qd, qdd).
template <class Law>
py::tuple sample(const Law& law, py::array t_arr, const char* names, const SampleOut& into = {}) {
  const long count = static_cast<long>(t_arr.size()), n = law.dof();
  if (count * n > kMaxValues) fail(std::string(names) + ": more than " + std::to_string(kMaxValues) + " values to sample");
  const py::ssize_t shape[2] = {count, n};
  const py::handle given[3] = {into.q, into.qd, into.qdd};
  const char* out_names[3] = {"out.q", "out.qd", "out.qdd"};
  py::array arrays[3];
  for (int k = 0; k < 3; ++k) {
    arrays[k] = output_array(given[k], 2, shape, into.t, into.t_size, "t", out_names[k]);
    for (int j = 0; j < k; ++j)
      require_apart(arrays[k], float64_data(arrays[j]), count * n, out_names[k], out_names[j]);
  }
  const double* t = float64_data(t_arr);
  const JointSamples out{float64_data(arrays[0]), float64_data(arrays[1]), float64_data(arrays[2])};
  released("traj", [&](Progress* progress) {
    parallel_for(count, 8192, [&](long begin, long end) { law.evaluate(t, begin, end, out); }, progress);
  });
  for (const py::array& a : arrays)
    if (!all_finite(float64_data(a), count * n))
      fail(std::string(names) + ": the trajectory is not finite (values or times too large)");
  return py::make_tuple(t_arr, arrays[0], arrays[1], arrays[2]);
}

// Sample times: 1-D, at least 2, finite, strictly increasing, a finite span (a copy: the
// trajectory's own times).
py::array checked_times(const Array& t) {
  if (t.ndim() != 1 || t.shape(0) < 2) fail("t: expected a 1-D array of at least 2 times, got shape " + shape_of(t));
  require_finite(t.data(), t.size(), "t");
  for (py::ssize_t k = 1; k < t.size(); ++k)
    if (!(t.data()[k] > t.data()[k - 1])) fail("t: times must be strictly increasing");
  if (!std::isfinite(t.data()[t.size() - 1] - t.data()[0])) fail("t: the time span is not finite");
  return array_of(t.data(), {t.size()});
}

py::tuple quintic_at(const Vector& q0, const Vector& q1, const Vector& qd0, const Vector& qd1, py::array t,
                     const char* names, const SampleOut& into = {}) {
  const double* tp = float64_data(t);
  const Quintic law(q0, q1, qd0, qd1, tp[0], tp[t.size() - 1]);
  return sample(law, t, names, into);
}

py::tuple quintic(ArrayLike q0_obj, ArrayLike q1_obj, ArrayLike t_obj, ArrayLike qd0_obj, ArrayLike qd1_obj,
                  OutArray q_out, OutArray qd_out, OutArray qdd_out) {
  Vector q0, q1;
  const long n = joint_pair(q0_obj, q1_obj, q0, q1);
  const Vector qd0 = optional_vector(qd0_obj, "qd0", n), qd1 = optional_vector(qd1_obj, "qd1", n);
  const Array t = as_array(t_obj, "t");
  const SampleOut into{q_out, qd_out, qdd_out, t.data(), t.size()};
  return quintic_at(q0, q1, qd0, qd1, checked_times(t), "q0, q1, qd0, qd1, t", into);
}

py::tuple trapezoidal(ArrayLike q0_obj, ArrayLike q1_obj, ArrayLike vmax_obj, ArrayLike amax_obj, double dt) {
  Vector q0, q1;
  const long n = joint_pair(q0_obj, q1_obj, q0, q1);
  const Vector vmax = positive_vector(vmax_obj, "vmax", n), amax = positive_vector(amax_obj, "amax", n);
  const Trapezoid law(q0, q1, vmax, amax);
  return sample(law, vector_array(sample_times(law.duration(), dt, kMaxValues / n)), "q0, q1, vmax, amax, dt");
}

py::tuple via_points(ArrayLike points_obj, ArrayLike vmax_obj, ArrayLike amax_obj, double dt) {
  Array p = as_array(points_obj, "points");
  if (p.ndim() != 2 || p.shape(0) < 1 || p.shape(1) < 1)
    fail("points: expected a (M, n) array, M >= 1 via points of n >= 1 joints, got shape " + shape_of(p));
  require_finite(p.data(), p.size(), "points");
  const long n = p.shape(1);
  const Eigen::MatrixXd points =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(p.data(), p.shape(0), n);
  const Vector vmax = positive_vector(vmax_obj, "vmax", n), amax = positive_vector(amax_obj, "amax", n);
  const ViaPath law(points, vmax, amax);
  py::tuple r = sample(law, vector_array(sample_times(law.duration(), dt, kMaxValues / n)), "points, vmax, amax, dt");
  return py::make_tuple(r[0], r[1], r[2], r[3], to_numpy(law.via_times()));
}

py::tuple cartesian(ArrayLike T0_obj, ArrayLike T1_obj, const std::string& law_name, ArrayLike t_obj,
                    ArrayLike vmax_obj, ArrayLike amax_obj, double dt) {
  const Rigid T0 = Rigid::from_matrix(as_transform(T0_obj, "T0")), T1 = Rigid::from_matrix(as_transform(T1_obj, "T1"));
  const CartesianLine line(T0, T1);
  Vector zero = Vector::Zero(2), end(2);
  end << line.length(), line.angle();
  py::tuple law;
  if (law_name == "quintic") {
    if (t_obj.is_none()) fail("t: the quintic law needs the sample times t");
    if (!vmax_obj.is_none() || !amax_obj.is_none())
      fail("vmax, amax: limits are for the trapezoidal law (law='trapezoidal'); the quintic law takes t");
    law = quintic_at(zero, end, zero, zero, checked_times(as_array(t_obj, "t")), "T0, T1, t");
  } else if (law_name == "trapezoidal") {
    if (!t_obj.is_none()) fail("t: the trapezoidal law samples every dt from 0; give t for the quintic law only");
    if (vmax_obj.is_none() || amax_obj.is_none())
      fail("vmax, amax: the trapezoidal law needs vmax = (linear, angular) and amax = (linear, angular)");
    const Vector vmax = positive_vector(vmax_obj, "vmax", 2), amax = positive_vector(amax_obj, "amax", 2);
    const Trapezoid trap(zero, end, vmax, amax);
    law = sample(trap, vector_array(sample_times(trap.duration(), dt, kMaxValues / 2)), "T0, T1, vmax, amax, dt");
  } else {
    fail("law: expected 'quintic' or 'trapezoidal', got '" + law_name + "'");
  }
  py::array t = law[0].cast<py::array>(), x = law[1].cast<py::array>(), xd = law[2].cast<py::array>(),
            xdd = law[3].cast<py::array>();
  const long count = static_cast<long>(t.size());
  const py::ssize_t pshape[3] = {count, 4, 4};
  py::array poses = new_array(3, pshape), vel = new_array({count, 6}), acc = new_array({count, 6});
  const double *xp = float64_data(x), *xdp = float64_data(xd), *xddp = float64_data(xdd);
  double *pp = float64_data(poses), *vp = float64_data(vel), *ap = float64_data(acc);
  released([&] { parallel_for(count, 4096, [&](long b, long e) { line.evaluate(xp, xdp, xddp, b, e, pp, vp, ap); }); });
  for (const py::array* a : {&poses, &vel, &acc})
    if (!all_finite(float64_data(*a), a->size())) fail("T0, T1: the trajectory is not finite (poses too far apart)");
  return py::make_tuple(t, poses, vel, acc);
}

}  // namespace

void bind_traj(py::module_& m) {
  m.def("traj_quintic", &quintic, py::arg("q0"), py::arg("q1"), py::arg("t"), py::arg("qd0") = py::none(),
        py::arg("qd1") = py::none(), py::kw_only(), py::arg("q_out") = py::none(), py::arg("qd_out") = py::none(),
        py::arg("qdd_out") = py::none(),
        "Quintic joint trajectory sampled at t: (t, q, qd, qdd), q, qd and qdd written into q_out, qd_out and "
        "qdd_out when given (out.q, out.qd, out.qdd in messages). Use robokin.traj.quintic.");
  m.def("traj_trapezoidal", &trapezoidal, py::arg("q0"), py::arg("q1"), py::arg("vmax"), py::arg("amax"),
        py::arg("dt"), "Synchronised trapezoidal joint trajectory: (t, q, qd, qdd). Use robokin.traj.trapezoidal.");
  m.def("traj_via_points", &via_points, py::arg("points"), py::arg("vmax"), py::arg("amax"), py::arg("dt"),
        "Linear segments with parabolic blends: (t, q, qd, qdd, via_times). Use robokin.traj.via_points.");
  m.def("traj_cartesian", &cartesian, py::arg("T0"), py::arg("T1"), py::arg("law"), py::arg("t"), py::arg("vmax"),
        py::arg("amax"), py::arg("dt"), "Cartesian straight line: (t, poses, velocity, acceleration). Use robokin.traj.cartesian.");
}

}  // namespace robokin::bind
