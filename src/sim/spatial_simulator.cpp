// Time integration of a spatial robot's forward dynamics (spatial_simulator.hpp).
#include "nocdyn/sim/spatial_simulator.hpp"

#include <array>
#include <utility>

#include "integrator.hpp"

namespace nocdyn::spatial {

namespace {

/// The spatial forward dynamics as the integrator's plant: x = [p; dp/dt], six coordinates
/// each (a translation robot's last three of each stay 0).
struct SpatialPlant {
    using State = std::array<double, 12>;
    explicit SpatialPlant(const Model& m) : model(m), data(model), scratch(model) {}
    SpatialPlant(SpatialPlant&& o) noexcept : model(std::move(o.model)), data(model), scratch(model) {}
    SpatialPlant(const SpatialPlant&) = delete;
    SpatialPlant& operator=(const SpatialPlant&) = delete;
    SpatialPlant& operator=(SpatialPlant&&) = delete;
    ~SpatialPlant() = default;

    Model model;
    Data data;     ///< every stage at the current time
    Data scratch;  ///< right-hand-side evaluations
    TaskVector p, dp, ddp;
    ActuatorVector force;

    [[nodiscard]] int actuators() const { return model.actuators; }
    void split(const State& x) {
        const int d = model.task_dimension;
        p.resize(d);
        dp.resize(d);
        for (int i = 0; i < d; ++i) {
            p(i) = x[static_cast<std::size_t>(i)];
            dp(i) = x[static_cast<std::size_t>(i) + 6];
        }
    }
    Status evaluate(Data& into, const State& x, const nocdyn::ActuatorVector& tau) {
        if (tau.size() != model.actuators) return {StatusCode::not_finite, -1, static_cast<double>(tau.size())};
        split(x);
        force = tau;
        return forwardDynamics(model, into, p, dp, force, ddp);
    }
    Status derivative(const State& x, const nocdyn::ActuatorVector& tau, State& dxdt) {
        if (const Status status = evaluate(scratch, x, tau); !status) return status;
        dxdt.fill(0.0);
        for (int i = 0; i < model.task_dimension; ++i) {
            dxdt[static_cast<std::size_t>(i)] = x[static_cast<std::size_t>(i) + 6];
            dxdt[static_cast<std::size_t>(i) + 6] = ddp(i);
        }
        return {};
    }
    Status current(const State& x, const nocdyn::ActuatorVector& tau) { return evaluate(data, x, tau); }
};

}  // namespace

struct Simulator::Impl : nocdyn::detail::Integrator<SpatialPlant> {
    Impl(const Model& m, const SimulatorOptions& o) : Integrator(SpatialPlant(m), o) {}
};

Simulator::Simulator(const Model& model, const SimulatorOptions& options)
    : impl_(std::make_unique<Impl>(model, options)) {
    (void)reset(model.home, TaskVector::Zero(model.task_dimension));
}

Simulator::~Simulator() = default;
Simulator::Simulator(Simulator&&) noexcept = default;
Simulator& Simulator::operator=(Simulator&&) noexcept = default;

Status Simulator::reset(const TaskVector& p, const TaskVector& dp, double t) {
    Impl& s = *impl_;
    const int d = s.plant.model.task_dimension;
    if (p.size() != d || dp.size() != d) return {StatusCode::not_finite, -1, static_cast<double>(p.size())};
    SpatialPlant::State x{};
    for (int i = 0; i < d; ++i) {
        x[static_cast<std::size_t>(i)] = p(i);
        x[static_cast<std::size_t>(i) + 6] = dp(i);
    }
    s.held.setZero();
    if (const Status status = s.plant.evaluate(s.plant.scratch, x, s.held); !status) return status;
    s.start(x, t);
    return s.evaluateCurrent();
}

void Simulator::setForces(const nocdyn::ActuatorVector& tau) { impl_->setForces(tau); }
void Simulator::setForces(ForceSignal forces) { impl_->setForces(std::move(forces)); }
Status Simulator::advance(double dt) { return impl_->advance(dt); }

double Simulator::time() const { return impl_->t; }
TaskVector Simulator::pose() const {
    const int d = impl_->plant.model.task_dimension;
    TaskVector p(d);
    for (int i = 0; i < d; ++i) p(i) = impl_->x[static_cast<std::size_t>(i)];
    return p;
}
TaskVector Simulator::poseRate() const {
    const int d = impl_->plant.model.task_dimension;
    TaskVector dp(d);
    for (int i = 0; i < d; ++i) dp(i) = impl_->x[static_cast<std::size_t>(i) + 6];
    return dp;
}
TaskVector Simulator::poseAcceleration() const { return impl_->plant.ddp; }
const Data& Simulator::data() const { return impl_->plant.data; }
const Model& Simulator::model() const { return impl_->plant.model; }
double Simulator::kineticEnergy() const { return spatial::kineticEnergy(impl_->plant.model, impl_->plant.data); }
double Simulator::potentialEnergy() const { return spatial::potentialEnergy(impl_->plant.model, impl_->plant.data); }
std::size_t Simulator::acceptedSteps() const { return impl_->accepted; }
std::size_t Simulator::rejectedSteps() const { return impl_->rejected; }
std::size_t Simulator::evaluations() const { return impl_->evaluations; }

}  // namespace nocdyn::spatial
