// Robot's algorithms at one sample, bound one to one (as Pinocchio's expose-rnea.cpp binds
// rnea): inverse dynamics and the NOC matrices (dynamics.hpp), the exact derivatives
// (derivatives.hpp), the linearised model (analysis/linearization.hpp), direct kinematics
// (direct_kinematics.hpp), the state from actuator values, the regressor and the standard
// parameters (sim/identification.hpp), a payload merged into the platform (sim/control.hpp).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "app/frequency_response.hpp"
#include "arrays.hpp"
#include "expose.hpp"
#include "nocdyn/analysis/linearization.hpp"
#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/batch.hpp"
#include "nocdyn/derivatives.hpp"
#include "nocdyn/direct_kinematics.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/forward_dynamics.hpp"
#include "nocdyn/sim/identification.hpp"

namespace nocdyn::python {

namespace {

py::tuple inverseDynamicsSample(const Robot& robot, const py::handle& p, const py::handle& dp, const py::handle& ddp,
                                bool matrices, bool check_limits, bool check) {
    const Model& model = *robot.model;
    const Pose p3 = vector3(p, "p");
    const Twist dp3 = vector3(dp, "dp"), ddp3 = vector3(ddp, "ddp");
    Data data(model);
    // the limits of passive joints need every joint's q and rate: the full path
    const bool actuated_only = limitsOnActuatedJointsOnly(model);
    const bool full = matrices || (check_limits && !actuated_only);
    const Status status =
        full ? inverseDynamics(model, data, p3, dp3, ddp3) : inverseDynamicsFast(model, data, p3, dp3, ddp3);
    if (!status) throw Error(describe(status, model));
    if (check_limits) {
        const Status limits =
            actuated_only ? checkActuatorLimits(model, data.u, data.du, data.tau) : checkSampleLimits(model, data);
        if (!limits) throw Error(describe(limits, model));
    }
    // finite input whose results overflow (huge rates or accelerations): an error, as the
    // batch's failed sample (check=False returns them)
    if (check) {
        const int n = model.actuators;
        bool finite = data.u.head(n).allFinite() && data.du.head(n).allFinite() && data.ddu.head(n).allFinite() &&
                      data.tau.head(n).allFinite();
        if (matrices) {
            finite = finite && data.I.allFinite() && data.C.allFinite();
            for (int i = 0; finite && i < model.bodies; ++i) finite = data.T[static_cast<std::size_t>(i)].allFinite();
        }
        if (!finite) throw Error("the inverse dynamics is not finite (the input is too large)");
    }
    if (!matrices) return py::make_tuple(toArray(data.u), toArray(data.du), toArray(data.ddu), toArray(data.tau));
    // the independent coordinates are the pose when redundant: I, C and T's columns then in
    // Python's pose order; T_i's rows are body i's twist, [v_x, v_y, omega] in that order too
    const bool pose_coordinates = model.coordinates == Coordinates::platform;
    py::array_t<double> T({static_cast<py::ssize_t>(model.bodies), py::ssize_t{3}, py::ssize_t{3}});
    for (int i = 0; i < model.bodies; ++i) {
        const Eigen::MatrixXd Ti = inPythonOrder(data.T[static_cast<std::size_t>(i)], true, pose_coordinates);
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) T.mutable_at(i, r, c) = Ti(r, c);
    }
    const Matrix3 I = inPythonOrder(data.I, pose_coordinates, pose_coordinates);
    const Matrix3 C = inPythonOrder(data.C, pose_coordinates, pose_coordinates);
    return py::make_tuple(toArray(data.u), toArray(data.du), toArray(data.ddu), toArray(data.tau), toArray(I),
                          toArray(C), T);
}

/// An actuator x pose derivative as an (n, 3) array, its columns in Python's pose order.
py::array_t<double> poseColumns(const ActuatorPoseJacobian& m) { return toArray(inPythonOrder(m, false, true)); }

/// d tau/d p, d tau/d dp, d tau/d ddp of one sample, each (n, 3).
py::tuple inverseDynamicsDerivativesSample(const Robot& robot, const py::handle& p, const py::handle& dp,
                                           const py::handle& ddp) {
    const Model& model = *robot.model;
    InverseDynamicsDerivatives d;
    const Status status =
        inverseDynamicsDerivatives(model, *robot.data, vector3(p, "p"), vector3(dp, "dp"), vector3(ddp, "ddp"), d);
    if (!status) throw Error(describe(status, model));
    return py::make_tuple(poseColumns(d.d_p), poseColumns(d.d_dp), poseColumns(d.d_ddp));
}

/// u, du, ddu, each (n,), and d u/d p, d du/d p, d du/d dp, d ddu/d p, d ddu/d dp, d ddu/d ddp,
/// each (n, 3), of one sample.
py::tuple actuatorDerivativesSample(const Robot& robot, const py::handle& p, const py::handle& dp,
                                    const py::handle& ddp) {
    const Model& model = *robot.model;
    ActuatorVariableDerivatives d;
    const Status status =
        actuatorVariableDerivatives(model, *robot.data, vector3(p, "p"), vector3(dp, "dp"), vector3(ddp, "ddp"), d);
    if (!status) throw Error(describe(status, model));
    return py::make_tuple(toArray(d.u), toArray(d.du), toArray(d.ddu), poseColumns(d.u_p), poseColumns(d.du_p),
                          poseColumns(d.du_dp), poseColumns(d.ddu_p), poseColumns(d.ddu_dp), poseColumns(d.ddu_ddp));
}

/// "field: expected a, b or c, got 'word'" for a word E's table does not list.
template <class E>
std::string unknownChoice(const char* field, const std::string& word) {
    std::string message = field;
    message.append(": expected ").append(choiceList<E>()).append(", got '").append(word).append("'");
    return message;
}

/// The linearised model at (p, dp, tau): (A, B, C, D, inputs, model), the output "acceleration"
/// or "actuators"; compliance "auto" (the lumped compliant model, linearizeCompliant, when the
/// robot file declares compliance), "rigid" or "lumped" as `nocdyn frequency-response
/// --compliance`; inputs: per column of B "tau" (a force) or "uc" (a commanded drive position);
/// model: "rigid" or "lumped".
py::tuple linearizeSample(const Robot& robot, const py::handle& p, const py::handle& dp, const py::handle& tau,
                          const std::string& output, const std::string& compliance) {
    const Model& model = *robot.model;
    const std::optional<LinearOutput> kind = choiceNamed<LinearOutput>(output);
    if (!kind) throw Error(unknownChoice<LinearOutput>("output", output));
    const std::optional<app::PlantCompliance> plant = choiceNamed<app::PlantCompliance>(compliance);
    if (!plant) throw Error(unknownChoice<app::PlantCompliance>("compliance", compliance));
    const StiffnessModel stiffness(model);
    const bool lumped =
        *plant == app::PlantCompliance::lumped || (*plant == app::PlantCompliance::automatic && stiffness.any);
    if (lumped && !stiffness.any) {
        throw Error("compliance: the robot file declares no joint or drive stiffness and no elastic link");
    }
    const Pose p3 = vector3(p, "p");
    const Twist dp3 = vector3(dp, "dp");
    const ActuatorVector tau_n = actuatorVector(model, tau, "tau");
    StateSpace ss;
    const Status status = lumped ? linearizeCompliant(model, stiffness, *robot.data, p3, dp3, tau_n, *kind, ss)
                                 : linearize(model, *robot.data, p3, dp3, tau_n, *kind, ss);
    if (!status) throw Error(describe(status, model));
    if (!(ss.A.allFinite() && ss.B.allFinite() && ss.C.allFinite() && ss.D.allFinite())) {
        throw Error("the linearised model is not finite at this operating point (the input is too large)");
    }
    py::list inputs;
    for (const LinearInput input : ss.inputs) inputs.append(name(input));
    // the state [p; dp] and the output ddp in Python's pose order; a two-DOF robot's state
    // [x, y, dx/dt, dy/dt] is in that order already
    const bool pose = model.task_dimension == 3;
    const bool pose_output = pose && *kind == LinearOutput::platform_acceleration;
    return py::make_tuple(toArray(inPythonOrder(ss.A, pose, pose)), toArray(inPythonOrder(ss.B, pose, false)),
                          toArray(inPythonOrder(ss.C, pose_output, pose)),
                          toArray(inPythonOrder(ss.D, pose_output, false)), py::tuple(inputs),
                          lumped ? "lumped" : "rigid");
}

/// Every assembly mode with actuator values u (direct kinematics).
py::dict forwardKinematics(const Robot& robot, const py::handle& u, double tolerance) {
    const Model& model = *robot.model;
    const ActuatorVector uu = actuatorVector(model, u, "u");
    Data data(model);
    AssemblyModes modes;
    DirectKinematicsOptions options;
    options.tolerance = tolerance;
    const Status status = directKinematics(model, data, uu, modes, options);
    if (!status) throw Error(describe(status, model));
    py::list list;
    for (const AssemblyMode& mode : modes) {
        py::dict d;
        d["pose"] = taskPoseArray(model, mode.p);
        std::vector<int> branch(mode.branch.begin(), mode.branch.begin() + model.limbs);
        d["branch"] = branch;
        d["working"] = mode.working;
        d["u_error"] = mode.u_error;
        d["condition"] = mode.condition;
        list.append(d);
    }
    py::dict out;
    out["modes"] = list;
    out["degenerate"] = modes.degenerate;
    out["truncated"] = modes.truncated;
    return out;
}

/// The state with actuator values u and rates du (None: at rest), by the library call the
/// command line's simulate uses (stateFromActuators).
py::dict stateFromActuatorValues(const Robot& robot, const py::handle& u, const py::handle& du, int assembly_mode) {
    const Model& model = *robot.model;
    const ActuatorVector uu = actuatorVector(model, u, "u");
    const ActuatorVector dd = du.is_none() ? ActuatorVector() : actuatorVector(model, du, "du");
    if (assembly_mode < 0) throw Error("assembly_mode: expected 0 (the nearest home) or a mode number from 1");
    Data data(model);
    ActuatorStart start;
    if (const Status status = stateFromActuators(model, data, uu, dd, assembly_mode, start); !status) {
        throw Error(describe(status, model));
    }
    py::dict out;
    out["p"] = taskPoseArray(model, start.p);
    out["dp"] = taskPoseArray(model, start.dp);
    out["mode"] = start.mode;
    out["working"] = start.working;
    out["modes"] = start.modes;
    return out;
}

/// Y of one sample: (n, P), tau = Y pi.
RowArray regressorSample(const Robot& robot, const py::handle& p, const py::handle& dp, const py::handle& ddp) {
    const Model& model = *robot.model;
    Data data(model);
    RegressorMatrix Y;
    const Status status =
        inverseDynamicsRegressor(model, data, vector3(p, "p"), vector3(dp, "dp"), vector3(ddp, "ddp"), Y);
    if (!status) throw Error(describe(status, model));
    if (!Y.allFinite()) throw Error("the regressor is not finite (the input is too large)");
    RowArray out({static_cast<py::ssize_t>(Y.rows()), static_cast<py::ssize_t>(Y.cols())});
    auto o = out.mutable_unchecked<2>();
    for (Eigen::Index r = 0; r < Y.rows(); ++r)
        for (Eigen::Index c = 0; c < Y.cols(); ++c) o(r, c) = Y(r, c);
    return out;
}

/// The stacked regressor of N samples: (N n, P), rows k n .. k n + n - 1 those of sample k.

py::list parameterNames(const Robot& r) {
    py::list names;
    for (int c = 0; c < parameterCount(*r.model); ++c) names.append(parameterName(*r.model, c));
    return names;
}

py::list parameterUnits(const Robot& r) {
    py::list units;
    for (int c = 0; c < parameterCount(*r.model); ++c) units.append(parameterUnit(*r.model, c));
    return units;
}

}  // namespace

void exposeRobotAlgorithms(py::module_& m) {
    py::class_<Robot>(m.attr("Robot"))
        .def("_inverse_dynamics_sample", &inverseDynamicsSample, py::arg("p"), py::arg("dp"), py::arg("ddp"),
             py::arg("matrices") = false, py::arg("check_limits") = true, py::arg("check") = true)
        .def("_inverse_dynamics_derivatives_sample", &inverseDynamicsDerivativesSample, py::arg("p"), py::arg("dp"),
             py::arg("ddp"))
        .def("_actuator_derivatives_sample", &actuatorDerivativesSample, py::arg("p"), py::arg("dp"), py::arg("ddp"))
        .def("_linearize", &linearizeSample, py::arg("p"), py::arg("dp"), py::arg("tau"),
             py::arg("output") = "acceleration", py::arg("compliance") = "rigid")
        .def("_forward_kinematics", &forwardKinematics, py::arg("u"), py::arg("tolerance") = 1e-9)
        .def("_state_from_actuators", &stateFromActuatorValues, py::arg("u"), py::arg("du"), py::arg("assembly_mode"))
        .def("_regressor_sample", &regressorSample, py::arg("p"), py::arg("dp"), py::arg("ddp"))
        .def("_parameter_names", &parameterNames)
        .def("_parameter_units", &parameterUnits)
        .def("_standard_parameters",
             [](const Robot& r) {
                 const ParameterVector pi = standardParameters(*r.model);
                 return toArray(std::vector<double>(pi.data(), pi.data() + pi.size()));
             })
        .def(
            "_with_payload",
            [](const Robot& r, double mass, const std::array<double, 2>& com, double inertia) {
                return Robot(withPayload(r.model->description, Payload{mass, inertia, Vector2(com[0], com[1])}));
            },
            py::arg("mass"), py::arg("com"), py::arg("inertia"));
}

}  // namespace nocdyn::python
