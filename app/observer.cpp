#include "app/observer.hpp"

namespace nocdyn::app {

void Observer::progress(double /*done*/, double /*total*/, std::string_view /*unit*/) {}
void Observer::step(std::string_view /*what*/, int /*index*/, int /*total*/) {}
void Observer::warning(std::string_view /*text*/) {}
bool Observer::stopRequested() { return false; }

Observer& silent() {
    // stateless: one shared instance serves every thread
    static Observer nothing;
    return nothing;
}

Meter::Meter(Observer& observer, double total, std::string_view unit)
    : observer_(&observer), total_(total), unit_(unit) {}

void Meter::report(double done) {
    observer_->progress(done, total_, unit_);
    stopIfRequested(*observer_);
}

void stopIfRequested(Observer& observer) {
    if (observer.stopRequested()) throw Cancelled();
}

}  // namespace nocdyn::app
