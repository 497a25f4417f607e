// Mesh files written by the tests: binary STL, ASCII STL and OBJ of the
// same triangles, in a folder of their own (ctest runs test cases side by
// side, one process each: the folder's name carries the pid).
#pragma once

#include <plab_host/mass_properties.hpp>

#include <unistd.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace plab::testing_support {

inline std::filesystem::path mesh_dir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / ("plab_mesh_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return dir;
}

// 80-byte header (starting with "solid", as some exporters write it: the
// reader must go by the size), the count, then normal, 3 vertices and 2
// attribute bytes per triangle, little-endian float32.
inline std::string binary_stl(const std::vector<Triangle>& t, const std::string& header = "solid written by a test") {
    std::string out = header;
    out.resize(80, ' ');
    auto u32 = [&](std::uint32_t v) { for (int k = 0; k < 4; ++k) out.push_back(char((v >> (8 * k)) & 0xff)); };
    auto f32 = [&](double x) {
        const float f = float(x);
        std::uint32_t bits;
        std::memcpy(&bits, &f, 4);
        u32(bits);
    };
    u32(std::uint32_t(t.size()));
    for (const Triangle& tri : t) {
        for (int c = 0; c < 3; ++c) f32(0.0);
        for (const Vec& v : tri)
            for (int c = 0; c < 3; ++c) f32(v[c]);
        out += std::string(2, '\0');
    }
    return out;
}

inline std::string ascii_stl(const std::vector<Triangle>& t, const char* eol = "\n") {
    std::ostringstream s;
    s.precision(17);
    s << "solid test" << eol;
    for (const Triangle& tri : t) {
        s << "  facet normal 0 0 0" << eol << "    outer loop" << eol;
        for (const Vec& v : tri) s << "      vertex " << v.x() << " " << v.y() << " " << v.z() << eol;
        s << "    endloop" << eol << "  endfacet" << eol;
    }
    s << "endsolid test" << eol;
    return s.str();
}

inline void write_file(const std::filesystem::path& p, const std::string& bytes) {
    std::ofstream f(p, std::ios::binary);
    f << bytes;
}

// The unit cube [0, 1]^3: its 8 corners, 6 quads (outward by the right-hand
// rule), and the 12 triangles a fan of each quad from its first corner makes.
inline std::vector<Vec> cube_corners() {
    return {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
}
inline std::vector<std::array<int, 4>> cube_quads() {
    return {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
}
inline std::vector<Triangle> cube_triangles(double side = 1.0) {
    const auto v = cube_corners();
    std::vector<Triangle> t;
    for (const auto& q : cube_quads()) {
        t.push_back({side * v[q[0]], side * v[q[1]], side * v[q[2]]});
        t.push_back({side * v[q[0]], side * v[q[2]], side * v[q[3]]});
    }
    return t;
}

} // namespace plab::testing_support
