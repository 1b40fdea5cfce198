#include "frame_dicts.hpp"

#include <pybind11/stl.h>

#include "arrays.hpp"
#include "horopter/interaction/detection.hpp"
#include "horopter/interaction/godfather.hpp"
#include "horopter/interaction/tracking.hpp"
#include "horopter/sim/sim_frame.hpp"

namespace horopter::python {

namespace {

py::tuple point(const cv::Point2f& p) {
  return py::make_tuple(p.x, p.y);
}
py::tuple point(const cv::Point3f& p) {
  return py::make_tuple(p.x, p.y, p.z);
}

py::dict partDict(const PartState& part) {
  py::dict d;
  d["tracked"] = part.tracked;
  d["observed"] = part.observed;
  d["image"] = point(part.image);
  d["rig"] = point(part.rig);
  return d;
}

py::dict personDict(const synth::PersonTruth& p) {
  py::dict d;
  d["id"] = p.id;
  d["visible"] = p.visible;
  d["inside_zone"] = p.insideZone;
  d["head_2d"] = point(p.head2d);
  d["left_hand_2d"] = point(p.leftHand2d);
  d["right_hand_2d"] = point(p.rightHand2d);
  d["head_3d"] = point(p.head3d);
  d["left_hand_3d"] = point(p.leftHand3d);
  d["right_hand_3d"] = point(p.rightHand3d);
  d["face_width_px"] = p.faceWidthPx;
  d["movement"] = synth::movementName(p.movement);
  return d;
}

py::tuple box(const cv::Rect& r) {
  return py::make_tuple(r.x, r.y, r.width, r.height);
}

py::dict triangleDict(const BodyTriangle& t) {
  py::dict d;
  d["head"] = point(t.head);
  d["left_hand"] = point(t.leftHand);
  d["right_hand"] = point(t.rightHand);
  d["incentre"] = point(t.incentre);
  d["perimeter"] = t.perimeter;
  d["head_angle_rad"] = t.headAngleRad;
  d["degenerate"] = t.degenerate;
  return d;
}

py::dict detectionsDict(const Detections& det) {
  py::list faces, hands;
  for (const FaceDetection& f : det.faces) {
    py::dict d;
    d["box"] = box(f.box);
    d["centre"] = point(f.centre);
    d["width"] = f.width;
    d["inside_zone"] = f.insideZone;
    faces.append(d);
  }
  for (const HandDetection& h : det.hands) {
    py::dict d;
    d["centroid"] = point(h.centroid);
    d["box"] = box(h.box);
    d["area_px"] = h.areaPx;
    d["inside_zone"] = h.insideZone;
    hands.append(d);
  }
  py::dict d;
  d["scope"] = detectionScopeName(det.scope);
  d["faces"] = faces;
  d["hands"] = hands;
  d["triangle"] = det.triangle ? py::object(triangleDict(*det.triangle)) : py::none();
  d["searched"] = box(det.searched);
  d["searched_pixels"] = det.searchedPixels;
  return d;
}

py::dict trackingDict(const TrackingState& t) {
  py::dict d;
  d["time_s"] = t.timeS;
  d["election"] = electionStateName(t.election);
  d["candidate_s"] = t.candidateS;
  d["face_width_px"] = t.faceWidthPx;
  d["head"] = partDict(t.head);
  d["left_hand"] = partDict(t.leftHand);
  d["right_hand"] = partDict(t.rightHand);
  d["triangle"] = t.triangle ? py::object(triangleDict(*t.triangle)) : py::none();
  if (t.headCommand) {
    py::dict c;
    c["pan"] = t.headCommand->pan;
    c["tilt"] = t.headCommand->tilt;
    c["vergence"] = t.headCommand->vergence;
    c["frame"] = t.headCommandFrame;
    d["head_command"] = c;
  } else {
    d["head_command"] = py::none();
  }
  return d;
}

}  // namespace

py::dict bodyDict(const BodySample& body) {
  py::dict d;
  d["frame"] = body.frame;
  d["time_s"] = body.timeS;
  d["godfather"] = body.godfather;
  d["head"] = partDict(body.head);
  d["left_hand"] = partDict(body.leftHand);
  d["right_hand"] = partDict(body.rightHand);
  return d;
}

BodySample bodyFromDict(py::handle dict) {
  const auto part = [](py::handle d) {
    PartState p;
    p.tracked = d["tracked"].cast<bool>();
    p.observed = d["observed"].cast<bool>();
    const auto image = d["image"].cast<std::pair<float, float>>();
    p.image = {image.first, image.second};
    const auto rig = d["rig"].cast<std::tuple<float, float, float>>();
    p.rig = {std::get<0>(rig), std::get<1>(rig), std::get<2>(rig)};
    return p;
  };
  BodySample b;
  b.frame = dict["frame"].cast<std::int64_t>();
  b.timeS = dict["time_s"].cast<double>();
  b.godfather = dict["godfather"].cast<bool>();
  b.head = part(dict["head"]);
  b.leftHand = part(dict["left_hand"]);
  b.rightHand = part(dict["right_hand"]);
  return b;
}

py::dict movementDict(const MovementState& state) {
  py::dict posterior;
  for (int i = 0; i < kMovementClassCount; ++i)
    posterior[movementClassName(static_cast<MovementClass>(i))] =
        state.posterior[static_cast<std::size_t>(i)];
  py::dict d;
  d["features_valid"] = state.features.valid;
  d["likeliest"] = movementClassName(state.likeliest);
  d["posterior"] = posterior;
  d["decision"] = state.decision ? py::object(py::str(movementClassName(*state.decision)))
                                 : py::object(py::none());
  d["action"] = robotActionName(state.action);
  d["action_started"] = state.actionStarted;
  d["interaction_stopped"] = state.interactionStopped;
  return d;
}

py::dict truthDict(const synth::FrameTruth& truth) {
  py::dict d;
  d["index"] = truth.index;
  d["time_s"] = truth.timeS;
  d["disparity"] = shareMat(truth.disparity);
  d["inside"] = shareMat(truth.inside);
  d["occluded"] = shareMat(truth.occluded);
  py::list people;
  for (const auto& p : truth.people)
    people.append(personDict(p));
  d["people"] = people;
  py::dict head;
  head["pan"] = truth.head.pan;
  head["tilt"] = truth.head.tilt;
  head["vergence"] = truth.head.vergence;
  d["head"] = head;
  d["fixation_distance_m"] = truth.fixationDistanceM;
  return d;
}

py::dict frameDict(const Frame& frame) {
  py::dict d;
  d["index"] = frame.index;
  d["left"] = shareMat(frame.left);
  d["right"] = shareMat(frame.right);
  d["left_grey"] = shareMat(frame.leftGrey);
  d["right_grey"] = shareMat(frame.rightGrey);
  d["disparity"] = shareMat(frame.disparity);
  d["mask"] = shareMat(frame.mask);
  py::array_t<std::int16_t> thresholds(static_cast<py::ssize_t>(frame.thresholds.size()));
  std::copy(frame.thresholds.begin(), frame.thresholds.end(), thresholds.mutable_data());
  d["thresholds"] = thresholds;
  d["search_range"] =
      py::make_tuple(frame.searchRange.minDisparity, frame.searchRange.numDisparities);
  d["body"] = bodyDict(frame.body);
  const synth::FrameTruth* truth = sim::truthOf(frame);
  d["truth"] = truth ? py::object(truthDict(*truth)) : py::none();
  d["movement"] = frame.movement ? py::object(movementDict(*frame.movement)) : py::none();
  d["detections"] = frame.detections ? py::object(detectionsDict(*frame.detections)) : py::none();
  d["tracking"] = frame.tracking ? py::object(trackingDict(*frame.tracking)) : py::none();
  return d;
}

}  // namespace horopter::python
