// Runs the `saddle` app ([KS15] Sects. 6.1-6.2) on its coarse version (--quick: 8 x 8 elements,
// 3 x 3 contact points) as a user would, and checks its files and the physics they show: the
// plate comes down onto the saddle and stays on it, the contact zone grows with the load, a
// frictionless run has no sticking points; bad input exits 1 naming the JSON path.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <sys/wait.h>

namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

int saddle(const std::string& args, std::string& output) {
  const fs::path log = fs::temp_directory_path() / ("saddle_test_" + std::to_string(::getpid()) + ".txt");
  const std::string cmd = std::string("\"") + SADDLE_EXE + "\" " + args + " >\"" + log.string() + "\" 2>&1 </dev/null";
  const int raw = std::system(cmd.c_str());
  output = slurp(log);
  fs::remove(log);
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

/// saddle.csv as rows of named columns.
std::vector<std::map<std::string, std::string>> read_csv(const fs::path& p) {
  std::istringstream in(slurp(p));
  std::string line;
  std::vector<std::string> head;
  std::vector<std::map<std::string, std::string>> rows;
  auto split = [](const std::string& s) {
    std::vector<std::string> f;
    std::stringstream ss(s);
    std::string x;
    while (std::getline(ss, x, ',')) f.push_back(x);
    return f;
  };
  std::getline(in, line);
  head = split(line);
  while (std::getline(in, line)) {
    const std::vector<std::string> f = split(line);
    std::map<std::string, std::string> r;
    for (std::size_t k = 0; k < head.size() && k < f.size(); ++k) r[head[k]] = f[k];
    rows.push_back(r);
  }
  return rows;
}

}  // namespace

TEST_CASE("saddle --quick: the plate settles on the saddle, the contact zone grows with the load",
          "[apps][saddle]") {
  const fs::path out = fs::temp_directory_path() / ("saddle_quick_" + std::to_string(::getpid()));
  fs::remove_all(out);
  std::string log;
  const int status = saddle("--quick --out \"" + out.string() + "\"", log);
  INFO(log);
  REQUIRE(status == 0);
  for (const char* f : {"saddle.csv", "saddle_summary.json", "model_used.json", "contact_mu0.csv",
                        "contact_mu0.125.csv", "saddle_load_deflection.png", "saddle_contact_mu0.png",
                        "saddle_contact_mu0.125.png", "mu0/rigid.vtk", "mu0/t1000_shell.vtk",
                        "mu0/t1000_contact.vtk", "mu0.125/snapshots_shell.pvd", "mu0.125/steps.csv"})
    CHECK(fs::exists(out / f));
  const auto rows = read_csv(out / "saddle.csv");
  const nlohmann::json summary = nlohmann::json::parse(slurp(out / "saddle_summary.json"));
  REQUIRE(summary["runs"].size() == 2);
  for (const auto& run : summary["runs"]) {
    const std::string name = run["name"];
    INFO(name);
    CHECK(run["status"] == "converged");
    CHECK(run["steps"].get<int>() < 200);  // adaptive stepping, not 1000 steps
    // The contact zone at the snapshots grows with the load.
    const auto& snaps = run["snapshots"];
    REQUIRE(snaps.size() == 4);
    for (std::size_t k = 1; k < snaps.size(); ++k)
      CHECK(snaps[k]["contact_points"].get<int>() > snaps[k - 1]["contact_points"].get<int>());
    // The plate's centre comes to rest on the saddle point: the lower face (h/2 = 0.1 below the
    // mid-surface, which starts at z = 2.75) touches z = 0, so the deflection is 2.65 less the
    // penalty's penetration.
    const double w = run["centre_deflection"];
    CHECK(w == Approx(2.65).margin(2e-3));
    if (run["mu"].get<double>() == 0.0) CHECK(run["sticking_points"].get<int>() == 0);
  }
  // saddle.csv: one row per converged step of both runs, load q = 2.756 t / 1000.
  int n = 0;
  for (const auto& r : rows) {
    CHECK(std::stod(r.at("load")) == Approx(2.756 * std::stod(r.at("t")) / 1000.0));
    CHECK(std::stoi(r.at("sticking_points")) + std::stoi(r.at("sliding_points")) == std::stoi(r.at("contact_points")));
    ++n;
  }
  CHECK(n == summary["runs"][0]["steps"].get<int>() + summary["runs"][1]["steps"].get<int>());
  fs::remove_all(out);
}

TEST_CASE("saddle: bad input exits 1 naming the file and JSON path", "[apps][saddle][errors]") {
  const fs::path out = fs::temp_directory_path() / ("saddle_bad_" + std::to_string(::getpid()));
  std::string log;
  CHECK(saddle("--quick --set /materials/plate/thickness=-0.2 --out \"" + out.string() + "\"", log) == 1);
  CHECK_THAT(log, Catch::Contains("saddle.json: /materials/plate/thickness: must be > 0, got -0.2"));
  CHECK(saddle("--quick --set /contact/0/stratgy=\"slave\" --out \"" + out.string() + "\"", log) == 1);
  CHECK_THAT(log, Catch::Contains("/contact/0/stratgy: --set names no existing entry"));
  CHECK(saddle("--quick --strategy sideways --out \"" + out.string() + "\"", log) != 0);
  fs::remove_all(out);
}
