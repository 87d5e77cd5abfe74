// Reading JSON input with errors that name the file, the JSON path, the value and what was
// expected, and writing JSON back readably. Used by every loader (geometry here, analysis
// models in iga/). Paths are RFC 6901 JSON pointers; the format is docs/model_format.md.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace iga {

/// The JSON type of all model I/O: objects keep the order of the file (nlohmann::json would
/// sort keys). A nlohmann::json converts implicitly (its keys then come alphabetically).
using Json = nlohmann::ordered_json;
using JsonPointer = nlohmann::json::json_pointer;  // same type as Json::json_pointer

/// Bad model input. what() = "<file>: <json pointer>: <message>"; the pointer part is left
/// out when the pointer is "" (the document root).
class ModelError : public std::runtime_error {
 public:
  ModelError(std::string file, std::string pointer, const std::string& message);
  const std::string& file() const { return file_; }
  const std::string& pointer() const { return pointer_; }
  /// The message without the file and pointer prefix.
  const std::string& message() const { return message_; }

 private:
  std::string file_, pointer_, message_;
};

/// Limits of every JSON document read (docs/model_format.md, section 1). They bound what a
/// hostile or broken file can cost before anything is built from it:
/// - a model file is a regular file of at most 64 MiB (real models are kilobytes; a 10^6-point
///   NURBS net is about 60 MB of text);
/// - arrays and objects nest at most 256 deep (models need 5), so that no recursive code
///   (writing, error messages) ever sees a deeper document;
/// - a document holds at most 10 million JSON values (numbers, strings, arrays, objects...),
///   so that the parsed document stays below about 1 GB even for a file of `[0,0,0,...]`.
constexpr std::size_t kMaxModelFileBytes = std::size_t{64} << 20;
constexpr std::size_t kMaxJsonDepth = 256;
constexpr std::size_t kMaxJsonValues = 10'000'000;

/// The whole text of a model file. Raises ModelError naming the file, before reading
/// anything, unless `path` is a regular file (not a directory, FIFO or device) of at most
/// `max_bytes` bytes; also when it cannot be opened or read. Every reader of model files goes
/// through here.
std::string read_model_text(const std::string& path, std::size_t max_bytes = kMaxModelFileBytes);
/// read_model_text + parse_json_text. Malformed JSON raises ModelError with line and column
/// and the JSON path reached; numbers that overflow a double (1e999), duplicate keys in an
/// object, nesting deeper than kMaxJsonDepth and more than kMaxJsonValues values are rejected
/// the same way. A UTF-8 byte-order mark at the start is skipped.
Json read_json_file(const std::string& path);
/// The same checks on text already in memory; `file` is used in messages only.
Json parse_json_text(const std::string& text, const std::string& file);

/// "string \"abc\"", "number 3", "null", "array [1,2]": type name and compact value.
std::string describe_json(const Json& j);
/// Compact dump, cut to about `max_chars` characters with "..." (doubles round-trip). Only the
/// part shown is serialized: a huge or deep value costs no more than a small one.
std::string short_dump(const Json& j, std::size_t max_chars = 60);
/// Indented dump that keeps arrays of scalars on one line ("[0.0, 1.0, 2.5]"); doubles are
/// written with round-trip precision. Ends without a newline.
std::string format_json(const Json& j);

/// A read-only cursor into a JSON document that knows where it is. Accessors check types and
/// finiteness and throw ModelError naming the path, the value and what was expected.
/// The document must outlive the cursor.
class JsonCursor {
 public:
  JsonCursor(const Json& j, std::string file, JsonPointer at = JsonPointer());

  const Json& json() const { return *j_; }
  const std::string& file() const { return file_; }
  const JsonPointer& path() const { return at_; }

  bool has(const std::string& key) const;  ///< false unless an object with that key
  /// Child by key (must exist) / by index (must be in range).
  JsonCursor operator[](const std::string& key) const;
  JsonCursor operator[](std::size_t index) const;
  std::size_t size() const;  ///< array length or object size
  /// Object keys in document order.
  std::vector<std::string> keys() const;

  /// Throws unless the value is an object whose keys are all in `allowed`; an unknown key is
  /// reported at its own path, with the list of allowed keys.
  void expect_object(std::initializer_list<const char*> allowed) const;
  void expect_array(std::size_t min_size = 0) const;

  double as_number() const;  ///< finite number
  int as_int() const;        ///< integer in int range (2.0 is accepted, 2.5 is not)
  bool as_bool() const;
  std::string as_string() const;
  std::vector<double> as_numbers() const;  ///< array of finite numbers

  /// Throws ModelError at this path: "<file>: <path>: <message>, got <value>".
  [[noreturn]] void fail(const std::string& message) const;
  /// Same, without the value.
  [[noreturn]] void fail_plain(const std::string& message) const;
  /// "<message>, got <type> <value>" for type mismatches ("expected a number, got string \"a\"").
  [[noreturn]] void fail_type(const std::string& expected) const;

 private:
  const Json* j_;
  std::string file_;
  JsonPointer at_;
};

}  // namespace iga
