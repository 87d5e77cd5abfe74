// The round-off probe (see roundoff_probe.hpp).
#include "iga/solvers/roundoff_probe.hpp"

#include <cstdlib>
#include <mutex>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>

namespace iga {

namespace {

/// The seed of IGA_ROUNDOFF_PROBE, or nothing when it is unset or empty.
std::optional<unsigned long long> probe_seed() {
  const char* v = std::getenv("IGA_ROUNDOFF_PROBE");
  if (v == nullptr || *v == '\0') return std::nullopt;
  const std::string s(v);
  if (s.find_first_not_of("0123456789") != std::string::npos || s.size() > 18)
    throw std::invalid_argument(
        "IGA_ROUNDOFF_PROBE: must be a non-negative integer (the seed), got \"" + s + "\"");
  return std::stoull(s);
}

struct Probe {
  bool on = false;
  std::mutex mutex;
  std::mt19937_64 gen;
};

Probe& probe() {
  static Probe* p = [] {
    auto* q = new Probe;  // never destroyed: used until the process ends
    if (const std::optional<unsigned long long> seed = probe_seed()) {
      q->on = true;
      q->gen.seed(*seed);
    }
    return q;
  }();
  return *p;
}

}  // namespace

bool roundoff_probe_enabled() {
  return probe().on;
}

void roundoff_probe_perturb(Eigen::VectorXd& du) {
  Probe& p = probe();
  if (!p.on) return;
  const std::lock_guard<std::mutex> lock(p.mutex);
  std::uniform_real_distribution<double> xi(-1.0, 1.0);
  for (Eigen::Index i = 0; i < du.size(); ++i) du[i] *= 1.0 + kRoundoffProbeSize * xi(p.gen);
}

bool roundoff_probe_refuses() {
  Probe& p = probe();
  if (!p.on) return false;
  const std::lock_guard<std::mutex> lock(p.mutex);
  return std::uniform_real_distribution<double>(0.0, 1.0)(p.gen) < kRoundoffProbeRefusal;
}

}  // namespace iga
