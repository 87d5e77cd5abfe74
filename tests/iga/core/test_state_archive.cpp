// Tests of the restart archive (iga/core/state_archive.hpp): one routine writes and reads,
// values come back bit for bit, and a file that does not fit is refused with the file, the
// section and what differs.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "iga/core/state_archive.hpp"
#include "tests/support/files.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_state_archive {

using namespace iga;
namespace fs = std::filesystem;

namespace {

struct State {
  double x = 0.0;
  int n = 0;
  bool flag = false;
  std::string text;
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  Eigen::VectorXd u;
  std::vector<double> w;
  std::vector<Eigen::Vector2d> points;
  void archive(StateArchive& a) {
    a.section("scalars");
    a.io(x);
    a.io(n);
    a.io(flag);
    a.io(text);
    a.section("vectors");
    a.io(v);
    a.io(M);
    a.io(u);
    a.io(w);
    a.items(
        points, [&](Eigen::Vector2d& p) { a.io(p); }, "points", /*resize=*/false);
  }
};

}  // namespace

TEST_CASE("StateArchive: the same routine writes and reads, bit for bit", "[iga][core][restart]") {
  State s;
  s.x = std::nextafter(1.0 / 3.0, 1.0);
  s.n = -7;
  s.flag = true;
  s.text = "contact, 3 pairs";
  s.v << 1e-300, -0.0, 4.5;
  s.M = Eigen::Matrix3d::Random();
  s.u = Eigen::VectorXd::Random(11);
  s.w = {std::numeric_limits<double>::denorm_min(), 2.0};
  s.points = {Eigen::Vector2d(1, 2), Eigen::Vector2d(3, 4)};
  const std::string path = test::fresh_out_dir("restart", "archive") + ".bin";
  fs::create_directories(fs::path(path).parent_path());
  StateArchive w = StateArchive::writer();
  s.archive(w);
  w.save(path);
  CHECK_FALSE(fs::exists(path + ".part"));

  State r;
  r.points.resize(2);
  StateArchive a = StateArchive::reader(path);
  CHECK(a.loading());
  r.archive(a);
  a.finish();
  CHECK(r.x == s.x);
  CHECK(r.n == s.n);
  CHECK(r.flag);
  CHECK(r.text == s.text);
  CHECK(r.v == s.v);
  CHECK(std::signbit(r.v[1]));
  CHECK(r.M == s.M);
  CHECK(r.u == s.u);
  CHECK(r.w == s.w);
  CHECK(r.points == s.points);

  SECTION("an archive written as it goes into its file is the same file") {
    const std::string streamed = path + ".streamed";
    fs::remove(streamed);  // of an earlier run
    StateArchive f = StateArchive::file_writer(streamed);
    State copy = s;
    copy.archive(f);
    CHECK(fs::exists(streamed + ".part"));  // written into the temporary file
    CHECK_FALSE(fs::exists(streamed));
    CHECK_THROWS_WITH(f.save(path), Catch::Contains("this archive writes " + streamed));
    f.save(streamed);
    CHECK_FALSE(fs::exists(streamed + ".part"));
    std::ifstream fa(path, std::ios::binary), fb(streamed, std::ios::binary);
    const std::string da((std::istreambuf_iterator<char>(fa)), std::istreambuf_iterator<char>());
    const std::string db((std::istreambuf_iterator<char>(fb)), std::istreambuf_iterator<char>());
    CHECK(da.size() > 100);
    CHECK(da == db);
  }
  SECTION("a model with another number of points is refused") {
    State other;
    other.points.resize(3);
    StateArchive b = StateArchive::reader(path);
    CHECK_THROWS_WITH(other.archive(b), Catch::Contains(path) &&
                                            Catch::Contains("section \"vectors\"") &&
                                            Catch::Contains("the file has 2 points, the model 3"));
  }
  SECTION("a routine that reads other sections is refused") {
    StateArchive b = StateArchive::reader(path);
    CHECK_THROWS_WITH(b.section("solver"),
                      Catch::Contains("expected the section \"solver\", found \"scalars\""));
  }
  SECTION("a routine that reads less than was written is refused at the end") {
    StateArchive b = StateArchive::reader(path);
    b.section("scalars");
    CHECK_THROWS_WITH(b.finish(), Catch::Contains("bytes left unread"));
  }
}

}  // namespace test_state_archive
