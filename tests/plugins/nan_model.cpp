// A model whose force turns NaN once the overlap exceeds 1 mm.
#include "test_models.hpp"
#include <cmath>
struct NanModel : SpringBase {
    static constexpr const char* name = "nan_model";
    using SpringBase::SpringBase;
    void law(const plab::Contact& c) const {
        const double f = c.overlap() > 1e-3 ? std::nan("") : k * c.overlap();
        c.set_force(f * c.normal());
        c.set_stiffness(k);
    }
};
PLAB_PLUGIN(plab::add_contact_model<NanModel>(r))
