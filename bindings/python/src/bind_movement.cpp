// The movement classifier (issue 8): models (train, load, save), body
// tracks, synthetic labelled sequences, and classification of a track into
// plain dicts (posterior, decision, the robot's action).
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "frame_dicts.hpp"
#include "horopter/eval/movement_training.hpp"
#include "horopter/movement/body_track_file.hpp"
#include "horopter/movement/movement.hpp"
#include "horopter/movement/movement_classifier.hpp"

namespace horopter::python {

namespace {

// pybind11 holds models as shared_ptr<MovementModel>; Python only reaches
// const methods, so the engine's shared_ptr<const MovementModel> is cast.
using ModelPtr = std::shared_ptr<MovementModel>;

py::dict paramsDict(const MovementModelParams& p) {
  py::dict d;
  d["stay"] = p.stay;
  d["evidence_weight"] = p.evidenceWeight;
  d["decision_threshold"] = p.decisionThreshold;
  d["rearm_threshold"] = p.rearmThreshold;
  d["alpha"] = p.alpha;
  return d;
}

std::vector<BodySample> samplesFrom(const py::iterable& samples) {
  std::vector<BodySample> out;
  for (const py::handle& s : samples)
    out.push_back(bodyFromDict(s));
  return out;
}

ModelPtr train(int sequences, std::uint64_t firstSeed) {
  if (sequences < 1) throw py::value_error("sequences must be >= 1");
  TrainingOptions options;
  options.sequences = sequences;
  options.firstSeed = firstSeed;
  py::gil_scoped_release release;
  return std::make_shared<MovementModel>(trainMovementModel(options));
}

py::list classify(const py::iterable& samples, const ModelPtr& model) {
  const std::vector<BodySample> track = samplesFrom(samples);
  std::vector<MovementState> states;
  {
    py::gil_scoped_release release;
    states = classifyTrack(track, model);
  }
  py::list out;
  for (const MovementState& s : states)
    out.append(movementDict(s));
  return out;
}

}  // namespace

void bindMovement(py::module_& m) {
  py::class_<MovementModel, ModelPtr>(m, "MovementModel",
                                      "The Bayesian movement classifier's model: counts of the "
                                      "LMA symbols per movement, and its parameters")
      .def_static(
          "load",
          [](const std::string& path) {
            return ModelPtr(std::make_shared<MovementModel>(MovementModel::load(path)));
          },
          py::arg("path"), "A model file written by `horopter train` or save()")
      .def_static("train", &train, py::arg("sequences") = 300,
                  py::arg("first_seed") = kTrainingSeedBase,
                  "Trains on synthetic labelled sequences (the default model: 300)")
      .def_static(
          "default",
          [] {
            py::gil_scoped_release release;
            return std::const_pointer_cast<MovementModel>(defaultMovementModel());
          },
          "The model the commands use without --model (trained on first use, a few seconds)")
      .def("save", &MovementModel::save, py::arg("path"))
      .def("serialize", &MovementModel::serialize)
      .def_property_readonly("params",
                             [](const MovementModel& model) { return paramsDict(model.params()); });

  m.def("classify_track", &classify, py::arg("samples"), py::arg("model"),
        "Runs LMA, the classifier and the behaviour over body samples (dicts as in a pipeline "
        "frame's 'body'); one movement dict per sample");
  m.def(
      "synthetic_sequence",
      [](std::uint64_t seed, double seconds) {
        SequenceOptions options;
        options.seconds = seconds;
        const LabelledSequence seq = syntheticSequence(seed, options);
        py::list samples, labels;
        for (const BodySample& s : seq.samples)
          samples.append(bodyDict(s));
        for (MovementClass c : seq.labels)
          labels.append(movementClassName(c));
        py::dict d;
        d["seed"] = seq.seed;
        d["samples"] = samples;
        d["labels"] = labels;
        return d;
      },
      py::arg("seed"), py::arg("seconds") = 0.0,
      "A labelled synthetic body track: {'seed', 'samples': [body dicts], 'labels': [names]}");
  m.def(
      "read_body_track",
      [](const std::string& path) {
        py::list out;
        for (const BodySample& s : readBodyTrack(path))
          out.append(bodyDict(s));
        return out;
      },
      py::arg("path"), "A body track file (horopter classify --write-track) as body dicts");
  m.def(
      "write_body_track",
      [](const std::string& path, const py::iterable& samples) {
        writeBodyTrack(path, samplesFrom(samples));
      },
      py::arg("path"), py::arg("samples"),
      "Writes body samples (dicts as in a pipeline frame's 'body') as a body track file, as "
      "`horopter classify --write-track` does; read_body_track reads it back");
  py::list names;
  for (int i = 0; i < kMovementClassCount; ++i)
    names.append(movementClassName(static_cast<MovementClass>(i)));
  m.attr("MOVEMENTS") = names;
}

}  // namespace horopter::python
