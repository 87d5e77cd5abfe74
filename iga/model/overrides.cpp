// --set /json/pointer=value overrides of a model document, and JSON pointers named in it.
#include "iga/model/analysis.hpp"

#include <string>

namespace iga {

namespace {

/// RFC 6901: every '~' is followed by 0 or 1. Checked before nlohmann parses a pointer, so
/// that the message is ours and names the pointer.
bool escapes_valid(const std::string& pointer) {
  for (std::size_t i = 0; i < pointer.size(); ++i)
    if (pointer[i] == '~' &&
        (i + 1 == pointer.size() || (pointer[i + 1] != '0' && pointer[i + 1] != '1')))
      return false;
  return true;
}

/// doc.contains(p), false also where nlohmann throws (an array index beyond size_t).
bool has_entry(const Json& doc, const JsonPointer& p) {
  try {
    return doc.contains(p);
  } catch (const nlohmann::json::exception&) {
    return false;
  }
}

}  // namespace

void apply_override(Json& doc, const std::string& file, const std::string& assignment) {
  const std::size_t eq = assignment.find('=');
  const std::string text = assignment.substr(0, eq);  // the pointer, or all of a bad assignment
  if (eq == std::string::npos || text.empty() || text[0] != '/')
    throw ModelError("--set", "",
                     "expected /json/pointer=value (e.g. /solver/max_steps=50), got " +
                         short_dump(Json(assignment), 80));
  if (!escapes_valid(text))
    throw ModelError("--set", "",
                     "\"" + text +
                         "\" is not a JSON pointer: '~' must be followed by 0 or 1 (~0 stands "
                         "for '~', ~1 for '/')");
  const JsonPointer ptr(text);
  if (!has_entry(doc, ptr)) {
    // A new key is allowed where its parent object exists; the loader then accepts the key or
    // rejects it as unknown at its own path.
    const JsonPointer parent = ptr.parent_pointer();
    if (!has_entry(doc, parent))
      throw ModelError(file, ptr.to_string(),
                       "--set: no such entry, and its parent " +
                           (parent.empty() ? std::string("(the root)") : parent.to_string()) +
                           " does not exist either");
    if (!doc.at(parent).is_object())
      throw ModelError(file, ptr.to_string(),
                       "--set: no such entry; a new key can only be added to an object, and " +
                           parent.to_string() + " is " + describe_json(doc.at(parent)));
  }
  Json value = parse_json_text(assignment.substr(eq + 1), "--set " + text);
  doc[ptr] = std::move(value);
}

JsonPointer model_pointer(const JsonCursor& c, const Json& doc) {
  const std::string s = c.as_string();
  if (s.empty() || s[0] != '/' || !escapes_valid(s))
    c.fail("expected a JSON pointer (\"/section/key\", ~0 for '~' and ~1 for '/')");
  JsonPointer p(s);
  if (!has_entry(doc, p)) c.fail("names no entry of the model");
  return p;
}

}  // namespace iga
