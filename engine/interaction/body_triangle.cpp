// The body triangle head / left hand / right hand; see horopter/interaction/detection.hpp.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "horopter/interaction/detection.hpp"

namespace horopter {

BodyTriangle bodyTriangle(cv::Point2f head, cv::Point2f leftHand, cv::Point2f rightHand) {
  BodyTriangle t;
  t.head = head;
  t.leftHand = leftHand;
  t.rightHand = rightHand;
  auto length = [](cv::Point2f p, cv::Point2f q) {
    return std::hypot(double(p.x - q.x), double(p.y - q.y));
  };
  // Each vertex is weighted by the length of the side opposite it.
  const double a = length(leftHand, rightHand);  // opposite the head
  const double b = length(head, rightHand);      // opposite the left hand
  const double c = length(head, leftHand);       // opposite the right hand
  t.perimeter = a + b + c;
  const double cross = double(leftHand.x - head.x) * (rightHand.y - head.y) -
                       double(leftHand.y - head.y) * (rightHand.x - head.x);
  if (t.perimeter <= 1e-9 || std::abs(cross) <= 1e-9 * t.perimeter * t.perimeter) {
    t.degenerate = true;
    t.incentre = (head + leftHand + rightHand) / 3.0f;
    t.headAngleRad = (b > 0 && c > 0 && a > b + c - 1e-9) ? std::numbers::pi : 0.0;
    return t;
  }
  t.incentre = cv::Point2f(
      static_cast<float>((a * head.x + b * leftHand.x + c * rightHand.x) / t.perimeter),
      static_cast<float>((a * head.y + b * leftHand.y + c * rightHand.y) / t.perimeter));
  // The law of cosines at the head vertex.
  const double cosine = std::clamp((b * b + c * c - a * a) / (2 * b * c), -1.0, 1.0);
  t.headAngleRad = std::acos(cosine);
  return t;
}

}  // namespace horopter
