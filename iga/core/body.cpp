// A deformable body of a model; see body.hpp.
#include "iga/core/body.hpp"

#include <stdexcept>

namespace iga {

void Body::partition(int /*rank*/, int /*processes*/, std::vector<int>& /*owner*/,
                     std::vector<int>& /*reads*/) {
  throw std::logic_error(describe() + " cannot be cut over several processes");
}

}  // namespace iga
