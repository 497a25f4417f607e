#include "monitor/monitor_checkpoint.hpp"

namespace plab {

void save_stability(const StabilityBaseline& b, CheckpointWriter& out) {
    out.section("stability");
    for (double v : {b.balance, b.body, b.boundary, b.dissipated, b.stored, b.potential, b.max_work}) out.f64(v);
    out.vec(b.lo);
    out.vec(b.hi);
}

void load_stability(StabilityBaseline& b, CheckpointReader& in) {
    in.section("stability");
    for (double* v : {&b.balance, &b.body, &b.boundary, &b.dissipated, &b.stored, &b.potential, &b.max_work})
        *v = in.f64();
    b.lo = in.vec();
    b.hi = in.vec();
}

} // namespace plab
