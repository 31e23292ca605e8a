// Pose conversions: roll-pitch-yaw, unit quaternions (w, x, y, z), axis-angle and the SE(3)
// exponential and logarithm. One implementation of each formula: robokin.pose and the Cartesian
// trajectories (traj.cpp) both call these.
#pragma once

#include "robokin/chain.hpp"

#include <Eigen/Dense>

namespace robokin {

using Vector6 = Eigen::Matrix<double, 6, 1>;

// R = Rz(yaw) Ry(pitch) Rx(roll): fixed axes x, then y, then z (the URDF / ROS convention).
Eigen::Matrix3d rpy_to_matrix(double roll, double pitch, double yaw);
// (roll, pitch, yaw), pitch in [-pi/2, pi/2], roll and yaw in [-pi, pi]; at pitch = +-pi/2
// (gimbal lock: only yaw -+ roll is defined) roll is 0.
Eigen::Vector3d matrix_to_rpy(const Eigen::Matrix3d& R);

// Unit quaternion (w, x, y, z) with w >= 0 (of the two, the one with the non-negative scalar).
Eigen::Vector4d matrix_to_quaternion(const Eigen::Matrix3d& R);
// The rotation of a quaternion (w, x, y, z) of any non-zero norm (it is normalised first).
Eigen::Matrix3d quaternion_to_matrix(const Eigen::Vector4d& q);
// Hamilton product a * b of quaternions (w, x, y, z).
Eigen::Vector4d quaternion_multiply(const Eigen::Vector4d& a, const Eigen::Vector4d& b);

// so(3) exponential (Rodrigues): the rotation by |w| about w / |w|. Its logarithm is
// rotation_vector (task.hpp).
Eigen::Matrix3d rotation_exp(const Eigen::Vector3d& w);

// SE(3) exponential of the twist xi = (v, w): T = exp([xi]), [xi] = [[w]x v; 0 0].
Rigid se3_exp(const Vector6& xi);
// Its inverse: xi = (v, w) with |w| in [0, pi].
Vector6 se3_log(const Rigid& T);

// The IK's pose error of `current` toward `target`: (p_t - p, rotation_vector(R_t R^T)), base frame.
Vector6 pose_error(const Rigid& target, const Rigid& current);

}  // namespace robokin
