// Reading a parameters YAML file (what `rosparam load` would put on the parameter server) into a
// costmap_layers::ParamValue tree, and writing a tree back as such a file, without ROS. Uses yaml-cpp.
//
// Structure: maps become Map (keys in document order; a repeated key keeps its first position and
// the last value, as rosparam does, and is described in repeated_keys when that is given),
// sequences become List, an empty document becomes Null. Aliases (*name) are expanded, and the
// YAML 1.1 merge key `<<: *base` (or `<<: [*a, *b]`) merges the maps in as rosparam/PyYAML do: keys
// written in the map itself win, then earlier merged maps win over later.
//
// Scalars are typed the way rosparam (PyYAML, YAML 1.1 rules) types plain scalars:
//   Null    ~  null Null NULL  and an empty value
//   Bool    true/false yes/no on/off in lower case, Capitalised or UPPER case (True, YES, Off, ...)
//   Int     decimal with optional sign (42, -7, +3, 1_000), 0x hex, 0b binary, 0-prefixed octal
//           (010 = 8), as PyYAML; a value beyond int64 becomes a Double
//   Double  1.0  -2.5  1.  .5  6.02e23  1.0e+3  .inf  -.inf  +.inf  .nan (also .Inf, .NAN, ...)
//           Note: this accepts a little more than PyYAML, which requires a dot and a signed exponent
//           and so reads "1e3", "1e-3" and "-.5" as strings; here they are numbers, unless
//           rosparam_floats asks for PyYAML's rule (what a file loaded by `rosparam load` gets:
//           costmap_tool reads its --params so, to refuse what costmap_node would refuse).
//   String  everything else (e.g. "09", "1.2.3", "0o17", "y", "n", dates, and sexagesimal "1:30",
//           which PyYAML would read as the number 90)
// Quoted ('...' or "...") and block (| or >) scalars are always String: yaml-cpp gives them the
// tag "!". Explicit standard tags are honoured: !!str -> String, !!int -> Int, !!float -> Double,
// !!bool -> Bool, !!null -> Null (an error when the text does not fit the tag). Other tags
// (e.g. !degrees) are ignored and the scalar is typed as if plain.
//
// Errors throw std::runtime_error with one line: the source name (`what`, or the file path), the
// line and column for YAML syntax errors, and the problem.
//
// Bounds: nesting deeper than 256 levels is refused, and so is a document whose tree would have
// more than kMaxYamlNodes values. yaml-cpp keeps an alias as a second reference to the anchored
// node, but the tree built here is plain data, so every alias is expanded into a copy: nine levels
// of ten aliases each (the "billion laughs", under 500 bytes) would make 10^9 values. Aliases and
// merge keys are kept (real configs use `<<: *base`), and the expansion is bounded instead: the
// budget counts every value the conversion creates, aliases included. It is twice the number of
// values an alias-free document of kMaxParamsYamlBytes can hold (each value takes at least 2 bytes,
// e.g. "1," in a flow list), so only alias expansion can reach it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "costmap_layers/core/config/param_value.hpp"
#include "costmap_layers/io/file_limits.hpp"

namespace costmap_layers
{
namespace io
{
/// The most values (scalars, lists, maps, each counted once per copy) one document may expand to.
constexpr uint64_t kMaxYamlNodes = uint64_t{1} << 18;

/// Parses YAML text; `what` names the source in error messages (e.g. a file name or "--params").
/// repeated_keys, when given, receives one line per key written twice in one map (where, which key,
/// where it was first), for the first 20 such keys, then one line counting the rest. max_nodes: the
/// value budget (kMaxYamlNodes; a format with a larger byte cap passes its own, e.g. zone files).
ParamValue parseParamsYaml(const std::string& text, const std::string& what, bool rosparam_floats = false,
                           std::vector<std::string>* repeated_keys = nullptr, uint64_t max_nodes = kMaxYamlNodes);

/// Reads and parses a YAML file: a regular file of at most max_bytes (file_limits.hpp); an error
/// names the path when it cannot be opened, is not a regular file or is too large.
ParamValue loadParamsYamlFile(const std::string& path, uint64_t max_bytes = kMaxParamsYamlBytes,
                              bool rosparam_floats = false, std::vector<std::string>* repeated_keys = nullptr,
                              uint64_t max_nodes = kMaxYamlNodes);

/// loadParamsYamlFile for this package's own file formats (zones, features): there is no rosparam
/// habit to keep, so a key written twice in one map, whose first value would be lost, refuses the file.
ParamValue loadOwnFormatYamlFile(const std::string& path, uint64_t max_bytes = kMaxParamsYamlBytes,
                                 uint64_t max_nodes = kMaxYamlNodes);

/// Throws, naming the first of repeated_keys (parseParamsYaml's lines) and how many more, unless empty.
void refuseRepeatedKeys(const std::vector<std::string>& repeated_keys);

/// The typing rule for one plain (unquoted, untagged) scalar, exposed for tests and for tools that
/// take "key:=value" arguments on a command line.
ParamValue typePlainScalar(const std::string& text, bool rosparam_floats = false);

/// A tree as YAML text for a user to paste into a params file (e.g. CompatResult::plugin_list), in the
/// layout costmap files are written in: maps in block style; a list that holds a map as a block
/// sequence of inline items (`plugins:\n  - {name: "a", type: "b"}`); every other list, and anything
/// inside a list, inline (`footprint: [[1.0, 2.5]]`). Strings are double-quoted (so "true", "1e3" or
/// "a: b" stay strings), Null is `null`, and a double has a decimal point in the shortest form that
/// reads back to the same double (3.0, 0.1, 1.0e-300, .inf, .nan): PyYAML (rosparam) takes a number
/// without a dot or with an unsigned exponent for a string. parseParamsYaml(), with or without
/// rosparam_floats, reads the text back to an equal tree. The text ends with a newline.
/// Throws std::runtime_error when yaml-cpp refuses to write the tree.
std::string paramToYaml(const ParamValue& value);
}  // namespace io
}  // namespace costmap_layers
