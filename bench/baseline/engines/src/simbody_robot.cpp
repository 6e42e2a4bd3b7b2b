// Independent Simbody model of the 3-PRR planar parallel robot. See the header for the model.
//
// Nothing from nocdyn's kinematics or dynamics is used here: the geometry of the reference
// posture (and an analytic seed for the Assembler, used only when continuation from the
// previous sample fails) is computed in this file from the robot parameters alone.
#include "nocdyn/prr3/simbody_robot.hpp"

#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>

#include <Eigen/LU>
#include <Simbody.h>

#include "nocdyn/error.hpp"
#include "plant_integration.hpp"

namespace nocdyn::prr3 {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Tolerances of the position/velocity solves: constraint errors are lengths [m]
// (and lengths times the system time scale for velocities). Far below the 1e-9 relative
// accuracy the golden files need, a little above what double precision can reach.
constexpr double kAssemblyTolerance = 1e-12;
constexpr double kProjectAccuracy = 1e-14;

// ---------------------------------------------------------------------------------
// Geometry (shared/model-notes.md), computed here from the robot parameters only.
// ---------------------------------------------------------------------------------
struct Geometry {
    double R = 0.0;                         // base circumradius b/sqrt3
    double r = 0.0;                         // platform circumradius a/sqrt3
    double l = 0.0;                         // link length
    double phi_a_ref = 0.0;                 // link angle from e_j at the reference posture
    std::array<double, 3> phi{};            // slider directions
    std::array<Eigen::Vector2d, 3> e;       // e_j
    std::array<Eigen::Vector2d, 3> n;       // E e_j: inward normal of L_j
    std::array<Eigen::Vector2d, 3> B;       // B_j
    std::array<Eigen::Vector2d, 3> A_ref;   // A_j at the reference posture
    std::array<Eigen::Vector2d, 3> M_plat;  // M_j in the platform frame (origin C)
};

Geometry makeGeometry(const io::RobotParameters& p) {
    nocdyn::io::validate(p);
    Geometry g;
    g.R = p.base_side / std::sqrt(3.0);
    g.r = p.platform_side / std::sqrt(3.0);
    g.l = p.link_length;
    const double d_ref = 0.5 * (g.R - g.r);
    if (!(d_ref > 0.0 && d_ref < g.l)) {
        std::ostringstream msg;
        msg << "Simbody model: robot '" << p.name
            << "' cannot be assembled at its reference posture: (R - r)/2 = " << d_ref
            << " m must lie in (0, l = " << g.l << " m)";
        throw Error(msg.str());
    }
    g.phi_a_ref = std::asin(d_ref / g.l);
    for (int j = 0; j < 3; ++j) {
        const double phi = (j == 0) ? 0.0 : (j == 1 ? 2.0 * kPi / 3.0 : -2.0 * kPi / 3.0);
        g.phi[j] = phi;
        g.e[j] = {std::cos(phi), std::sin(phi)};
        g.n[j] = {-std::sin(phi), std::cos(phi)};
        g.B[j] = g.R * Eigen::Vector2d(std::cos(phi - kPi / 6.0), std::sin(phi - kPi / 6.0));
        g.M_plat[j] = g.r * Eigen::Vector2d(std::cos(phi - kPi / 6.0), std::sin(phi - kPi / 6.0));
        const Eigen::Vector2d link(std::cos(g.phi_a_ref + phi), std::sin(g.phi_a_ref + phi));
        g.A_ref[j] = g.M_plat[j] - g.l * link;
    }
    return g;
}

/// Free coordinates of the mechanism: slider displacements and link (pin) angles.
struct Seed {
    std::array<double, 3> slider{};
    std::array<double, 3> pin{};
};

Seed referenceSeed(const Geometry& g) {
    Seed s;
    s.pin.fill(g.phi_a_ref);
    return s;
}

/// Closed-form inverse displacement of one pose on the intended branch. Used to report a
/// pose outside the workspace and to re-seed the Assembler if continuation fails; the
/// values Simbody returns are always its own assembled solution.
Seed analyticSeed(const Geometry& g, const Eigen::Vector3d& pose, double t) {
    Seed s;
    const Eigen::Vector2d c(pose[1], pose[2]);
    for (int j = 0; j < 3; ++j) {
        const double ang = pose[0] + g.phi[j] - kPi / 6.0;
        const Eigen::Vector2d M = c + g.r * Eigen::Vector2d(std::cos(ang), std::sin(ang));
        const double d = g.n[j].dot(M - g.B[j]);
        if (!(d > 0.0 && d < g.l)) {
            std::ostringstream msg;
            msg << "Simbody model: pose [theta=" << pose[0] << " rad, x=" << pose[1] << " m, y=" << pose[2]
                << " m] at t=" << t << " s is outside the workspace: limb " << (j + 1)
                << " needs 0 < d^M < l but d^M = " << d << " m (l = " << g.l << " m)";
            throw Error(msg.str());
        }
        const double phi_a = std::asin(d / g.l);
        const Eigen::Vector2d A = M - g.l * Eigen::Vector2d(std::cos(phi_a + g.phi[j]), std::sin(phi_a + g.phi[j]));
        s.slider[j] = g.e[j].dot(A - g.A_ref[j]);
        s.pin[j] = phi_a;
    }
    return s;
}

SimTK::Vec3 toVec3(const Eigen::Vector2d& v) { return {v.x(), v.y(), 0.0}; }

// ---------------------------------------------------------------------------------
// Motions
// ---------------------------------------------------------------------------------

/// Platform pose prescribed at the position level: from a trajectory at the state's time,
/// or (trajectory == nullptr) a fixed pose, rate and acceleration.
class PlatformMotion final : public SimTK::Motion::Custom::Implementation {
public:
    const PoseTrajectory* trajectory = nullptr;
    Eigen::Vector3d pose = Eigen::Vector3d::Zero();
    Eigen::Vector3d rate = Eigen::Vector3d::Zero();
    Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();

    SimTK::Motion::Level getLevel(const SimTK::State&) const override { return SimTK::Motion::Position; }
    // The Planar mobilizer's q are [rotation about z, x, y] = [theta, x, y], qdot = u.
    void calcPrescribedPosition(const SimTK::State& s, int nq, SimTK::Real* q) const override {
        write(s.getTime(), 0, nq, q);
    }
    void calcPrescribedPositionDot(const SimTK::State& s, int nq, SimTK::Real* qdot) const override {
        write(s.getTime(), 1, nq, qdot);
    }
    void calcPrescribedPositionDotDot(const SimTK::State& s, int nq, SimTK::Real* qdotdot) const override {
        write(s.getTime(), 2, nq, qdotdot);
    }

private:
    void write(double t, int order, int n, SimTK::Real* out) const {
        Eigen::Vector3d p = pose;
        Eigen::Vector3d dp = rate;
        Eigen::Vector3d ddp = acceleration;
        if (trajectory != nullptr) trajectory->evaluate(t, p, dp, ddp);
        const Eigen::Vector3d& v = order == 0 ? p : (order == 1 ? dp : ddp);
        for (int i = 0; i < n && i < 3; ++i) out[i] = v[i];
    }
};

/// A slider's acceleration prescribed to a value set from outside (pass 2).
class SliderAcceleration final : public SimTK::Motion::Custom::Implementation {
public:
    double udot = 0.0;

    SimTK::Motion::Level getLevel(const SimTK::State&) const override { return SimTK::Motion::Acceleration; }
    void calcPrescribedAcceleration(const SimTK::State&, int nu, SimTK::Real* out) const override {
        for (int i = 0; i < nu; ++i) out[i] = udot;
    }
};

double wrapAngle(double a) { return std::remainder(a, 2.0 * kPi); }

}  // namespace

// ---------------------------------------------------------------------------------
// The model
// ---------------------------------------------------------------------------------
class SimbodyRobot::Impl {
public:
    explicit Impl(const io::RobotParameters& p);

    io::RobotParameters params;
    Geometry geo;

    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter;
    SimTK::GeneralForceSubsystem forces;
    SimTK::Force::DiscreteForces actuators;

    std::array<SimTK::MobilizedBody::Slider, 3> sliders;
    std::array<SimTK::MobilizedBody::Pin, 3> links;
    SimTK::MobilizedBody::Planar platform;

    PlatformMotion* platform_motion = nullptr;  // owned by platform_motion_handle
    SimTK::Motion::Custom platform_motion_handle;
    std::array<SliderAcceleration*, 3> slider_motion{};  // owned by the handles
    std::array<SimTK::Motion::Custom, 3> slider_motion_handles;

    SimTK::State pose_driven;    // pass 1: platform prescribed, sliders free
    SimTK::State slider_driven;  // pass 2: slider accelerations prescribed, platform free
    SimTK::State plant;          // no prescribed motion, actuator forces applied
    std::unique_ptr<SimTK::Assembler> assembler;
    std::unique_ptr<SimTK::RungeKuttaMersonIntegrator> integrator;
    validation::detail::PlantIntegration run;

    /// The plant's current state (the integrator's while it runs).
    [[nodiscard]] const SimTK::State& current() const;

    Seed last_solution;  // continuation seed for the next assembly

    // Indices of the mobilities in Simbody's u (and q) vectors.
    std::array<int, 3> slider_u{};
    std::array<int, 3> link_u{};
    int platform_u = 0;
    int platform_q = 0;

    Seed readSeed(const SimTK::State& s) const;
    void writeSeed(SimTK::State& s, const Seed& seed) const;
    Eigen::Vector3d readPose(const SimTK::State& s) const;
    /// Assembles pose_driven at time t for the platform pose the Motion prescribes, which
    /// must equal `expected`; projects q and u. Throws nocdyn::Error on failure.
    void assemblePoseDriven(double t, const Eigen::Vector3d& expected, const Seed& seed);
    /// Sets the prescribed q and u, then Newton-projects the free q and u onto the
    /// constraint manifolds, with one extra forced iteration each so that the constraint
    /// errors end at round-off level rather than just below the required accuracy.
    void projectTight(SimTK::State& s) const;
    /// One attempt (Newton projection only, or the Assembler then a projection); returns an
    /// empty string on success, else why it failed.
    std::string tryAssemble(const Eigen::Vector3d& expected, bool use_assembler);

    // How the assemblies were obtained (diagnostics).
    long by_projection = 0, by_assembler = 0, by_analytic_seed = 0;
};

SimbodyRobot::Impl::Impl(const io::RobotParameters& p)
    : params(p), geo(makeGeometry(p)), matter(system), forces(system), actuators(forces, matter) {
    using namespace SimTK;
    // Sliders translate only: mass, no rotational inertia.
    const Body::Rigid slider_body(MassProperties(p.slider_mass, Vec3(0), Inertia(0)));
    // Link frame: origin A_j, x along A_j -> M_j; c.o.m. at l_c on x. Central inertia
    // (isotropic; only the z component matters in the plane) shifted to the origin A_j.
    const Vec3 link_com(p.link_com, 0, 0);
    const Body::Rigid link_body(
        MassProperties(p.link_mass, link_com, Inertia(p.link_inertia).shiftFromMassCenter(-link_com, p.link_mass)));
    // Platform frame: origin C (its c.o.m.), x rotated by theta.
    const Body::Rigid platform_body(MassProperties(p.platform_mass, Vec3(0), Inertia(p.platform_inertia)));

    for (int j = 0; j < 3; ++j) {
        // F frame on Ground at A_j(ref), x along e_j: slider q = displacement of A_j along
        // e_j from the reference posture = u_j.
        const Transform X_GF(Rotation(geo.phi[j], ZAxis), toVec3(geo.A_ref[j]));
        sliders[j] = MobilizedBody::Slider(matter.Ground(), X_GF, slider_body, Transform());
        // Pin at A_j about z; its angle is the link angle measured from e_j (phi_Aj).
        links[j] = MobilizedBody::Pin(sliders[j], Transform(), link_body, Transform());
        links[j].setDefaultAngle(geo.phi_a_ref);
    }
    platform = MobilizedBody::Planar(matter.Ground(), Transform(), platform_body, Transform());

    // Loop closures: M_j on the platform stays on the z-line through the link tip.
    for (int j = 0; j < 3; ++j) {
        Constraint::PointOnLine(links[j], UnitVec3(ZAxis), Vec3(geo.l, 0, 0), platform, toVec3(geo.M_plat[j]));
    }

    platform_motion = new PlatformMotion();
    platform_motion_handle = Motion::Custom(platform, platform_motion);
    platform_motion_handle.setDisabledByDefault(true);
    for (int j = 0; j < 3; ++j) {
        slider_motion[j] = new SliderAcceleration();
        slider_motion_handles[j] = Motion::Custom(sliders[j], slider_motion[j]);
        slider_motion_handles[j].setDisabledByDefault(true);
    }

    system.realizeTopology();
    const State& def = system.getDefaultState();

    pose_driven = def;
    platform_motion_handle.enable(pose_driven);
    system.realize(pose_driven, Stage::Instance);

    slider_driven = def;
    for (auto& m : slider_motion_handles) m.enable(slider_driven);
    system.realize(slider_driven, Stage::Instance);

    plant = def;
    system.realize(plant, Stage::Instance);

    for (int j = 0; j < 3; ++j) {
        slider_u[j] = sliders[j].getFirstUIndex(def);
        link_u[j] = links[j].getFirstUIndex(def);
    }
    platform_u = platform.getFirstUIndex(def);
    platform_q = platform.getFirstQIndex(def);
    if (def.getNU() != 9 || def.getNQ() != 9) {
        throw Error("Simbody model: expected 9 mobilities, got " + std::to_string(def.getNU()));
    }

    assembler = std::make_unique<Assembler>(system);
    assembler->setAccuracy(kAssemblyTolerance).setErrorTolerance(kAssemblyTolerance);

    integrator = std::make_unique<RungeKuttaMersonIntegrator>(system);

    last_solution = referenceSeed(geo);
}

Seed SimbodyRobot::Impl::readSeed(const SimTK::State& s) const {
    Seed seed;
    for (int j = 0; j < 3; ++j) {
        seed.slider[j] = sliders[j].getOneQ(s, 0);
        seed.pin[j] = links[j].getOneQ(s, 0);
    }
    return seed;
}

void SimbodyRobot::Impl::writeSeed(SimTK::State& s, const Seed& seed) const {
    for (int j = 0; j < 3; ++j) {
        sliders[j].setOneQ(s, 0, seed.slider[j]);
        links[j].setOneQ(s, 0, seed.pin[j]);
    }
}

Eigen::Vector3d SimbodyRobot::Impl::readPose(const SimTK::State& s) const {
    const SimTK::Vector& q = s.getQ();
    const int i = platform_q;  // Planar q = [theta, x, y]
    return {q[i], q[i + 1], q[i + 2]};
}

void SimbodyRobot::Impl::projectTight(SimTK::State& s) const {
    using SimTK::ProjectOptions;
    ProjectOptions options(kProjectAccuracy);
    options.setOption(ProjectOptions::ForceFullNewton);
    ProjectOptions forced(options);
    forced.setOption(ProjectOptions::ForceProjection);
    SimTK::Vector no_error_estimate;
    SimTK::ProjectResults results;
    system.realize(s, SimTK::Stage::Time);
    system.prescribeQ(s);
    system.realize(s, SimTK::Stage::Position);
    system.projectQ(s, no_error_estimate, options, results);  // throws if it cannot converge
    system.projectQ(s, no_error_estimate, forced, results);
    system.prescribeU(s);
    system.realize(s, SimTK::Stage::Velocity);
    // Velocity constraints are linear in u: one full Newton step solves them to round-off.
    system.projectU(s, no_error_estimate, forced, results);
}

std::string SimbodyRobot::Impl::tryAssemble(const Eigen::Vector3d& expected, bool use_assembler) {
    try {
        if (use_assembler) assembler->assemble(pose_driven);
        projectTight(pose_driven);
    } catch (const std::exception& ex) {
        return std::string("Simbody assembly failed: ") + ex.what();
    }
    const Eigen::Vector3d got = readPose(pose_driven);
    if ((got - expected).cwiseAbs().maxCoeff() > 1e-12) {
        std::ostringstream msg;
        msg << "assembled platform pose [" << got.transpose() << "] differs from the requested ["
            << expected.transpose() << "]";
        return msg.str();
    }
    // Intended branch: phi_A in (0, pi/2), i.e. M_j inside the base and ahead of A_j along e_j.
    for (int j = 0; j < 3; ++j) {
        const double phi_a = wrapAngle(links[j].getOneQ(pose_driven, 0));
        if (!(phi_a > 0.0 && phi_a < 0.5 * kPi)) {
            std::ostringstream msg;
            msg << "assembly landed on the wrong branch: limb " << (j + 1) << " has phi_A = " << phi_a
                << " rad, outside (0, pi/2)";
            return msg.str();
        }
    }
    return {};
}

void SimbodyRobot::Impl::assemblePoseDriven(double t, const Eigen::Vector3d& expected, const Seed& seed) {
    // Checks the workspace first (clear error naming the limb).
    const Seed analytic = analyticSeed(geo, expected, t);
    // 1) Newton projection from the continuation seed (cheap; enough between close samples),
    // 2) the Assembler from the same seed, 3) the Assembler seeded on the intended branch.
    pose_driven.setTime(t);
    writeSeed(pose_driven, seed);
    std::string why = tryAssemble(expected, false);
    if (why.empty()) {
        ++by_projection;
    } else {
        pose_driven.setTime(t);
        writeSeed(pose_driven, seed);
        const std::string why1 = tryAssemble(expected, true);
        if (why1.empty()) {
            ++by_assembler;
        } else {
            pose_driven.setTime(t);
            writeSeed(pose_driven, analytic);
            const std::string why2 = tryAssemble(expected, true);
            if (!why2.empty()) {
                std::ostringstream msg;
                msg << "Simbody model: cannot assemble at t=" << t << " s, pose [" << expected.transpose()
                    << "]: " << why1 << "; re-seeded on the intended branch: " << why2;
                throw Error(msg.str());
            }
            ++by_analytic_seed;
        }
    }
    last_solution = readSeed(pose_driven);
}

// ---------------------------------------------------------------------------------
// Public interface
// ---------------------------------------------------------------------------------
SimbodyRobot::SimbodyRobot(const io::RobotParameters& robot) : impl_(std::make_unique<Impl>(robot)) {
    // The model must assemble at the reference posture (and the plant starts there).
    resetPlant(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
}
SimbodyRobot::~SimbodyRobot() = default;
SimbodyRobot::SimbodyRobot(SimbodyRobot&&) noexcept = default;
SimbodyRobot& SimbodyRobot::operator=(SimbodyRobot&&) noexcept = default;

std::vector<EngineSample> SimbodyRobot::inverseDynamics(const PoseTrajectory& trajectory,
                                                        const std::vector<double>& times) {
    using namespace SimTK;
    Impl& m = *impl_;
    std::vector<EngineSample> out;
    out.reserve(times.size());

    m.platform_motion->trajectory = &trajectory;
    struct Reset {  // never leave a dangling trajectory pointer behind
        PlatformMotion* motion;
        ~Reset() { motion->trajectory = nullptr; }
    } reset{m.platform_motion};

    // Continuation: each assembly starts from the previous solution, extrapolated to second
    // order in time (the first from the reference posture).
    Seed q_prev = referenceSeed(m.geo), u_prev, a_prev;
    double t_prev = 0.0;
    bool have_prev = false;
    Vector motion_forces;
    for (double t : times) {
        Eigen::Vector3d p, dp, ddp;
        trajectory.evaluate(t, p, dp, ddp);

        // Pass 1: platform prescribed; Simbody finds the sliders' q, u and udot.
        Seed seed = q_prev;
        if (have_prev) {
            const double h = t - t_prev;
            for (int j = 0; j < 3; ++j) {
                seed.slider[j] += h * u_prev.slider[j] + 0.5 * h * h * a_prev.slider[j];
                seed.pin[j] += h * u_prev.pin[j] + 0.5 * h * h * a_prev.pin[j];
            }
        }
        m.assemblePoseDriven(t, p, seed);
        m.system.realize(m.pose_driven, Stage::Acceleration);
        q_prev = m.last_solution;
        for (int j = 0; j < 3; ++j) {
            u_prev.slider[j] = m.sliders[j].getOneU(m.pose_driven, 0);
            u_prev.pin[j] = m.links[j].getOneU(m.pose_driven, 0);
            a_prev.slider[j] = m.sliders[j].getOneUDot(m.pose_driven, 0);
            a_prev.pin[j] = m.links[j].getOneUDot(m.pose_driven, 0);
        }
        t_prev = t;
        have_prev = true;

        EngineSample s;
        s.t = t;
        s.pose = m.readPose(m.pose_driven);
        for (int j = 0; j < 3; ++j) {
            s.u[j] = m.sliders[j].getOneQ(m.pose_driven, 0);
            s.du[j] = m.sliders[j].getOneU(m.pose_driven, 0);
            s.ddu[j] = m.sliders[j].getOneUDot(m.pose_driven, 0);
        }
        s.kinetic = m.matter.calcKineticEnergy(m.pose_driven);

        // Pass 2: the same q and u, slider accelerations prescribed, platform free and
        // unforced; the actuator forces are minus the prescribed-motion reactions.
        m.slider_driven.setTime(t);
        m.slider_driven.updQ() = m.pose_driven.getQ();
        m.slider_driven.updU() = m.pose_driven.getU();
        for (int j = 0; j < 3; ++j) m.slider_motion[j]->udot = s.ddu[j];
        m.system.realize(m.slider_driven, Stage::Acceleration);
        m.matter.findMotionForces(m.slider_driven, motion_forces);
        for (int j = 0; j < 3; ++j) s.tau[j] = -motion_forces[m.slider_u[j]];

        // Consistency: pass 2 must reproduce the prescribed platform acceleration.
        const Vector& udot = m.slider_driven.getUDot();
        const Eigen::Vector3d ddp2(udot[m.platform_u], udot[m.platform_u + 1], udot[m.platform_u + 2]);
        if ((ddp2 - ddp).norm() > 1e-6 * (1.0 + ddp.norm())) {
            std::ostringstream msg;
            msg << "Simbody model: at t=" << t << " s the slider-driven pass gives platform "
                << "acceleration [" << ddp2.transpose() << "] instead of [" << ddp.transpose() << "]";
            throw Error(msg.str());
        }
        out.push_back(s);
    }
    return out;
}

Eigen::Matrix3d SimbodyRobot::jointSpaceInertia(const Eigen::Vector3d& pose) {
    using namespace SimTK;
    Impl& m = *impl_;
    m.platform_motion->trajectory = nullptr;
    m.platform_motion->pose = pose;
    m.platform_motion->rate.setZero();
    m.platform_motion->acceleration.setZero();
    m.assemblePoseDriven(0.0, pose, referenceSeed(m.geo));
    m.system.realize(m.pose_driven, Stage::Position);

    Matrix M, G;
    m.matter.calcM(m.pose_driven, M);  // 9 x 9
    m.matter.calcG(m.pose_driven, G);  // 6 x 9: the loop-closure constraints
    if (G.nrow() != 6 || G.ncol() != 9) {
        throw Error("Simbody model: unexpected constraint Jacobian size");
    }
    // N: du -> Simbody's u. Slider columns are unit; the other six u's solve G u = 0.
    std::array<int, 6> free_u{};
    for (int j = 0; j < 3; ++j) {
        free_u[j] = m.link_u[j];
        free_u[3 + j] = m.platform_u + j;
    }
    Eigen::Matrix<double, 6, 6> Gf;
    Eigen::Matrix<double, 6, 3> Gs;
    for (int r = 0; r < 6; ++r) {
        for (int c = 0; c < 6; ++c) Gf(r, c) = G(r, free_u[c]);
        for (int c = 0; c < 3; ++c) Gs(r, c) = G(r, m.slider_u[c]);
    }
    const Eigen::Matrix<double, 6, 3> X = Gf.fullPivLu().solve(-Gs);
    Eigen::Matrix<double, 9, 3> N = Eigen::Matrix<double, 9, 3>::Zero();
    for (int c = 0; c < 3; ++c) {
        N(m.slider_u[c], c) = 1.0;
        for (int r = 0; r < 6; ++r) N(free_u[r], c) = X(r, c);
    }
    Eigen::Matrix<double, 9, 9> Me;
    for (int r = 0; r < 9; ++r)
        for (int c = 0; c < 9; ++c) Me(r, c) = M(r, c);
    return N.transpose() * Me * N;
}

void SimbodyRobot::resetPlant(const Eigen::Vector3d& pose, const Eigen::Vector3d& pose_rate) {
    using namespace SimTK;
    Impl& m = *impl_;
    m.platform_motion->trajectory = nullptr;
    m.platform_motion->pose = pose;
    m.platform_motion->rate = pose_rate;
    m.platform_motion->acceleration.setZero();
    m.assemblePoseDriven(0.0, pose, referenceSeed(m.geo));

    m.plant.setTime(0.0);
    m.plant.updQ() = m.pose_driven.getQ();
    m.plant.updU() = m.pose_driven.getU();
    m.actuators.clearAllMobilityForces(m.plant);
    m.run.reset();
    m.system.realize(m.plant, Stage::Velocity);
}

void SimbodyRobot::setActuatorForces(const Eigen::Vector3d& tau) {
    Impl& m = *impl_;
    SimTK::State& s = m.run.forceState(*m.integrator, m.plant);
    // The slider's mobility force does power f u_j: it is the actuator force along e_j.
    for (int j = 0; j < 3; ++j) {
        m.actuators.setOneMobilityForce(s, m.sliders[j], SimTK::MobilizerUIndex(0), tau[j]);
    }
    m.run.forcesChanged(*m.integrator);
}

void SimbodyRobot::setIntegratorAccuracy(double accuracy) {
    impl_->run.setAccuracy(accuracy, *impl_->integrator, impl_->plant);
}

void SimbodyRobot::advance(double dt) {
    Impl& m = *impl_;
    validation::detail::advancePlant(*m.integrator, m.plant, m.run, dt);
}

const SimTK::State& SimbodyRobot::Impl::current() const { return run.current(*integrator, plant); }

double SimbodyRobot::time() const { return impl_->current().getTime(); }

Eigen::Vector3d SimbodyRobot::u() const {
    const SimTK::State& s = impl_->current();
    Eigen::Vector3d v;
    for (int j = 0; j < 3; ++j) v[j] = impl_->sliders[j].getOneQ(s, 0);
    return v;
}

Eigen::Vector3d SimbodyRobot::du() const {
    const SimTK::State& s = impl_->current();
    Eigen::Vector3d v;
    for (int j = 0; j < 3; ++j) v[j] = impl_->sliders[j].getOneU(s, 0);
    return v;
}

Eigen::Vector3d SimbodyRobot::pose() const { return impl_->readPose(impl_->current()); }

Eigen::Vector3d SimbodyRobot::poseRate() const {
    const SimTK::Vector& u = impl_->current().getU();
    const int i = impl_->platform_u;
    return {u[i], u[i + 1], u[i + 2]};
}

double SimbodyRobot::kineticEnergy() const {
    const SimTK::State& s = impl_->current();
    impl_->system.realize(s, SimTK::Stage::Velocity);
    return impl_->matter.calcKineticEnergy(s);
}

}  // namespace nocdyn::prr3
