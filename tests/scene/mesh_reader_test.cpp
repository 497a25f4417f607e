// The mesh reader (scripting/mesh_reader.cpp) on small files written here:
// the three formats give the same triangles, and bad files are refused
// naming the JSON path, the file and the line or triangle.
#include "../support/mesh_files.hpp"
#include "mesh_reader.hpp"

#include <plab_host/errors.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace plab;
using namespace plab::testing_support;
using Catch::Matchers::Contains;

namespace {

const std::string kWhere = "scene.walls[0].file";

MeshFile read(const std::filesystem::path& p) { return read_mesh(p.string(), p.filename().string(), kWhere); }

// The cube as an OBJ of quads, its faces in every vertex form: "v",
// "v/vt", "v//vn", "v/vt/vn", and counted back from the last vertex.
std::string cube_obj() {
    std::ostringstream s;
    s << "# a unit cube\no cube\n";
    for (const Vec& v : cube_corners()) s << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
    s << "vt 0 0\nvn 0 0 1\ns off\n";
    const auto q = cube_quads();
    const char* forms[] = {"%d", "%d/1", "%d//1", "%d/1/1"};
    for (std::size_t f = 0; f < q.size(); ++f) {
        s << "f";
        for (int k = 0; k < 4; ++k) {
            char word[32];
            const int one_based = q[f][std::size_t(k)] + 1;
            std::snprintf(word, sizeof word, forms[(f + std::size_t(k)) % 4], f == 5 ? one_based - 9 : one_based);  // last face: -8..-1
            s << " " << word;
        }
        s << "\n";
    }
    return s.str();
}

} // namespace

TEST_CASE("a unit cube of 12 triangles reads the same from binary STL, ASCII STL and OBJ", "[mesh][scene]") {
    const auto dir = mesh_dir("cube");
    const std::vector<Triangle> cube = cube_triangles();
    write_file(dir / "cube.stl", binary_stl(cube));  // header starts with "solid": told by its size
    write_file(dir / "cube_ascii.stl", ascii_stl(cube, "\r\n"));
    write_file(dir / "cube.obj", cube_obj());
    for (const char* name : {"cube.stl", "cube_ascii.stl", "cube.obj"}) {
        INFO(name);
        const MeshFile m = read(dir / name);
        REQUIRE(m.triangles.size() == 12);
        for (std::size_t t = 0; t < 12; ++t)
            for (int v = 0; v < 3; ++v) CHECK(m.triangles[t][std::size_t(v)] == cube[t][std::size_t(v)]);  // exact: 0 and 1
        CHECK(m.degenerate == 0);
        CHECK(m.ignored.empty());  // o, vt, vn, s: not shape, not worth a warning
    }
    CHECK(read(dir / "cube.stl").format == "binary STL");
    CHECK(read(dir / "cube_ascii.stl").format == "ASCII STL");
    std::filesystem::remove_all(dir);
}

TEST_CASE("a truncated binary STL is refused naming the triangle cut short, a bad OBJ index naming its line",
          "[mesh][scene]") {
    const auto dir = mesh_dir("truncated");
    const std::string whole = binary_stl(cube_triangles());
    write_file(dir / "cut.stl", whole.substr(0, 84 + 50 * 5 + 20));  // in the 6th triangle
    CHECK_THROWS_WITH(read(dir / "cut.stl"), Contains(kWhere) && Contains("\"cut.stl\" (binary STL)") &&
                                                  Contains("truncated") && Contains("counts 12 triangles") &&
                                                  Contains("the file has 354 bytes") && Contains("triangle 6 is incomplete"));
    write_file(dir / "long.stl", whole + "xx");
    CHECK_THROWS_WITH(read(dir / "long.stl"), Contains("the file has 686 bytes") && Contains("a wrong count"));
    write_file(dir / "short.stl", "abc");
    CHECK_THROWS_WITH(read(dir / "short.stl"), Contains("too short for a binary STL"));
    write_file(dir / "index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\n# a face past the end\nf 1 2 3\nf 1 2 9\n");
    CHECK_THROWS_WITH(read(dir / "index.obj"), Contains(kWhere) && Contains("\"index.obj\" (OBJ) line 7") &&
                                                   Contains("vertex index 9 is outside 1..3"));
    write_file(dir / "back.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\n");
    CHECK_THROWS_WITH(read(dir / "back.obj"), Contains("line 3") && Contains("-3 reaches before the first vertex"));
    write_file(dir / "zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
    CHECK_THROWS_WITH(read(dir / "zero.obj"), Contains("line 4") && Contains("vertex index 0"));
    write_file(dir / "word.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x/1\n");
    CHECK_THROWS_WITH(read(dir / "word.obj"), Contains("line 4") && Contains("\"x/1\" is not a vertex index"));
    std::filesystem::remove_all(dir);
}

TEST_CASE("non-finite vertices and cut ASCII files are refused by line or triangle, zero-area triangles are left out "
          "and counted, and a file without a triangle is refused", "[mesh][scene]") {
    const auto dir = mesh_dir("bad");
    std::vector<Triangle> t = cube_triangles();
    t[3][1].y() = std::nan("");
    write_file(dir / "nan.stl", binary_stl(t));
    CHECK_THROWS_WITH(read(dir / "nan.stl"), Contains("triangle 4 of 12") && Contains("vertex 2 is not finite"));
    write_file(dir / "nan_ascii.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 inf\n");
    CHECK_THROWS_WITH(read(dir / "nan_ascii.stl"), Contains("(ASCII STL) line 5") && Contains("not finite"));
    write_file(dir / "nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n");
    CHECK_THROWS_WITH(read(dir / "nan.obj"), Contains("(OBJ) line 3") && Contains("not finite"));
    const std::string ascii = ascii_stl(cube_triangles());
    write_file(dir / "cut_ascii.stl", ascii.substr(0, ascii.rfind('\n', ascii.size() / 2) + 1));  // at a line's end
    CHECK_THROWS_WITH(read(dir / "cut_ascii.stl"), Contains("(ASCII STL)") && Contains("truncated"));
    write_file(dir / "four.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                                 "vertex 1 1 0\nendloop\nendfacet\nendsolid s\n");
    CHECK_THROWS_WITH(read(dir / "four.stl"), Contains("line 7") && Contains("\"endloop\" after 3 vertices"));

    // two slivers among the cube's triangles: left out, the rest kept in order
    t = cube_triangles();
    t.insert(t.begin() + 2, Triangle{Vec(0, 0, 0), Vec(0.5, 0.5, 0.5), Vec(1, 1, 1)});  // collinear
    t.push_back(Triangle{Vec(1, 1, 1), Vec(1, 1, 1), Vec(0, 0, 1)});                   // two corners in one
    write_file(dir / "slivers.stl", binary_stl(t));
    const MeshFile m = read(dir / "slivers.stl");
    CHECK(m.triangles.size() == 12);
    CHECK(m.degenerate == 2);
    CHECK(m.degenerate_where == "triangle 3 of 14, triangle 14 of 14");
    CHECK(m.triangles[2][1] == cube_triangles()[2][1]);

    // a statement that is not v, f or one of the known non-shape ones is named, for the warning
    write_file(dir / "curve.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\ng part\ncstype bspline\ncurv 0 1 1 2\nf 1 2 3\n");
    const MeshFile curve = read(dir / "curve.obj");
    CHECK(curve.triangles.size() == 1);
    CHECK(curve.ignored == "\"cstype\" (line 5)");

    write_file(dir / "flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    CHECK_THROWS_WITH(read(dir / "flat.obj"), Contains("holds no triangle of non-zero area (1 zero-area ones left out)"));
    write_file(dir / "empty.stl", binary_stl({}));
    CHECK_THROWS_WITH(read(dir / "empty.stl"), Contains("(binary STL): holds no triangle"));
    write_file(dir / "empty.obj", "# nothing\nv 0 0 0\n");
    CHECK_THROWS_WITH(read(dir / "empty.obj"), Contains("(OBJ): holds no triangle"));
    std::filesystem::create_directories(dir / "folder.stl");
    CHECK_THROWS_WITH(read(dir / "folder.stl"), Contains("is a directory"));
    CHECK_THROWS_WITH(read(dir / "none.stl"), Contains("cannot open the mesh file"));
    write_file(dir / "mesh.ply", "ply\n");
    CHECK_THROWS_WITH(read(dir / "mesh.ply"), Contains("unknown mesh format \".ply\""));
    CHECK_THROWS_WITH(read_mesh("/dev/zero", "zero.stl", kWhere), Contains("not a regular file"));
    std::filesystem::remove_all(dir);
}
