// The plug-in library: the two exported entry points for the `hertz` model
// (law in hertz.hpp, so the test can drive it without loading the library).
#include "hertz.hpp"

PLAB_PLUGIN(plab::add_contact_model<tutorial::Hertz>(r))
