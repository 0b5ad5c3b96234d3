// What is wrong with an input, as a small result: the field at fault (a stable key for throttling and
// for tests, never a value from the message) and one line naming the field and its value.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace costmap_layers
{
struct InputError
{
  std::string field;    ///< e.g. "info.resolution", "data", "header.stamp"; empty when the input is fine
  std::string message;  ///< e.g. "info.resolution must be finite and positive (got nan)"

  bool ok() const { return message.empty(); }
  static InputError none() { return {}; }
  static InputError of(std::string field, std::string message) { return {std::move(field), std::move(message)}; }
};

/// A number as an error message shows it: the stream's default form (0.3, 1e+300, nan, inf).
std::string valueText(double value);
/// A sender's text (a frame_id, a topic) as a message shows it: at most max characters, then how long
/// it was, so that a megabyte name does not become a megabyte log line.
std::string shownText(const std::string& text, std::size_t max = 64);
/// A list of names as a message shows it: the first `listed` (each clipped to 64 characters), then
/// "and N more", so that a list of thousands does not become a line of thousands.
std::string namesText(const std::vector<std::string>& names, std::size_t listed = 8);
/// Why `name` is not a ROS graph resource name (roscpp's rule: a letter, '/' or, when allow_private,
/// '~' first, then letters, digits, '_' and '/'), or "" when it is one. The reason quotes the name
/// (clipped) and the first character at fault.
std::string rosNameProblem(const std::string& name, bool allow_private = true);

// One rule for each kind of name, used wherever that kind is read: a parameter, a message, a file.
// Each returns why the name is refused (quoting it, clipped, with the first character at fault) or "".

/// Longest frame id, plugin name or shape name accepted (real ones have a few dozen characters).
constexpr std::size_t kMaxNameLength = 256;
/// A tf frame id: 1..kMaxNameLength printable ASCII characters, no space or control character (tf2
/// would look a "map\nodom" up as it is and never find it; a file would read it back changed).
std::string frameIdProblem(const std::string& frame_id);
/// A plugin's name in a costmap's plugin list: a relative ROS name (a letter first, then letters,
/// digits, '_' and single '/' between parts), as costmap_2d and roscpp need it to make the plugin's
/// parameter namespace; at most kMaxNameLength characters.
std::string pluginNameProblem(const std::string& name);
/// A name shown to people and used as a key (a zone shape's name): 1..kMaxNameLength bytes, no
/// control character (UTF-8 letters are fine).
std::string labelProblem(const std::string& name);
}  // namespace costmap_layers
