// A constant-velocity Kalman filter in the image plane (state x, y, vx, vy in
// pixels and pixels/s), with a Mahalanobis gate for data association.
#pragma once

#include "horopter/core/export.hpp"

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace horopter {

struct HOROPTER_API KalmanOptions {
  double accelerationStd = 1500;  // white-noise acceleration, px/s^2 (how fast parts may turn)
  double measurementStd = 4;      // detection noise, px
  double initialSpeedStd = 300;   // velocity uncertainty of a new track, px/s
  double gateChi2 = 13.8;         // squared Mahalanobis gate (chi-square, 2 dof, 99.9 %)
  double gateMinPx = 12;          // a detection this close always passes the gate
};

class HOROPTER_API ConstantVelocityTrack {
 public:
  // Throws horopter::Error for non-positive noises or gate.
  ConstantVelocityTrack(cv::Point2f position, double timeS, const KalmanOptions& options);

  // Moves the state to `timeS` (>= the last time; an earlier time is ignored).
  void predict(double timeS);
  // Squared Mahalanobis distance of a detection from the predicted position.
  double distance2(cv::Point2f z) const;
  bool inGate(cv::Point2f z) const;
  void update(cv::Point2f z);
  // Scales the velocity (a track without detections slows down instead of
  // flying off along its last velocity).
  void dampVelocity(double factor);
  // Moves the position by `delta` (the image moved under the track: the
  // camera turned); velocity and covariance are kept.
  void shift(cv::Point2f delta);

  cv::Point2f position() const { return {static_cast<float>(x_(0)), static_cast<float>(x_(1))}; }
  cv::Point2f velocity() const { return {static_cast<float>(x_(2)), static_cast<float>(x_(3))}; }
  const Eigen::Matrix4d& covariance() const { return p_; }
  double timeS() const { return time_; }
  double lastUpdateS() const { return lastUpdate_; }

 private:
  KalmanOptions options_;
  Eigen::Vector4d x_;
  Eigen::Matrix4d p_;
  double time_ = 0, lastUpdate_ = 0;
};

}  // namespace horopter
