// The round-off probe (see roundoff_probe.hpp).
#include "iga/solvers/roundoff_probe.hpp"

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>

namespace iga {

namespace {

/// The seed of IGA_ROUNDOFF_PROBE, or nothing when it is unset or empty.
std::optional<std::uint64_t> probe_seed() {
  const char* v = std::getenv("IGA_ROUNDOFF_PROBE");
  if (v == nullptr || *v == '\0') return std::nullopt;
  const std::string s(v);
  if (s.find_first_not_of("0123456789") != std::string::npos || s.size() > 18)
    throw std::invalid_argument(
        "IGA_ROUNDOFF_PROBE: must be a non-negative integer (the seed), got \"" + s + "\"");
  return std::stoull(s);
}

/// The seed, read once; nothing when the probe is off.
const std::optional<std::uint64_t>& seed() {
  static const std::optional<std::uint64_t> s = probe_seed();
  return s;
}

/// FNV-1a over the bytes of n doubles, started from h.
std::uint64_t hash_doubles(std::uint64_t h, const double* x, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &x[i], sizeof bits);
    for (int b = 0; b < 8; ++b) {
      h ^= (bits >> (8 * b)) & 0xffU;
      h *= 0x100000001b3ULL;
    }
  }
  return h;
}

constexpr std::uint64_t kOffset = 0xcbf29ce484222325ULL;

/// The number of live RoundoffProbeOff guards (any thread): the probe is off while it is > 0.
std::atomic<int> guards_off{0};

}  // namespace

bool roundoff_probe_enabled() {
  return seed().has_value() && guards_off.load(std::memory_order_acquire) == 0;
}

RoundoffProbeOff::RoundoffProbeOff() {
  guards_off.fetch_add(1, std::memory_order_acq_rel);
}

RoundoffProbeOff::~RoundoffProbeOff() {
  guards_off.fetch_sub(1, std::memory_order_acq_rel);
}

void roundoff_probe_perturb(Eigen::VectorXd& du) {
  if (!roundoff_probe_enabled()) return;
  std::mt19937_64 gen(
      hash_doubles(kOffset ^ *seed(), du.data(), static_cast<std::size_t>(du.size())));
  std::uniform_real_distribution<double> xi(-1.0, 1.0);
  for (Eigen::Index i = 0; i < du.size(); ++i) du[i] *= 1.0 + kRoundoffProbeSize * xi(gen);
}

bool roundoff_probe_refuses(const std::vector<double>& state) {
  if (!roundoff_probe_enabled()) return false;
  std::mt19937_64 gen(
      hash_doubles(kOffset ^ (*seed() + 0x9e3779b97f4a7c15ULL), state.data(), state.size()));
  return std::uniform_real_distribution<double>(0.0, 1.0)(gen) < kRoundoffProbeRefusal;
}

}  // namespace iga
