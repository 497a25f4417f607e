// `coordination_number`: a post-force pass that counts, per ball, the active
// contacts of every model (ball–ball and ball–wall). The smallest example of
// a pass with its own per-body field; the SPH passes follow the same pattern.
#include <plab/pass.hpp>

#include <algorithm>

namespace {

struct CoordinationNumber {
    static constexpr const char* name = "coordination_number";
    static constexpr const char* doc = "Number of active contacts per ball, after each force-displacement.";
    static constexpr uint32_t phase = PLAB_PHASE_POST_FORCE;
    static constexpr uint32_t stage = 0;
    static constexpr plab_field_desc fields[] = {plab::field_desc("coordination_number", "1", 0.0)};

    explicit CoordinationNumber(const double*) {}

    void run(const plab_pass_view& v) const {
        double* z = v.fields[0];
        std::fill(z, z + v.body_count, 0.0);
        for (uint32_t k = 0; k < v.contact_count; ++k) {
            z[v.contact_end1[k]] += 1.0;
            if (!v.contact_end2_is_wall[k]) z[v.contact_end2[k]] += 1.0;
        }
    }
};

} // namespace

PLAB_PLUGIN(plab::add_pass<CoordinationNumber>(r))
