// Mass properties of rigid-body shapes (plab_host/mass_properties.hpp)
// against their closed forms: the analytic shapes, a box and a sphere as
// triangle meshes, two overlapping spheres and discs (the lens volume), and
// the principal frame of a turned tensor.
#include <plab_host/mass_properties.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

using namespace plab;

namespace {

// the box [-a, a] as 12 outward triangles
std::vector<Triangle> box_mesh(const Vec& a, const Vec& offset) {
    std::vector<Vec> v;
    for (int i = 0; i < 8; ++i)
        v.push_back(offset + Vec((i & 1 ? 1 : -1) * a.x(), (i & 2 ? 1 : -1) * a.y(), (i & 4 ? 1 : -1) * a.z()));
    const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    std::vector<Triangle> t;
    for (const auto& f : faces) {
        t.push_back({v[f[0]], v[f[1]], v[f[2]]});
        t.push_back({v[f[0]], v[f[2]], v[f[3]]});
    }
    return t;
}

// a UV sphere of radius r with n bands, outward
std::vector<Triangle> sphere_mesh(double r, int n) {
    auto at = [&](int i, int j) {
        const double th = M_PI * i / n, ph = 2 * M_PI * j / (2 * n);
        return Vec(r * std::sin(th) * std::cos(ph), r * std::sin(th) * std::sin(ph), r * std::cos(th));
    };
    std::vector<Triangle> t;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < 2 * n; ++j) {
            const Vec a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
            if (i > 0) t.push_back({a, b, d});
            if (i < n - 1) t.push_back({b, c, d});
        }
    return t;
}

// the volume of two spheres of radius r whose centres are d apart (r < d < 2r), and their lens
double two_sphere_volume(double r, double d) {
    const double lens = M_PI * (4 * r + d) * (2 * r - d) * (2 * r - d) / 12;
    return 2 * (4.0 / 3.0) * M_PI * r * r * r - lens;
}
double two_disc_area(double r, double d) {
    const double lens = 2 * r * r * std::acos(d / (2 * r)) - 0.5 * d * std::sqrt(4 * r * r - d * d);
    return 2 * M_PI * r * r - lens;
}

} // namespace

TEST_CASE("mass properties of the analytic shapes are their closed forms", "[rigid][mass]") {
    const MassProperties s = sphere_properties(0.5);
    CHECK(s.volume == Approx(M_PI / 6));
    CHECK(s.inertia(0, 0) == Approx(0.4 * s.volume * 0.25));
    const MassProperties b = box_properties({0.5, 1.0, 1.5});  // 1 x 2 x 3
    CHECK(b.volume == Approx(6.0));
    CHECK(b.inertia(0, 0) == Approx(6.0 * (4 + 9) / 12));
    CHECK(b.inertia(2, 2) == Approx(6.0 * (1 + 4) / 12));
    const MassProperties c = cylinder_properties(1.0, 2.0);
    CHECK(c.inertia(2, 2) == Approx(0.5 * c.volume));
    CHECK(c.inertia(0, 0) == Approx(c.volume * (3 + 4) / 12.0));
    const MassProperties ring = ring_properties(1.0, 0.5, 0.2);
    CHECK(ring.volume == Approx(M_PI * 0.75 * 0.2));
    CHECK(ring.inertia(2, 2) == Approx(0.5 * ring.volume * 1.25));
}

TEST_CASE("a closed mesh gives its solid's mass properties: a box exactly, a sphere as its facets converge", "[rigid][mass]") {
    const Vec a(0.5, 1.0, 1.5), offset(2, -1, 3);
    const MassProperties m = mesh_properties(box_mesh(a, offset)), exact = box_properties(a);
    CHECK(m.volume == Approx(exact.volume).epsilon(1e-12));
    CHECK((m.centroid - offset).norm() < 1e-12);
    CHECK((m.inertia - exact.inertia).norm() < 1e-12 * exact.inertia.norm());
    double last = 1;
    for (int n : {16, 32, 64}) {  // the inscribed polyhedron's error falls as 1/n^2
        const MassProperties sm = mesh_properties(sphere_mesh(1.0, n));
        const double err = std::fabs(sm.volume / sphere_properties(1.0).volume - 1);
        CHECK(err < last / 3);
        CHECK(std::fabs(sm.inertia(2, 2) / sphere_properties(1.0).inertia(2, 2) - 1) < 3 * err);
        last = err;
    }
    CHECK(last < 2e-3);
}

TEST_CASE("the union of overlapping spheres and discs converges to the lens-cut volume", "[rigid][mass]") {
    const double r = 0.01, d = 0.012;
    const UnionProperties u3 = pebble_union_properties({{Vec(0, 0, 0), r}, {Vec(d, 0, 0), r}}, 3, 1e-4);
    CHECK(u3.converged);
    CHECK(u3.properties.volume == Approx(two_sphere_volume(r, d)).epsilon(1e-3));
    CHECK(u3.properties.centroid.x() == Approx(d / 2).epsilon(1e-4));  // (the grid is not symmetric about it)
    // about the axis through both centres: twice a sphere's, less the lens's (an upper bound)
    CHECK(u3.properties.inertia(0, 0) < 2 * sphere_properties(r).inertia(0, 0));
    const UnionProperties u2 = pebble_union_properties({{Vec(0, 0, 0), r}, {Vec(d, 0, 0), r}}, 2, 1e-4);
    CHECK(u2.converged);
    CHECK(u2.properties.volume == Approx(two_disc_area(r, d)).epsilon(1e-3));
    // one disc alone: its polar moment 1/2 A r^2
    const UnionProperties one = pebble_union_properties({{Vec(0.3, 0.2, 0), r}}, 2, 1e-5);
    CHECK(one.properties.inertia(2, 2) == Approx(0.5 * M_PI * r * r * r * r).epsilon(1e-3));
    CHECK((one.properties.centroid - Vec(0.3, 0.2, 0)).norm() < 1e-9);
}

TEST_CASE("the principal axes of a turned box's tensor are its moments and its turned axes", "[rigid][mass]") {
    const MassProperties b = box_properties({0.5, 1.0, 1.5});
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Vec(1, 2, 3).normalized()).toRotationMatrix();
    const PrincipalAxes p = principal_axes(R * b.inertia * R.transpose());
    CHECK(p.moments.x() == Approx(b.inertia(2, 2)));  // ascending: the box's z moment is its least
    CHECK(p.moments.z() == Approx(b.inertia(0, 0)));
    const Eigen::Matrix3d axes = p.orientation.toRotationMatrix();
    CHECK(axes.determinant() == Approx(1.0));
    CHECK(std::fabs(axes.col(0).dot(R.col(2))) == Approx(1.0));  // the least axis is the box's turned z
    CHECK(std::fabs(axes.col(2).dot(R.col(0))) == Approx(1.0));
}
