#include "app/pose.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/SVD>

#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/reactions.hpp"
#include "nocdyn/detail/index.hpp"

namespace nocdyn::app {

namespace {

/// Fraction of the joint's range [lower, upper] used on the side q is on (0 when unlimited).
double rangeUsed(const JointLimits& limits, double q) {
    const double bound = q >= 0.0 ? limits.upper : -limits.lower;
    return std::isfinite(bound) && bound > 0.0 ? std::abs(q) / bound : 0.0;
}

using detail::at;

PoseCompliance compliance(const Model& model, const Data& data, Observer& observer) {
    const StiffnessModel stiffness(model);
    StiffnessData K;
    if (const Status status = cartesianStiffness(model, stiffness, data, K); !status) {
        throw Error(describe(status, model));
    }
    if (const std::string w = contrastWarning(K); !w.empty()) observer.warning(w);
    LumpedModes modes;
    lumpedModes(model, data, K, modes);
    PoseCompliance out;
    if (model.task_dimension == 2) {
        // over the task coordinates x, y (theta moves no body and loads no limb: always free)
        TaskModes task;
        taskModes(model, data, K, modes, task);
        if (!(task.K.allFinite() && task.frequency.allFinite() && task.shape.allFinite())) {
            throw Error("the stiffness or the natural frequencies are not finite at this pose");
        }
        out.K = task.K;
        out.frequencies = task.frequency;
        out.mode_shapes = task.shape;
        // the free directions in x, y: the free space is theta's plus theirs, so its projection
        // on x, y spans them (free_directions - 1 of them)
        if (K.free_directions > 1) {
            const Eigen::MatrixXd projected = K.free.leftCols(K.free_directions).bottomRows(2);
            const Eigen::JacobiSVD<Eigen::MatrixXd> svd(projected, Eigen::ComputeFullU);
            for (int i = 0; i < K.free_directions - 1; ++i) {
                const Vector2 d = svd.matrixU().col(i);
                out.free_directions.emplace_back(d);
                out.free_descriptions.push_back(describeDirection(Vector3(0.0, d.x(), d.y())));
            }
        }
        out.first_frequency = task.frequency(0);
        return out;
    }
    if (!(K.K.allFinite() && modes.frequency.allFinite() && modes.shape.allFinite())) {
        throw Error("the stiffness or the natural frequencies are not finite at this pose");
    }
    out.K = reported(K.K);
    for (int i = 0; i < K.free_directions; ++i) {
        const Vector3 v = K.free.col(i);
        out.free_directions.emplace_back(reported(v));
        out.free_descriptions.push_back(describeDirection(v));
    }
    out.frequencies = modes.frequency;
    out.first_frequency = modes.frequency(0);
    Matrix3 shapes;
    for (int i = 0; i < 3; ++i) shapes.col(i) = reported(Vector3(modes.shape.col(i)));
    out.mode_shapes = shapes;
    if (model.description.hasElasticBody()) {
        ElastodynamicModes elastic;
        if (const Status status = elastodynamicModes(model, stiffness, data, elastic); !status) {
            throw Error(describe(status, model));
        }
        if (const std::string w = elastodynamicPrecisionWarning(elastic); !w.empty()) observer.warning(w);
        if (const std::string w = lumpedMismatchWarning(modes, elastic); !w.empty()) {
            observer.warning(w);
            out.first_frequency = elastic.frequency(0);
            out.first_frequency_model = FrequencyModel::elastodynamic;
        }
        out.elastodynamic_frequencies = elastic.frequency;
        out.elastodynamic_dofs = elastic.dofs;
    }
    return out;
}

}  // namespace

void validate(const PoseOptions& options) {
    requireIn(options.x, kLengthRange, "x");
    requireIn(options.y, kLengthRange, "y");
    if (!std::isnan(options.theta)) requireIn(options.theta, kAngleRange, "theta");
}

PoseResult runPose(const PoseOptions& options, Observer& observer) {
    validate(options);
    const Model model(loadRobot(options.robot));
    Data data(model);
    if (model.task_dimension == 3 && std::isnan(options.theta)) {
        throw OptionError("theta", "required: this robot's platform turns (give X Y THETA)");
    }
    if (model.task_dimension == 2 && !std::isnan(options.theta) && options.theta != 0.0) {
        throw OptionError("theta", "a two-DOF robot (motion: translation) has no theta: give X Y only");
    }
    TaskVector p_task(model.task_dimension);
    if (model.task_dimension == 3) {
        p_task << options.theta, options.x, options.y;
    } else {
        p_task << options.x, options.y;
    }
    const Pose p = poseOfTask(model, p_task);
    if (const Status status = inverseDynamics(model, data, p, Twist::Zero(), Twist::Zero()); !status) {
        throw Error(describe(status, model));
    }
    PoseResult out;
    out.robot = model.description.name;
    out.task_dimension = model.task_dimension;
    out.pose = userPose(p);
    const Status limits = checkJointLimits(model, data);
    out.within_limits = limits.ok();
    if (!limits) {
        out.limits = describe(limits, model);
        // far outside (more than 10 times the range): most likely a unit slip
        double worst = 0.0;
        for (int j = 0; j < model.limbs; ++j) {
            for (int k = 0; k < 3; ++k) {
                worst = std::max(worst, rangeUsed(model.limb[at(j)].limits[at(k)], data.limb[at(j)].q(k)));
            }
        }
        observer.warning(out.limits +
                         (worst > 10.0 ? " -- far outside the range: poses are in m and rad (5 mm is 0.005)" : ""));
    }
    for (int j = 0; j < model.limbs; ++j) {
        PoseLimb limb;
        limb.limb = j + 1;
        limb.name = model.description.limbs[at(j)].name;
        limb.type = model.description.limbs[at(j)].type();
        limb.q = data.limb[at(j)].q;
        for (int k = 0; k < 3; ++k) limb.revolute[at(k)] = model.limb[at(j)].type[at(k)] == JointType::revolute;
        limb.cond_J = data.limb[at(j)].cond;
        out.limbs.push_back(std::move(limb));
    }
    for (int a = 0; a < model.actuators; ++a) {
        const int j = model.actuator_limb[at(a)];
        const int k = model.actuator_joint[at(a)];
        out.actuators.push_back({a + 1, j + 1, k + 1, model.limb[at(j)].type[at(k)] == JointType::revolute, data.u(a),
                                 rangeUsed(model.limb[at(j)].limits[at(k)], data.u(a))});
    }
    // du = A xi_P = A S(c) dp/dt: the actuation map in the pose's own rates (eq. 5 generalised)
    const Eigen::MatrixXd A_pose = Eigen::MatrixXd(data.A) * platformTwistMap(p.tail<2>());
    // (a two-DOF robot: A S(c) E, its x and y columns)
    out.A = (A_pose * userToCoreMap()).leftCols(model.task_dimension);
    out.cond_A = data.cond_A;
    out.max_condition = model.max_condition;
    if (model.coordinates == Coordinates::actuators) {
        out.coordinates = "actuators";
        out.I = data.I;
    } else {
        out.coordinates = "platform";
        // (a two-DOF robot: E^T I E, over x and y)
        const Eigen::MatrixXd I_user = userToCoreMap().transpose() * Eigen::MatrixXd(data.I) * userToCoreMap();
        out.I = I_user.topLeftCorner(model.task_dimension, model.task_dimension);
    }
    out.tau = data.tau.head(model.actuators);
    // at rest (dp = ddp = 0) tau holds the pose against gravity; the reactions that go with it
    Reactions reactions;
    jointReactions(model, data, reactions);
    for (int j = 0; j < model.limbs; ++j) {
        for (int k = 0; k < 3; ++k) {
            out.reactions.push_back(
                {j + 1, k + 1, model.limb[at(j)].type[at(k)] == JointType::revolute, reactions.joint[at(j)][at(k)]});
        }
    }
    if (model.description.hasCompliance()) {
        if (model.task_dimension == 2 && model.description.hasElasticBody()) {
            throw Error(where(model.description, 0) +
                        "the elastic bodies of a two-DOF robot (motion: translation) are not modelled yet: remove "
                        "the file's elastic entries (joint stiffness is)");
        }
        out.compliance = compliance(model, data, observer);
    }
    return out;
}

}  // namespace nocdyn::app
