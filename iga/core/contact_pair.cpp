// The world-frame output of a contact pair; see contact_pair.hpp.
#include "iga/core/contact_pair.hpp"

namespace iga {

bool ContactPair::sliding_steadily() const {
  if (mu() == 0.0) return true;
  const ContactCounts c = counts();
  return c.active > 0 && c.slip == c.active;
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
