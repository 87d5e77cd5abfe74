// The registry of body types (body_types.hpp), with the built-in rod, shell and membrane.
#include "iga/model/body_types.hpp"

#include <algorithm>
#include <map>
#include <mutex>
#include <set>
#include <utility>

namespace iga::model_detail {

// The built-in body types, each defined in its reader's file (<type>_body.cpp).
BodyType rod_body_type();
BodyType shell_body_type();
BodyType membrane_body_type();

namespace {

struct Registry {
  std::mutex mutex;
  std::map<std::string, BodyType> types{
      {"rod", rod_body_type()}, {"shell", shell_body_type()}, {"membrane", membrane_body_type()}};
};

Registry& registry() {
  static Registry r;
  return r;
}

}  // namespace

void register_body_type(const std::string& type, BodyType t) {
  if (type.empty() || !t.build || !t.check_material)
    throw std::invalid_argument("register_body_type: a name, a reader and a material check");
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  r.types[type] = std::move(t);
}

std::vector<std::string> body_type_names() {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  std::vector<std::string> names;
  for (const auto& [name, t] : r.types) names.push_back(name);
  return names;
}

std::vector<std::string> material_type_names() {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  std::set<std::string> names;
  for (const auto& [name, t] : r.types)
    names.insert(t.material_types.begin(), t.material_types.end());
  return {names.begin(), names.end()};
}

void check_material(const JsonCursor& m) {
  const std::string type = one_of(m["type"], material_type_names());
  std::function<void(const JsonCursor&)> check;
  {
    Registry& r = registry();
    const std::lock_guard<std::mutex> lock(r.mutex);
    for (const auto& [name, t] : r.types)
      if (std::find(t.material_types.begin(), t.material_types.end(), type) !=
          t.material_types.end())
        check = t.check_material;
  }
  check(m);
}

const BodyType& body_type(const JsonCursor& c) {
  const std::string name = one_of(c, body_type_names());
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  return r.types.at(name);  // entries are never removed: the reference stays valid
}

}  // namespace iga::model_detail
