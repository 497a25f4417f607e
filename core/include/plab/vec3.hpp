// A minimal 3-vector for plug-in authors: header-only, no dependency, so
// that no library type crosses the plug-in boundary. In 2D the z component
// is zero and rotations are about z.
#ifndef PLAB_VEC3_HPP
#define PLAB_VEC3_HPP

#include <cmath>

namespace plab {

struct Vec3 {
    double x = 0, y = 0, z = 0;

    Vec3& operator+=(const Vec3& o) { x += o.x; y += o.y; z += o.z; return *this; }
    Vec3& operator-=(const Vec3& o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
    Vec3& operator*=(double s) { x *= s; y *= s; z *= s; return *this; }
};

inline Vec3 operator+(Vec3 a, const Vec3& b) { return a += b; }
inline Vec3 operator-(Vec3 a, const Vec3& b) { return a -= b; }
inline Vec3 operator-(const Vec3& a) { return {-a.x, -a.y, -a.z}; }
inline Vec3 operator*(Vec3 a, double s) { return a *= s; }
inline Vec3 operator*(double s, Vec3 a) { return a *= s; }
inline Vec3 operator/(Vec3 a, double s) { return a *= (1.0 / s); }
inline double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }

// v turned into the plane normal to the unit vector n: its component along
// n projected out and its magnitude restored (PFC's rotation of a stored
// shear force with the contact plane). A zero vector stays zero; one with
// nothing left in the plane becomes zero. Written as choices between
// values, not branches, so that a loop over contacts vectorises. The host
// applies it to the history a model declares tangential (abi.h,
// PLAB_HISTORY_TANGENTIAL).
inline Vec3 rotate_into_plane(const Vec3& v, const Vec3& n) {
    const double mag2 = dot(v, v);
    const Vec3 t = v - dot(v, n) * n;
    const double tmag2 = dot(t, t);
    const Vec3 turned = t * std::sqrt(mag2 / tmag2);  // (not finite when tmag2 is 0: then not used)
    const bool zero = mag2 == 0.0, in_plane = tmag2 > 0.0;
    return {zero ? v.x : in_plane ? turned.x : 0.0, zero ? v.y : in_plane ? turned.y : 0.0,
            zero ? v.z : in_plane ? turned.z : 0.0};
}

} // namespace plab

#endif // PLAB_VEC3_HPP
