// The Robot class of the compiled module: a validated model built from a robot file (YAML text,
// a file, or an example compiled into the library), its description, and its drawing. Its
// algorithms are robot_algorithms.cpp's, stiffness.cpp's and batch.cpp's.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <string>

#include "arrays.hpp"
#include "expose.hpp"
#include "nocdyn/drawing.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/model.hpp"

namespace nocdyn::python {

namespace {

/// Per limb: name, type ("PRR", ...) and which of its joints are actuated.
py::list limbInfo(const Robot& r) {
    py::list out;
    const Model& model = *r.model;
    for (int j = 0; j < model.limbs; ++j) {
        const LimbDescription& limb = model.description.limbs[static_cast<std::size_t>(j)];
        py::dict d;
        d["name"] = limb.name;
        d["type"] = limb.type();
        py::list joints;
        for (const JointDescription& joint : limb.joints) joints.append(joint.actuated);
        d["actuated"] = joints;
        out.append(d);
    }
    return out;
}

/// Per actuator: its limb and joint (numbered from 1, as the command line names them), type and limits.
py::list actuatorInfo(const Robot& r) {
    py::list out;
    const Model& model = *r.model;
    for (int a = 0; a < model.actuators; ++a) {
        const auto j = static_cast<std::size_t>(model.actuator_limb[static_cast<std::size_t>(a)]);
        const auto k = static_cast<std::size_t>(model.actuator_joint[static_cast<std::size_t>(a)]);
        const JointDescription& joint = model.description.limbs[j].joints[k];
        py::dict d;
        d["limb"] = static_cast<int>(j) + 1;
        d["limb_name"] = model.description.limbs[j].name;
        d["joint"] = static_cast<int>(k) + 1;
        d["type"] = joint.type == JointType::prismatic ? "P" : "R";
        d["lower"] = joint.limits.lower;
        d["upper"] = joint.limits.upper;
        d["effort"] = joint.limits.effort;
        d["velocity"] = joint.limits.velocity;
        out.append(d);
    }
    return out;
}

/// The geometry the animation page and the CLI's frames draw (drawing.hpp) at a pose.
py::dict drawing(const Robot& r, const py::handle& pose) {
    Data data(*r.model);
    RobotDrawing drawing;
    if (const Status status = drawRobot(*r.model, data, vector3(pose, "pose"), drawing); !status)
        throw Error(describe(status, *r.model));
    const auto point = [](const Vector2& v) { return py::make_tuple(v.x(), v.y()); };
    py::list limbs, platform;
    for (int j = 0; j < drawing.limbs; ++j) {
        py::list joints;
        for (const JointDrawing& joint : drawing.limb[static_cast<std::size_t>(j)].joint) {
            py::dict d;
            d["type"] = joint.type == JointType::prismatic ? "P" : "R";
            d["actuator"] = joint.actuator;
            d["position"] = point(joint.position);
            d["rail_start"] = point(joint.rail_start);
            d["rail_end"] = point(joint.rail_end);
            joints.append(d);
        }
        limbs.append(joints);
        platform.append(point(drawing.platform[static_cast<std::size_t>(j)]));
    }
    py::dict out;
    out["limbs"] = limbs;
    out["platform"] = platform;
    out["C"] = point(drawing.C);
    return out;
}

}  // namespace

void exposeRobot(py::module_& m) {
    py::class_<Robot>(m, "Robot")
        .def_static(
            "load", [](const std::string& path) { return Robot(io::loadRobotDescription(path)); }, py::arg("path"))
        .def_static(
            "from_yaml",
            [](const std::string& text, const std::string& source) {
                return Robot(io::parseRobotDescription(text, source));
            },
            py::arg("text"), py::arg("source") = "<string>")
        .def_static(
            "example", [](const std::string& name) { return Robot(io::exampleRobot(name)); }, py::arg("name"))
        .def_static("paper", [] { return Robot(io::exampleRobot("paper-3prr")); })
        .def_static("example_names", [] { return io::exampleRobotNames(); })
        .def_property_readonly("name", [](const Robot& r) { return r.model->description.name; })
        .def_property_readonly("source", [](const Robot& r) { return r.model->description.source; })
        .def_property_readonly("actuator_count", [](const Robot& r) { return r.model->actuators; })
        .def_property_readonly("limb_count", [](const Robot& r) { return r.model->limbs; })
        .def_property_readonly("bodies", [](const Robot& r) { return r.model->bodies; })
        .def_property_readonly("home", [](const Robot& r) { return taskPoseArray(*r.model, r.model->home); })
        .def_property_readonly("gravity",
                               [](const Robot& r) {
                                   return std::array{r.model->gravity(0), r.model->gravity(1)};
                               })
        .def_property_readonly("task_dimension", [](const Robot& r) { return r.model->task_dimension; })
        .def_property_readonly("redundant",
                               [](const Robot& r) { return r.model->coordinates == Coordinates::platform; })
        .def("limb_info", &limbInfo)
        .def("actuator_info", &actuatorInfo)
        .def("_drawing", &drawing, py::arg("pose"))
        .def("to_yaml", [](const Robot& r) { return io::descriptionToYaml(r.model->description); });
}

}  // namespace nocdyn::python
