// JSON input with errors that name file, path, value and expectation; readable JSON output.
// One SAX pass over the text tracks the JSON path so that syntax errors, overflowing numbers,
// duplicate keys and the limits of json_reader.hpp (depth, number of values) are reported
// where they are, and builds the order-preserving nlohmann::ordered_json on the way. Nothing
// recursive sees a document before the pass accepted it.
#include "geometry/json_reader.hpp"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <system_error>
#include <unordered_set>
#include <utility>

namespace iga {

namespace {

/// The first `head` and last `tail` bytes of s with "..." between them when s is longer,
/// cut at UTF-8 character boundaries.
std::string abbreviate(const std::string& s, std::size_t head, std::size_t tail) {
  if (s.size() <= head + tail + 3) return s;
  auto is_tail_byte = [&](std::size_t i) {
    return (static_cast<unsigned char>(s[i]) & 0xC0) == 0x80;
  };
  std::size_t h = head, t = s.size() - tail;
  while (h > 0 && is_tail_byte(h)) --h;
  while (t < s.size() && is_tail_byte(t)) ++t;
  return s.substr(0, h) + "..." + s.substr(t);
}

}  // namespace

// A pointer into a deep or long-keyed document is shortened in what() (pointer() keeps it).
ModelError::ModelError(std::string file, std::string pointer, const std::string& message)
    : std::runtime_error(pointer.empty()
                             ? file + ": " + message
                             : file + ": " + abbreviate(pointer, 120, 80) + ": " + message),
      file_(std::move(file)),
      pointer_(std::move(pointer)),
      message_(message) {}

namespace {

/// 1-based line and column (in UTF-8 characters) of the byte at `offset` (0-based).
std::pair<std::size_t, std::size_t> line_column(const std::string& text, std::size_t offset) {
  offset = std::min(offset, text.size());
  std::size_t line = 1, line_start = 0;
  for (std::size_t i = 0; i < offset; ++i)
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  // A byte-order mark is no column (editors do not show it).
  if (line == 1 && text.rfind("\xEF\xBB\xBF", 0) == 0)
    line_start = std::min<std::size_t>(3, offset);
  std::size_t column = 1;
  for (std::size_t i = line_start; i < offset; ++i)
    if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) ++column;  // skip UTF-8 tails
  return {line, column};
}

/// nlohmann's what() without "[json.exception.parse_error.101] parse error at line 1, ...: ".
std::string bare_message(const std::string& what) {
  std::string m = what;
  if (!m.empty() && m.front() == '[') {
    const std::size_t close = m.find("] ");
    if (close != std::string::npos) m = m.substr(close + 2);
  }
  if (m.rfind("parse error", 0) == 0) {
    const std::size_t colon = m.find(": ");
    if (colon != std::string::npos) m = m.substr(colon + 2);
  }
  return m;
}

/// SAX handler that builds the document while it keeps the JSON path of the current position,
/// rejects duplicate keys, enforces the limits (depth, number of values) and records where a
/// parse error happened. Keys are appended to objects without the linear search of
/// ordered_json's own insertion (duplicates are excluded here by a hash set), so an object
/// with millions of keys costs linear, not quadratic, time.
// bugprone-exception-escape: the implicit destructor destroys root_, whose destructor
// (nlohmann::json's non-recursive destroy) reserves a work vector; out of memory there ends the
// program, as for any destructor.
// NOLINTNEXTLINE(bugprone-exception-escape)
class PathTracker final : public nlohmann::json_sax<Json> {
 public:
  struct Frame {
    bool array = false;
    std::size_t index = 0;  // next element of an array
    std::string key;        // current key of an object
    bool has_key = false;
    std::unordered_set<std::string> keys;
    Json* value = nullptr;  // the array or object being filled
  };

  enum class Limit { none, depth, values };

  bool null() override { return value(Json(nullptr)); }
  bool boolean(bool b) override { return value(Json(b)); }
  bool number_integer(number_integer_t x) override { return value(Json(x)); }
  bool number_unsigned(number_unsigned_t x) override { return value(Json(x)); }
  bool number_float(number_float_t x, const string_t&) override { return value(Json(x)); }
  bool string(string_t& x) override { return value(Json(std::move(x))); }
  bool binary(binary_t&) override { return value(Json(nullptr)); }  // not in JSON text
  bool start_object(std::size_t) override {
    if (!enter()) return false;
    Frame f;
    f.value = insert(Json::object());
    stack_.push_back(std::move(f));
    return true;
  }
  bool key(string_t& k) override {
    Frame& f = stack_.back();
    f.key = k;
    f.has_key = true;
    if (!f.keys.insert(k).second) {
      duplicate_ = true;
      duplicate_key_ = k;
      return false;
    }
    return true;
  }
  bool end_object() override {
    stack_.pop_back();
    return advance();
  }
  bool start_array(std::size_t) override {
    if (!enter()) return false;
    Frame f;
    f.array = true;
    f.value = insert(Json::array());
    stack_.push_back(std::move(f));
    return true;
  }
  bool end_array() override {
    stack_.pop_back();
    return advance();
  }
  bool parse_error(std::size_t position, const std::string& last_token,
                   const nlohmann::json::exception& ex) override {
    error_position_ = position;
    error_token_ = last_token;
    error_message_ = ex.what();
    error_id_ = ex.id;
    return false;
  }

  /// The document read (complete once sax_parse returned true).
  Json take() { return std::move(root_); }

  JsonPointer pointer() const {
    JsonPointer p;
    for (const Frame& f : stack_) {
      if (f.array) {
        p.push_back(std::to_string(f.index));
      } else {
        if (!f.has_key) break;
        p.push_back(f.key);
      }
    }
    return p;
  }

  bool duplicate_ = false;
  std::string duplicate_key_;
  std::size_t error_position_ = 0;
  std::string error_token_, error_message_;
  int error_id_ = 0;
  Limit limit_ = Limit::none;

 private:
  /// Counts a new array or object; false when it would break a limit.
  bool enter() {
    if (stack_.size() >= kMaxJsonDepth) {
      limit_ = Limit::depth;
      return false;
    }
    return count();
  }
  bool count() {
    if (++values_ > kMaxJsonValues) {
      limit_ = Limit::values;
      return false;
    }
    return true;
  }
  bool value(Json v) {
    if (!count()) return false;
    insert(std::move(v));
    return advance();
  }
  /// Puts v where the parser is: the root, the next array element or the current key's value.
  /// The pointers on the stack stay valid: a container only grows while it is the innermost.
  Json* insert(Json v) {
    if (stack_.empty()) {
      root_ = std::move(v);
      return &root_;
    }
    Frame& f = stack_.back();
    if (f.array) {
      auto& a = f.value->get_ref<Json::array_t&>();
      a.push_back(std::move(v));
      return &a.back();
    }
    // ordered_map is a vector of pairs: append, the hash set has excluded duplicates.
    using Pairs = std::vector<std::pair<const std::string, Json>>;
    Pairs& o = f.value->get_ref<Json::object_t&>();
    o.emplace_back(f.key, std::move(v));
    return &o.back().second;
  }
  /// One value of the enclosing array or object is complete.
  bool advance() {
    if (!stack_.empty()) {
      Frame& f = stack_.back();
      if (f.array)
        ++f.index;
      else
        f.has_key = false;
    }
    return true;
  }
  std::vector<Frame> stack_;
  std::size_t values_ = 0;
  Json root_;
};

/// Byte offset of the array or object that opens nesting level `depth` + 1 (the first level
/// is 1), or text.size(). Brackets inside strings are skipped; the text up to there is valid
/// JSON (the SAX pass stopped at that bracket), so this simple scan is exact.
std::size_t offset_beyond_depth(const std::string& text, std::size_t depth) {
  std::size_t level = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++level > depth) return i;
    } else if (c == ']' || c == '}') {
      --level;
    }
  }
  return text.size();
}

/// Like line_column(text, offset) as "line L, column C".
std::string where(const std::string& text, std::size_t offset) {
  const auto [line, col] = line_column(text, offset);
  return "line " + std::to_string(line) + ", column " + std::to_string(col);
}

constexpr char kBom[] = "\xEF\xBB\xBF";

}  // namespace

Json parse_json_text(const std::string& text, const std::string& file) {
  // A UTF-8 byte-order mark (some editors write one) is skipped here, for every reader.
  const std::size_t skip = text.rfind(kBom, 0) == 0 ? 3 : 0;
  const char* const first = text.data() + skip;
  const char* const last = text.data() + text.size();
  PathTracker tracker;
  if (!Json::sax_parse(first, last, &tracker)) {
    const std::string at = tracker.pointer().to_string();
    if (tracker.duplicate_)
      throw ModelError(file, at,
                       "duplicate key \"" + abbreviate(tracker.duplicate_key_, 60, 20) +
                           "\" (each key may appear once per object)");
    if (tracker.limit_ == PathTracker::Limit::depth)
      throw ModelError(file, at,
                       "arrays and objects nested deeper than " + std::to_string(kMaxJsonDepth) +
                           " levels (" + where(text, offset_beyond_depth(text, kMaxJsonDepth)) +
                           ")");
    if (tracker.limit_ == PathTracker::Limit::values)
      throw ModelError(file, at,
                       "more than " + std::to_string(kMaxJsonValues) +
                           " JSON values (the limit of a model file)");
    // nlohmann reports the position after the last character read. Its token text starts at
    // the last string or number scanned, so it is the offending token itself only when it is a
    // whole string or number ("ball" after a missing comma, 1e999): then point at its start.
    const std::string& token = tracker.error_token_;
    const std::size_t end = skip + tracker.error_position_;
    const bool number =
        !token.empty() && token.find_first_not_of("0123456789+-.eE") == std::string::npos;
    const bool string = token.size() >= 2 && token.front() == '"' && token.back() == '"';
    const bool clean = (number || string) && token.size() <= end;
    const std::string at_text = where(text, clean ? end - token.size() : (end > 0 ? end - 1 : 0));
    if (tracker.error_id_ == 406)  // out_of_range.406: number overflow
      throw ModelError(
          file, at,
          "number " + abbreviate(token, 60, 20) + " is out of range of a double (" + at_text + ")");
    throw ModelError(file, at,
                     "malformed JSON at " + at_text + ": " +
                         abbreviate(bare_message(tracker.error_message_), 200, 20));
  }
  return tracker.take();
}

std::string read_model_text(const std::string& path, std::size_t max_bytes) {
  namespace fs = std::filesystem;
  // Checked before opening: opening a FIFO blocks, and /dev/zero never ends.
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st)) {
    const int err = ec ? ec.value() : ENOENT;
    throw ModelError(path, "", std::string("cannot open file: ") + std::strerror(err));
  }
  if (fs::is_directory(st)) throw ModelError(path, "", "is a directory, not a model file");
  if (!fs::is_regular_file(st))
    throw ModelError(path, "",
                     "is not a regular file (a FIFO, socket or device); model files must be "
                     "regular files");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw ModelError(path, "", "cannot read file: " + ec.message());
  const std::string limit = std::to_string(max_bytes >> 20) + " MiB";
  auto too_large = [&](std::uintmax_t bytes) {
    return ModelError(
        path, "",
        "file of " + std::to_string(bytes) + " bytes is larger than the limit of " +
            (max_bytes % (std::size_t{1} << 20) == 0 ? limit
                                                     : std::to_string(max_bytes) + " bytes") +
            " for a model file");
  };
  if (size > max_bytes) throw too_large(size);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ModelError(path, "", std::string("cannot open file: ") + std::strerror(errno));
  // The size may change under us: read at most max_bytes + 1 bytes and check again.
  std::string text(static_cast<std::size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.bad()) throw ModelError(path, "", "cannot read file");
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (in) {  // the file grew: read the rest, within the limit
    char buf[65536];
    while (in.read(buf, sizeof buf) || in.gcount() > 0) {
      text.append(buf, static_cast<std::size_t>(in.gcount()));
      if (text.size() > max_bytes) throw too_large(text.size());
    }
    if (in.bad()) throw ModelError(path, "", "cannot read file");
  }
  return text;
}

Json read_json_file(const std::string& path) {
  return parse_json_text(read_model_text(path), path);
}

// ---- describing and writing values --------------------------------------------------------

namespace {

std::string dump_scalar(const Json& j) {
  if (j.is_number_float() && !std::isfinite(j.get<double>())) {
    const double x = j.get<double>();
    return std::isnan(x) ? "nan" : (x > 0 ? "inf" : "-inf");
  }
  return j.dump();
}

bool is_scalar(const Json& j) {
  return !j.is_object() && !j.is_array();
}

bool is_scalar_array(const Json& j) {
  if (!j.is_array()) return false;
  for (const Json& e : j)
    if (!is_scalar(e)) return false;
  return true;
}

void write_pretty(std::string& out, const Json& j, int indent) {
  const std::string pad(static_cast<std::size_t>(indent + 2), ' ');
  const std::string close_pad(static_cast<std::size_t>(indent), ' ');
  if (is_scalar(j)) {
    out += j.dump();
  } else if (j.empty()) {
    out += j.is_array() ? "[]" : "{}";
  } else if (is_scalar_array(j)) {
    out += '[';
    bool first = true;
    for (const Json& e : j) {
      if (!first) out += ", ";
      out += e.dump();
      first = false;
    }
    out += ']';
  } else if (j.is_array()) {
    out += "[\n";
    for (std::size_t i = 0; i < j.size(); ++i) {
      out += pad;
      write_pretty(out, j[i], indent + 2);
      out += i + 1 < j.size() ? ",\n" : "\n";
    }
    out += close_pad + ']';
  } else {
    out += "{\n";
    std::size_t i = 0;
    for (auto it = j.begin(); it != j.end(); ++it, ++i) {
      out += pad + Json(it.key()).dump() + ": ";
      write_pretty(out, it.value(), indent + 2);
      out += i + 1 < j.size() ? ",\n" : "\n";
    }
    out += close_pad + '}';
  }
}

}  // namespace

namespace {

/// Appends the compact dump of j to out, stopping soon after out exceeds `limit` characters:
/// only what is shown is serialized (a large string is cut before it is escaped).
void dump_bounded(std::string& out, const Json& j, std::size_t limit) {
  if (out.size() > limit) return;
  if (j.is_string()) {
    const std::string& s = j.get_ref<const std::string&>();
    std::size_t n = std::min(s.size(), limit - out.size() + 1);
    while (n < s.size() && n > 0 && (static_cast<unsigned char>(s[n]) & 0xC0) == 0x80) --n;
    out += Json(s.substr(0, n)).dump(-1, ' ', false, Json::error_handler_t::replace);
    if (n < s.size()) out += "...";  // certainly over the limit: cut below
    return;
  }
  if (is_scalar(j)) {
    out += dump_scalar(j);
    return;
  }
  out += j.is_array() ? '[' : '{';
  bool first = true;
  for (auto it = j.begin(); it != j.end() && out.size() <= limit; ++it) {
    if (!first) out += ',';
    first = false;
    if (j.is_object()) {
      dump_bounded(out, Json(it.key()), limit);
      out += ':';
    }
    dump_bounded(out, it.value(), limit);
  }
  out += j.is_array() ? ']' : '}';
}

}  // namespace

std::string short_dump(const Json& j, std::size_t max_chars) {
  std::string s;
  dump_bounded(s, j, max_chars);
  if (s.size() > max_chars && max_chars > 3) {
    std::size_t cut = max_chars - 3;
    while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;  // UTF-8
    s = s.substr(0, cut) + "...";
  }
  return s;
}

std::string describe_json(const Json& j) {
  if (j.is_null()) return "null";
  return std::string(j.type_name()) + " " + short_dump(j);
}

std::string format_json(const Json& j) {
  std::string out;
  write_pretty(out, j, 0);
  return out;
}

// ---- JsonCursor ---------------------------------------------------------------------------

JsonCursor::JsonCursor(const Json& j, std::string file, JsonPointer at)
    : j_(&j), file_(std::move(file)), at_(std::move(at)) {}

bool JsonCursor::has(const std::string& key) const {
  return j_->is_object() && j_->contains(key);
}

JsonCursor JsonCursor::operator[](const std::string& key) const {
  if (!j_->is_object()) fail_type("an object");
  const auto it = j_->find(key);
  if (it == j_->end()) fail_plain("missing required key \"" + key + "\"");
  return JsonCursor(*it, file_, at_ / key);
}

JsonCursor JsonCursor::operator[](std::size_t index) const {
  if (!j_->is_array()) fail_type("an array");
  if (index >= j_->size())
    fail_plain("index " + std::to_string(index) + " out of range (the array has " +
               std::to_string(j_->size()) + " elements)");
  return JsonCursor((*j_)[index], file_, at_ / index);
}

std::size_t JsonCursor::size() const {
  if (!j_->is_array() && !j_->is_object()) fail_type("an array or an object");
  return j_->size();
}

std::vector<std::string> JsonCursor::keys() const {
  if (!j_->is_object()) fail_type("an object");
  std::vector<std::string> k;
  k.reserve(j_->size());
  for (auto it = j_->begin(); it != j_->end(); ++it) k.push_back(it.key());
  return k;
}

void JsonCursor::expect_object(std::initializer_list<const char*> allowed) const {
  if (!j_->is_object()) fail_type("an object");
  for (auto it = j_->begin(); it != j_->end(); ++it) {
    bool known = false;
    for (const char* a : allowed) known = known || it.key() == a;
    if (known) continue;
    std::string list;
    for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
    throw ModelError(file_, (at_ / it.key()).to_string(),
                     "unknown key \"" + it.key() + "\" (allowed here: " + list + ")");
  }
}

void JsonCursor::expect_array(std::size_t min_size) const {
  if (!j_->is_array()) fail_type("an array");
  if (j_->size() < min_size)
    fail("expected an array of at least " + std::to_string(min_size) + " element" +
         (min_size == 1 ? "" : "s"));
}

double JsonCursor::as_number() const {
  if (!j_->is_number()) fail_type("a number");
  const double x = j_->get<double>();
  if (!std::isfinite(x)) fail("expected a finite number");
  return x;
}

int JsonCursor::as_int() const {
  if (j_->is_number_integer()) {  // signed or unsigned
    if (j_->is_number_unsigned()) {
      const auto u = j_->get<std::uint64_t>();
      if (u > static_cast<std::uint64_t>(std::numeric_limits<int>::max()))
        fail("expected an integer in int range");
      return static_cast<int>(u);
    }
    const auto i = j_->get<std::int64_t>();
    if (i < std::numeric_limits<int>::min() || i > std::numeric_limits<int>::max())
      fail("expected an integer in int range");
    return static_cast<int>(i);
  }
  if (!j_->is_number()) fail_type("an integer");
  const double x = j_->get<double>();
  if (!(std::floor(x) == x) || std::abs(x) > std::numeric_limits<int>::max())
    fail("expected an integer");
  return static_cast<int>(x);
}

bool JsonCursor::as_bool() const {
  if (!j_->is_boolean()) fail_type("true or false");
  return j_->get<bool>();
}

std::string JsonCursor::as_string() const {
  if (!j_->is_string()) fail_type("a string");
  return j_->get<std::string>();
}

std::vector<double> JsonCursor::as_numbers() const {
  expect_array();
  std::vector<double> x(j_->size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = (*this)[i].as_number();
  return x;
}

void JsonCursor::fail(const std::string& message) const {
  throw ModelError(file_, at_.to_string(), message + ", got " + short_dump(*j_));
}

void JsonCursor::fail_plain(const std::string& message) const {
  throw ModelError(file_, at_.to_string(), message);
}

void JsonCursor::fail_type(const std::string& expected) const {
  throw ModelError(file_, at_.to_string(), "expected " + expected + ", got " + describe_json(*j_));
}

}  // namespace iga
