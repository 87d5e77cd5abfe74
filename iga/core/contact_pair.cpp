// The world-frame output of a contact pair; see contact_pair.hpp.
#include "iga/core/contact_pair.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

namespace iga {

bool ContactPair::local_sliding_steadily() const {
  if (mu() == 0.0) return true;
  const ContactCounts c = local_counts();
  return c.active > 0 && c.slip == c.active;
}

bool ContactPair::sliding_steadily() const {
  if (!total_) return local_sliding_steadily();
  // The parts without contact hold nothing back: the whole slides steadily when it has contact
  // and every part with contact slides so (without friction: always, as one part).
  return mu() == 0.0 || (total_->counts.active > 0 && total_->steady);
}

std::string ContactPair::status() const {
  const ContactCounts c = counts();
  std::string s = "contact " + std::to_string(c.active) + " (stick " + std::to_string(c.stick) +
                  ", slip " + std::to_string(c.slip) + ")";
  if (const std::optional<double> gap = checked_gap()) {
    char buf[32];
    std::snprintf(buf, sizeof buf, ", |gap| %.1e", total_ ? total_->max_gap : *gap);
    s += buf;
  }
  return s;
}

ContactTally ContactPair::local_tally() const {
  ContactTally t;
  t.counts = local_counts();
  t.force = force_;
  t.moment = moment_;
  t.roundoff = local_roundoff();
  t.max_gap = checked_gap().value_or(0.0);
  t.steady = t.counts.active == 0 || local_sliding_steadily();
  return t;
}

ContactTally ContactPair::combine(const ContactTally& a, const ContactTally& b) {
  ContactTally c;
  c.counts = {a.counts.active + b.counts.active, a.counts.stick + b.counts.stick,
              a.counts.slip + b.counts.slip};
  c.force = a.force + b.force;
  c.moment = a.moment + b.moment;
  c.roundoff = a.roundoff + b.roundoff;
  c.max_gap = std::max(a.max_gap, b.max_gap);
  c.steady = a.steady && b.steady;
  return c;
}

void ContactPair::add_fields(SampledMesh& body) const {
  const std::size_t first = body.fields.vectors.size();
  add_tool_fields(body);
  if (!pose_.turns()) return;
  for (std::size_t k = first; k < body.fields.vectors.size(); ++k)
    for (Vector3d& v : body.fields.vectors[k].second) v = pose_.Q * v;
}

SampledMesh ContactPair::points() const {
  SampledMesh m = tool_points();
  for (Vector3d& x : m.points) x = pose_.to_world(x);
  if (pose_.turns())
    for (auto& f : m.fields.vectors)
      for (Vector3d& v : f.second) v = pose_.Q * v;
  return m;
}

std::vector<ContactFoot> ContactPair::feet() const {
  std::vector<ContactFoot> feet = tool_feet();
  for (ContactFoot& f : feet) {
    f.x = pose_.to_world(f.x);
    f.traction = pose_.Q * f.traction;
  }
  return feet;
}

}  // namespace iga
