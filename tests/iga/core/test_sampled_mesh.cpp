// PointFields: fields named first, then filled one point at a time.
#include <stdexcept>

#include <catch2/catch.hpp>

#include "iga/core/sampled_mesh.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_sampled_mesh {

using Eigen::Vector3d;
using iga::PointFields;

TEST_CASE("PointFields: named fields keep their order, a point's values go to each in turn",
          "[iga][core][output]") {
  PointFields f;
  f.name({"N", "gap"}, {"normal"});
  REQUIRE(f.scalars.size() == 2);
  REQUIRE(f.vectors.size() == 1);
  CHECK(f.scalars[0].first == "N");
  CHECK(f.scalars[1].first == "gap");
  CHECK(f.vectors[0].first == "normal");
  CHECK(f.scalars[0].second.empty());  // no point yet: the fields exist, empty
  f.append({-1.0, 0.5}, {Vector3d::UnitZ()});
  f.append({-2.0, 0.25}, {Vector3d::UnitX()});
  CHECK(f.scalars[0].second == std::vector<double>{-1.0, -2.0});
  CHECK(f.scalars[1].second == std::vector<double>{0.5, 0.25});
  CHECK(f.vectors[0].second[1] == Vector3d::UnitX());
  // a value missing or too many: an error, not a field out of step with the points
  CHECK_THROWS_AS(f.append({1.0}, {Vector3d::Zero()}), std::logic_error);
  CHECK_THROWS_AS(f.append({1.0, 2.0}, {}), std::logic_error);
  CHECK(f.scalars[0].second.size() == 2);
  // fields of the same points added after these, in their order
  PointFields more;
  more.name({"state"}, {"traction"});
  more.append({2.0}, {Vector3d::UnitY()});
  more.append({1.0}, {Vector3d::UnitY()});
  f.add(std::move(more));
  REQUIRE(f.scalars.size() == 3);
  CHECK(f.scalars[2].first == "state");
  CHECK(f.scalars[2].second == std::vector<double>{2.0, 1.0});
  REQUIRE(f.vectors.size() == 2);
  CHECK(f.vectors[1].first == "traction");
  // naming again starts over
  f.name({"slip"}, {});
  CHECK(f.scalars.size() == 1);
  CHECK(f.vectors.empty());
}

}  // namespace test_sampled_mesh
