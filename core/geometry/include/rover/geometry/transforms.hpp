#pragma once
/// @file
/// Small helpers over Eigen rotations and rigid transforms.
///
/// Frames (rover convention): rover frame x forward, y left, z up; site frame x north, y west,
/// z up; camera frame x right, y down, z forward. Angles are radians, lengths metres.
///
/// Transform naming: `a_from_b` (an Eigen::Isometry3d) maps coordinates of a point in frame b
/// to frame a, p_a = a_from_b * p_b; equivalently it is the pose of frame b in frame a (its
/// translation is b's origin in a, its rotation's columns are b's axes in a).
///
/// Roll-pitch-yaw follow the aerospace ZYX convention: R = Rz(yaw) * Ry(pitch) * Rx(roll), i.e.
/// yaw about z (positive = turning left, counter-clockwise seen from above in the z-up rover
/// frame), then pitch about the new y (positive = nose DOWN, since y points left), then roll
/// about the new x (positive = right side down, left side up).

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace rover::geometry {

using Vector6d = Eigen::Matrix<double, 6, 1>;

/// Roll, pitch, yaw [rad] as a vector (x = roll, y = pitch, z = yaw).
using Rpy = Eigen::Vector3d;

/// R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Matrix3d RotationFromRpy(double roll, double pitch, double yaw);
inline Eigen::Matrix3d RotationFromRpy(const Rpy& rpy) {
  return RotationFromRpy(rpy.x(), rpy.y(), rpy.z());
}

/// The unit quaternion of RotationFromRpy(roll, pitch, yaw), with w >= 0.
Eigen::Quaterniond QuaternionFromRpy(double roll, double pitch, double yaw);
inline Eigen::Quaterniond QuaternionFromRpy(const Rpy& rpy) {
  return QuaternionFromRpy(rpy.x(), rpy.y(), rpy.z());
}

/// Inverse of RotationFromRpy: returns (roll, pitch, yaw) with pitch in [-pi/2, pi/2] and roll,
/// yaw in (-pi, pi]. At gimbal lock (|pitch| = pi/2, where only yaw - roll or yaw + roll is
/// defined) roll is set to 0. Precondition: `r` is a rotation matrix (orthonormal, det +1).
Rpy RpyFromRotation(const Eigen::Matrix3d& r);

/// RpyFromRotation of the (normalised) quaternion `q`.
Rpy RpyFromQuaternion(const Eigen::Quaterniond& q);

/// Wraps an angle [rad] to (-pi, pi]. Non-finite input is returned unchanged.
double WrapAngle(double angle);

/// Skew-symmetric (cross-product) matrix: Skew(v) * w = v.cross(w).
Eigen::Matrix3d Skew(const Eigen::Vector3d& v);

/// SO(3) exponential: the rotation by |phi| radians about phi / |phi| (Rodrigues).
Eigen::Matrix3d ExpSo3(const Eigen::Vector3d& phi);

/// SO(3) logarithm: the rotation vector phi with |phi| in [0, pi] such that ExpSo3(phi) == r.
/// At |phi| = pi the sign of phi is not unique; either is returned. Precondition: rotation.
Eigen::Vector3d LogSo3(const Eigen::Matrix3d& r);

/// SE(3) exponential of the twist xi = [rho; phi] (translation part first, then the rotation
/// vector), as in Barfoot, "State Estimation for Robotics", ch. 7:
///   R = ExpSo3(phi),   t = J(phi) rho,
///   J(phi) = I + (1 - cos a)/a^2 K + (a - sin a)/a^3 K^2,   a = |phi|, K = Skew(phi).
/// Note rho == t only when phi == 0. Small angles use Taylor series (no division by zero).
Eigen::Isometry3d ExpSe3(const Vector6d& xi);

/// SE(3) logarithm, inverse of ExpSe3: xi = [J(phi)^-1 t; LogSo3(R)] with |phi| <= pi.
/// For a pose error between an estimate and a reference use LogSe3(reference.inverse() * estimate)
/// (the error expressed in the reference's body frame).
Vector6d LogSe3(const Eigen::Isometry3d& t);

/// Left Jacobian J(phi) of SO(3) used by ExpSe3 (see above).
Eigen::Matrix3d LeftJacobianSo3(const Eigen::Vector3d& phi);

/// Inverse of LeftJacobianSo3 (defined for |phi| < 2 pi).
Eigen::Matrix3d InverseLeftJacobianSo3(const Eigen::Vector3d& phi);

}  // namespace rover::geometry
