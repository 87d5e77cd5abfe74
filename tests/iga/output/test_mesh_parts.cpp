// The output meshes of a run over several processes (iga/output/mesh_parts.hpp): packed and
// unpacked unchanged; a patch's grid sampled in blocks (element_grid with an ElementBlock) and
// joined is the grid sampled whole, its border samples the lower block's; points are
// concatenated in rank order; what cannot be joined is refused with the mesh's name.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#include "iga/core/partition.hpp"
#include "iga/output/mesh_parts.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_mesh_parts {

using namespace iga;
using Eigen::Vector3d;

namespace {

/// A grid with fields that are functions of the sample: its parameters and element.
MeshOutput sampled(const std::vector<double>& bu, const std::vector<double>& bv, int samples,
                   const ElementBlock& block) {
  MeshOutput o{"shell", "last_shell", "a shell", element_grid(bu, bv, samples, block), {}};
  std::vector<double> e;
  std::vector<Vector3d> x;
  for (std::size_t i = 0; i < o.mesh.params.size(); ++i) {
    const auto [u, v] = o.mesh.params[i];
    o.mesh.points.emplace_back(u, v, u * v);
    e.push_back(o.mesh.elements[i]);
    x.emplace_back(u, v, 1.0);
  }
  o.mesh.fields.scalars = {{"element", e}};
  o.mesh.fields.vectors = {{"x", x}};
  return o;
}

}  // namespace

TEST_CASE("meshes are packed into bytes and unpacked unchanged", "[mesh_parts]") {
  std::vector<MeshOutput> m;
  m.push_back(sampled({0, 0.5, 1}, {0, 1, 2, 3}, 2, {}));
  MeshOutput points{"", "contact", "points", {}, {}};
  points.mesh.points = {Vector3d(1, 2, 3)};
  points.mesh.fields.scalars = {{"N", {-4.0}}};
  m.push_back(points);
  m.push_back({"empty", "e", "", {}, {}});
  const std::vector<MeshOutput> back = unpack_meshes(pack_meshes(m));
  REQUIRE(back.size() == 3);
  for (std::size_t k = 0; k < 3; ++k) {
    CHECK(back[k].series == m[k].series);
    CHECK(back[k].stem == m[k].stem);
    CHECK(back[k].title == m[k].title);
    CHECK(back[k].mesh.shape == m[k].mesh.shape);
    CHECK(back[k].mesh.nu == m[k].mesh.nu);
    CHECK(back[k].mesh.points == m[k].mesh.points);
    CHECK(back[k].mesh.params == m[k].mesh.params);
    CHECK(back[k].mesh.elements == m[k].mesh.elements);
    CHECK(back[k].mesh.fields.scalars == m[k].mesh.fields.scalars);
    CHECK(back[k].mesh.fields.vectors == m[k].mesh.fields.vectors);
  }
  std::string bytes = pack_meshes(m);
  CHECK_THROWS_WITH(unpack_meshes(bytes.substr(0, bytes.size() - 3)), Catch::Contains("end early"));
  CHECK_THROWS_WITH(unpack_meshes(bytes + "x"), Catch::Contains("left over"));
}

TEST_CASE("a grid sampled in blocks and joined is the grid sampled whole", "[mesh_parts]") {
  const std::vector<double> bu{0, 0.1, 0.35, 0.5, 0.8, 1}, bv{0, 0.25, 0.5, 1};  // 5 x 3
  for (int P : {2, 3, 4, 6}) {
    CAPTURE(P);
    const MeshOutput whole = sampled(bu, bv, 3, {});
    std::vector<MeshOutput> parts;
    for (int r = 0; r < P; ++r) parts.push_back(sampled(bu, bv, 3, element_block(r, P, 5, 3)));
    const MeshOutput joined = join_parts(parts);
    CHECK(joined.stem == "last_shell");
    CHECK(joined.mesh.shape == SampledMesh::Shape::kGrid);
    CHECK(joined.mesh.nu == whole.mesh.nu);
    CHECK(joined.mesh.nv == whole.mesh.nv);
    // bit for bit: a border sample is the lower block's, computed as in the whole grid
    CHECK(joined.mesh.points == whole.mesh.points);
    CHECK(joined.mesh.params == whole.mesh.params);
    CHECK(joined.mesh.elements == whole.mesh.elements);
    CHECK(joined.mesh.fields.scalars == whole.mesh.fields.scalars);
    CHECK(joined.mesh.fields.vectors == whole.mesh.fields.vectors);
  }
}

TEST_CASE("points join in rank order, and empty parts need no fields", "[mesh_parts]") {
  MeshOutput a{"contact", "c", "", {}, {}}, b = a, none = a;
  a.mesh.points = {Vector3d(0, 0, 0)};
  a.mesh.fields.scalars = {{"N", {1.0}}};
  b.mesh.points = {Vector3d(1, 0, 0), Vector3d(2, 0, 0)};
  b.mesh.fields.scalars = {{"N", {2.0, 3.0}}};
  const MeshOutput j = join_parts({none, a, b});
  CHECK(j.mesh.points.size() == 3);
  CHECK(j.mesh.fields.scalars.at(0).second == std::vector<double>{1.0, 2.0, 3.0});
  CHECK(join_parts({none, none}).mesh.points.empty());
}

TEST_CASE("parts that cannot be joined are refused with the mesh's name", "[mesh_parts]") {
  MeshOutput line{"rod", "last_rod", "", {}, {}};
  line.mesh.shape = SampledMesh::Shape::kPolyline;
  line.mesh.points = {Vector3d(0, 0, 0), Vector3d(1, 0, 0)};
  CHECK(join_parts({MeshOutput{}, line}).mesh.points.size() == 2);  // a rod on one process
  CHECK_THROWS_WITH(join_parts({line, line}),
                    Catch::Contains("last_rod") && Catch::Contains("several processes"));
  MeshOutput other = line;
  other.mesh.fields.scalars = {{"N", {1.0, 2.0}}};
  CHECK_THROWS_WITH(join_parts({line, other}), Catch::Contains("differ in shape or fields"));
  const std::vector<double> b{0, 0.5, 1};
  const MeshOutput corner = sampled(b, b, 2, element_block(0, 4, 2, 2));
  CHECK_THROWS_WITH(join_parts({corner, sampled(b, b, 2, element_block(3, 4, 2, 2))}),
                    Catch::Contains("holes"));
  CHECK_THROWS_AS(join_parts({}), std::invalid_argument);
}

}  // namespace test_mesh_parts
