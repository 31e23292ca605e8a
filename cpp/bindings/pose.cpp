// robokin.pose's core: RPY, quaternions, axis-angle, SE(3) exp / log and the IK's pose error,
// for one value or a batch (N, ...). The Python module (python/robokin/pose.py) adds the
// ergonomics (objects with .A, positions, axis and angle as two arrays).
#include "arrays.hpp"
#include "bindings.hpp"

#include "robokin/pose.hpp"
#include "robokin/task.hpp"

#include <string>
#include <vector>

namespace robokin::bind {
namespace {

// Frames (4, 4) or (N, 4, 4); with rotations_too, also rotations (3, 3) or (N, 3, 3) (translation 0).
// Every rotation orthonormal with determinant +1 (within 1e-9), a frame's last row 0 0 0 1.
// Returns N, or -1 for a single one.
long read_frames(py::handle obj, const char* name, bool rotations_too, std::vector<Rigid>& out) {
  Array a = as_array(obj, name);
  const long nd = a.ndim();
  const long side = nd >= 2 ? a.shape(nd - 1) : 0;
  const bool ok = (nd == 2 || nd == 3) && a.shape(nd - 2) == side && (side == 4 || (rotations_too && side == 3));
  if (!ok)
    fail(std::string(name) + (rotations_too ? ": expected a (4, 4) frame or (3, 3) rotation, or a batch (N, 4, 4) / (N, 3, 3), got shape "
                                            : ": expected a (4, 4) frame or a batch (N, 4, 4), got shape ") +
         shape_of(a));
  require_finite(a.data(), a.size(), name);
  const long count = nd == 3 ? a.shape(0) : 1, stride = side * side;
  out.resize(count);
  for (long k = 0; k < count; ++k) {
    const double* m = a.data() + k * stride;
    Rigid& T = out[k];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) T.R(r, c) = m[side * r + c];
    if (side == 4) {
      T.p << m[3], m[7], m[11];
      if (!(m[12] == 0 && m[13] == 0 && m[14] == 0 && m[15] == 1) &&
          !Eigen::RowVector4d(m[12], m[13], m[14], m[15]).isApprox(Eigen::RowVector4d(0, 0, 0, 1), 1e-12))
        fail(std::string(name) + ": not a rigid transform (last row must be 0 0 0 1)");
    } else {
      T.p.setZero();
    }
    if ((T.R.transpose() * T.R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-9 || T.R.determinant() < 0)
      fail(std::string(name) + ": not a rotation (must be orthonormal with determinant +1)");
  }
  return nd == 3 ? count : -1;
}

// A new array of `count` values of shape `inner` (no leading axis when count < 0).
py::array output(long count, std::vector<py::ssize_t> inner) {
  if (count >= 0) inner.insert(inner.begin(), count);
  return new_array(static_cast<int>(inner.size()), inner.data());
}

py::array checked(py::array out, const char* name) {
  if (!all_finite(float64_data(out), out.size())) fail(std::string(name) + ": the result is not finite (values too large)");
  return out;
}

// Frames built from vectors of `width` values by make(values) -> Rigid.
template <class Make>
py::array frames_from(py::handle obj, const char* name, long width, Make make) {
  const Array a = as_array(obj, name);
  const long count = one_or_batch(view_of(a), name, width);
  py::array out = output(count, {4, 4});
  double* dst = float64_data(out);
  for (long k = 0; k < (count < 0 ? 1 : count); ++k) write_frame(make(a.data() + k * width), dst + 16 * k);
  return checked(out, name);
}

// Vectors of `width` values computed from frames by get(T, out).
template <class Get>
py::array vectors_from(py::handle obj, const char* name, bool rotations_too, long width, Get get) {
  std::vector<Rigid> frames;
  const long count = read_frames(obj, name, rotations_too, frames);
  py::array out = output(count, {width});
  double* dst = float64_data(out);
  for (size_t k = 0; k < frames.size(); ++k) get(frames[k], dst + k * width);
  return checked(out, name);
}

py::array pose_error_of(ArrayLike target_obj, ArrayLike current_obj) {
  std::vector<Rigid> target, current;
  const long nt = read_frames(target_obj, "target", false, target);
  const long nc = read_frames(current_obj, "current", false, current);
  if (nt >= 0 && nc >= 0 && nt != nc)
    fail("target, current: batches of different sizes (" + std::to_string(nt) + " and " + std::to_string(nc) + ")");
  const long count = std::max(nt, nc);
  py::array out = output(count, {6});
  double* dst = float64_data(out);
  for (long k = 0; k < (count < 0 ? 1 : count); ++k) {
    const Vector6 e = pose_error(target[nt >= 0 ? k : 0], current[nc >= 0 ? k : 0]);
    std::copy(e.data(), e.data() + 6, dst + 6 * k);
  }
  return checked(out, "target, current");
}

}  // namespace

void bind_pose(py::module_& m) {
  m.def("pose_from_rpy", [](ArrayLike rpy) {
    return frames_from(rpy, "rpy", 3, [](const double* v) { return Rigid{rpy_to_matrix(v[0], v[1], v[2]), Eigen::Vector3d::Zero()}; });
  }, py::arg("rpy"), "Frames of rotations Rz(yaw) Ry(pitch) Rx(roll). Use robokin.pose.from_rpy.");
  m.def("pose_rpy", [](ArrayLike T) {
    return vectors_from(T, "T", true, 3, [](const Rigid& T, double* o) { Eigen::Map<Eigen::Vector3d> out(o); out = matrix_to_rpy(T.R); });
  }, py::arg("T"), "(roll, pitch, yaw) of rotations. Use robokin.pose.rpy.");
  m.def("pose_from_quaternion", [](ArrayLike q) {
    return frames_from(q, "quaternion", 4, [](const double* v) {
      const Eigen::Vector4d q(v[0], v[1], v[2], v[3]);
      const double norm = q.stableNorm();
      if (!(norm > 0) || !std::isfinite(norm)) fail("quaternion: must have a non-zero finite norm");
      return Rigid{quaternion_to_matrix(q), Eigen::Vector3d::Zero()};
    });
  }, py::arg("quaternion"), "Frames of quaternions (w, x, y, z). Use robokin.pose.from_quaternion.");
  m.def("pose_quaternion", [](ArrayLike T) {
    return vectors_from(T, "T", true, 4, [](const Rigid& T, double* o) { Eigen::Map<Eigen::Vector4d> out(o); out = matrix_to_quaternion(T.R); });
  }, py::arg("T"), "Unit quaternions (w, x, y, z), w >= 0. Use robokin.pose.quaternion.");
  m.def("pose_from_rotation_vector", [](ArrayLike w) {
    return frames_from(w, "rotation_vector", 3, [](const double* v) { return Rigid{rotation_exp(Eigen::Vector3d(v[0], v[1], v[2])), Eigen::Vector3d::Zero()}; });
  }, py::arg("rotation_vector"), "Frames of rotation vectors (angle * axis). Use robokin.pose.from_axis_angle.");
  m.def("pose_rotation_vector", [](ArrayLike T) {
    return vectors_from(T, "T", true, 3, [](const Rigid& T, double* o) { Eigen::Map<Eigen::Vector3d> out(o); out = rotation_vector(T.R); });
  }, py::arg("T"), "Rotation vectors (angle in [0, pi] times the unit axis). Use robokin.pose.axis_angle.");
  m.def("pose_exp", [](ArrayLike xi) {
    return frames_from(xi, "xi", 6, [](const double* v) { return se3_exp(Eigen::Map<const Vector6>(v)); });
  }, py::arg("xi"), "SE(3) exponential of twists (v, w). Use robokin.pose.exp.");
  m.def("pose_log", [](ArrayLike T) {
    return vectors_from(T, "T", false, 6, [](const Rigid& F, double* o) { Eigen::Map<Vector6> out(o); out = se3_log(F); });
  }, py::arg("T"), "SE(3) logarithm (v, w) of frames. Use robokin.pose.log.");
  m.def("pose_error", &pose_error_of, py::arg("target"), py::arg("current"),
        "The IK's pose error (p_t - p, rotation vector of R_t R^T). Use robokin.pose.error.");
}

}  // namespace robokin::bind
