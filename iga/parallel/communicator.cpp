// The serial communicator and the run's world; see communicator.hpp.
#include "iga/parallel/communicator.hpp"

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace iga {

namespace {
const Communicator* g_world = nullptr;
}  // namespace

SerialCommunicator::SerialCommunicator(int rank, int size) : rank_(rank), size_(size) {
  if (size < 1 || rank < 0 || rank >= size)
    throw std::invalid_argument("SerialCommunicator: process " + std::to_string(rank) + " of " +
                                std::to_string(size));
}

std::string SerialCommunicator::describe() const {
  if (size_ == 1) return "serial";
  return "process " + std::to_string(rank_) + " of " + std::to_string(size_) + ", alone";
}

void SerialCommunicator::abort(int code, const std::string& message) const {
  std::fprintf(stderr, "%s\n", message.c_str());
  std::fflush(stderr);
  std::exit(code);
}

std::vector<std::vector<double>> SerialCommunicator::exchange(
    const std::vector<std::vector<double>>& to) const {
  if (to.size() != static_cast<std::size_t>(size_))
    throw std::invalid_argument("Communicator::exchange: " + std::to_string(to.size()) +
                                " lists for " + std::to_string(size_) + " processes");
  std::vector<std::vector<double>> from(to.size());
  from[static_cast<std::size_t>(rank_)] = to[static_cast<std::size_t>(rank_)];
  return from;
}

std::string Communicator::first_message(const std::string& s) const {
  std::string first;
  for (const std::string& m : gather(s))  // rank 0 only: the others gather nothing
    if (!m.empty()) {
      first = m;
      break;
    }
  broadcast(first, 0);
  return first;
}

const Communicator& serial_communicator() {
  static const SerialCommunicator serial;
  return serial;
}

const Communicator& world() {
  return g_world ? *g_world : serial_communicator();
}

void detail::set_world(const Communicator* w) {
  g_world = w;
}

bool launched_by_mpirun() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(v) != nullptr) return true;
  return false;
}

}  // namespace iga
