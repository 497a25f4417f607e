// A minimal well-formed model to derive broken variants from.
#pragma once
#include <plab/contact_model.hpp>

struct SpringBase {
    static constexpr const char* doc = "test spring";
    static constexpr const char* timestep_rule = "sqrt(m/k)";
    static constexpr uint32_t range_kind = PLAB_RANGE_GAP;
    static constexpr uint32_t io = 0;  // reads and writes nothing optional
    static constexpr plab_property_desc properties[] = {
        plab::prop::number("k", "stiffness", "N/m", 1e5, 0.0, 1e12, PLAB_MIN_EXCLUSIVE, "spring")};
    static double activity_range(const double*) { return 0.0; }
    explicit SpringBase(const double* p) : k(p[0]) {}
    double k;
};
