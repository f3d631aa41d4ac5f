// JSON input: parsing with positions in the error, and validation against the
// JSON Schemas of schemas/ (draft-07, embedded in the binary).
//
// Every problem is a SchemaViolation: a JSON pointer into the document and a
// rule in plain words, with the unit taken from the schema's custom "unit"
// keyword where the rule is a bound:
//   /strength/A: must be >= 0 (Pa)
//   /elastic/nu: must be < 0.5 (-)
//   /density: must be a number, got string
//   /strength/B: required field is missing        (pointer of the missing field)
//   /strength/foo: unknown field
//   /damage/initiation/model: must be one of "none", "johnson-cook", "shear"
// Validation itself is valijson's; schema.cpp (the only file that includes
// valijson) turns its reports into these lines. Nothing here knows a
// particular schema: any file schemas/NAME.schema.json is available as NAME.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace splat {

struct SchemaViolation {
  std::string pointer;  // JSON pointer of the offending value, "" = the whole document
  std::string message;  // the rule broken, e.g. "must be >= 0 (Pa)"

  friend bool operator==(const SchemaViolation&, const SchemaViolation&) = default;
};

// "POINTER: MESSAGE", or just MESSAGE when the pointer is "" (whole document).
std::string to_string(const SchemaViolation& v);
std::ostream& operator<<(std::ostream& os, const SchemaViolation& v);

// Invalid input: every violation found, one per line in what().
class InputError : public std::runtime_error {
 public:
  explicit InputError(std::vector<SchemaViolation> violations);
  const std::vector<SchemaViolation>& violations() const { return violations_; }

 private:
  std::vector<SchemaViolation> violations_;
};

// Names of the embedded schemas ("material", ...), sorted.
std::vector<std::string> schema_names();

// The parsed embedded schema NAME. Throws std::invalid_argument for an
// unknown name. The reference stays valid for the life of the program.
const nlohmann::json& schema_document(std::string_view name);

// Violations of `doc` against the embedded schema (compiled once, cached,
// safe to call from several threads); empty = valid. Throws
// std::invalid_argument for an unknown schema name.
std::vector<SchemaViolation> validate(std::string_view schema_name, const nlohmann::json& doc);

// Throws InputError with all violations if there are any.
void validate_or_throw(std::string_view schema_name, const nlohmann::json& doc);

// Same as validate() against a schema given as a document (compiled on each
// call, not cached): for schemas built at run time and for tests.
// Throws std::invalid_argument if `schema` is not a valid draft-07 schema.
std::vector<SchemaViolation> validate_against(const nlohmann::json& schema,
                                              const nlohmann::json& doc);

// Arrays and objects nest at most this deep in JSON input (scenes use less
// than 10 levels); deeper text is refused while it is parsed.
constexpr int k_max_json_depth = 64;  // levels, -

// Parses JSON text. `what` names the text in messages ("file 'a.json'").
// Malformed text, a field given twice in one object or nesting deeper than
// k_max_json_depth throws InputError with one violation: pointer "" and
// "malformed JSON in WHAT at line L, column C: REASON", or the pointer of the
// repeated field and "duplicate field", or the pointer of the container one
// level too deep.
nlohmann::json parse_json_text(std::string_view text, std::string_view what);

// Reads and parses a JSON file; a missing, unreadable or malformed file throws
// InputError (pointer "") whose message names the file.
nlohmann::json read_json_file(const std::filesystem::path& path);

// Violations with `prefix` put in front of each pointer, for documents nested
// in others (a material inside a scene: prefix "/bodies/0/material").
std::vector<SchemaViolation> prefixed(std::string_view prefix,
                                      std::vector<SchemaViolation> violations);

}  // namespace splat
