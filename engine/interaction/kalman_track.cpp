// The constant-velocity Kalman filter; see horopter/interaction/kalman_track.hpp.
#include "horopter/interaction/kalman_track.hpp"

#include <Eigen/Dense>

#include "horopter/core/error.hpp"

namespace horopter {

ConstantVelocityTrack::ConstantVelocityTrack(cv::Point2f position, double timeS,
                                             const KalmanOptions& options)
    : options_(options), time_(timeS), lastUpdate_(timeS) {
  if (!(options.accelerationStd > 0) || !(options.measurementStd > 0) ||
      !(options.initialSpeedStd > 0) || !(options.gateChi2 > 0) || options.gateMinPx < 0)
    throw Error("Kalman noises and gate must be positive");
  x_ << position.x, position.y, 0, 0;
  const double r = options.measurementStd * options.measurementStd;
  const double v = options.initialSpeedStd * options.initialSpeedStd;
  p_ = Eigen::Vector4d(r, r, v, v).asDiagonal();
}

void ConstantVelocityTrack::predict(double timeS) {
  const double dt = timeS - time_;
  if (!(dt > 0)) return;
  Eigen::Matrix4d f = Eigen::Matrix4d::Identity();
  f(0, 2) = f(1, 3) = dt;
  // Discrete white-noise acceleration: G q G^T with G = [dt^2/2, dt]^T per axis.
  const double q = options_.accelerationStd * options_.accelerationStd;
  const double dt2 = dt * dt, dt3 = dt2 * dt, dt4 = dt3 * dt;
  Eigen::Matrix4d qm = Eigen::Matrix4d::Zero();
  qm(0, 0) = qm(1, 1) = q * dt4 / 4;
  qm(0, 2) = qm(2, 0) = qm(1, 3) = qm(3, 1) = q * dt3 / 2;
  qm(2, 2) = qm(3, 3) = q * dt2;
  x_ = f * x_;
  p_ = f * p_ * f.transpose() + qm;
  time_ = timeS;
}

double ConstantVelocityTrack::distance2(cv::Point2f z) const {
  const Eigen::Vector2d y(z.x - x_(0), z.y - x_(1));
  Eigen::Matrix2d s = p_.topLeftCorner<2, 2>();
  s.diagonal().array() += options_.measurementStd * options_.measurementStd;
  return y.dot(s.ldlt().solve(y));
}

bool ConstantVelocityTrack::inGate(cv::Point2f z) const {
  const double dx = z.x - x_(0), dy = z.y - x_(1);
  if (dx * dx + dy * dy <= options_.gateMinPx * options_.gateMinPx) return true;
  return distance2(z) <= options_.gateChi2;
}

void ConstantVelocityTrack::update(cv::Point2f z) {
  Eigen::Matrix<double, 2, 4> h = Eigen::Matrix<double, 2, 4>::Zero();
  h(0, 0) = h(1, 1) = 1;
  const Eigen::Vector2d y(z.x - x_(0), z.y - x_(1));
  Eigen::Matrix2d s = h * p_ * h.transpose();
  s.diagonal().array() += options_.measurementStd * options_.measurementStd;
  const Eigen::Matrix<double, 4, 2> k = p_ * h.transpose() * s.inverse();
  x_ += k * y;
  // Joseph form keeps the covariance symmetric and positive.
  const Eigen::Matrix4d ikh = Eigen::Matrix4d::Identity() - k * h;
  const double r = options_.measurementStd * options_.measurementStd;
  p_ = ikh * p_ * ikh.transpose() + r * k * k.transpose();
  lastUpdate_ = time_;
}

void ConstantVelocityTrack::dampVelocity(double factor) {
  x_(2) *= factor;
  x_(3) *= factor;
}

void ConstantVelocityTrack::shift(cv::Point2f delta) {
  x_(0) += delta.x;
  x_(1) += delta.y;
}

}  // namespace horopter
