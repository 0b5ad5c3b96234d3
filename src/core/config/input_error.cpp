#include "costmap_layers/core/config/input_error.hpp"

#include <sstream>

namespace costmap_layers
{
std::string valueText(double value)
{
  std::ostringstream s;
  s << value;
  return s.str();
}

std::string shownText(const std::string& text, std::size_t max)
{
  if (text.size() <= max) return text;
  return text.substr(0, max) + "... (" + std::to_string(text.size()) + " characters)";
}

std::string namesText(const std::vector<std::string>& names, std::size_t listed)
{
  std::string out;
  for (std::size_t k = 0; k < names.size() && k < listed; ++k)
    out += (k == 0 ? "" : ", ") + shownText(names[k]);
  if (names.size() > listed) out += " and " + std::to_string(names.size() - listed) + " more";
  return out;
}

std::string rosNameProblem(const std::string& name, bool allow_private)
{
  if (name.empty()) return "is empty, not a ROS name";
  const auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
  for (std::size_t k = 0; k < name.size(); ++k)
  {
    const char c = name[k];
    const bool ok = k == 0 ? letter(c) || c == '/' || (allow_private && c == '~')
                           : letter(c) || (c >= '0' && c <= '9') || c == '_' || c == '/';
    if (ok) continue;
    const bool printable = c > ' ' && c < 127;
    std::string shown;
    for (const char d : shownText(name, 200))
      shown += d >= ' ' && d < 127 ? d : '?';
    return "'" + shown + "' is not a ROS name: " +
           (printable ? "'" + std::string(1, c) + "'"
                      : std::string("character code ") + std::to_string(static_cast<unsigned char>(c))) +
           " at position " + std::to_string(k) + " (a letter, '/'" + (allow_private ? " or '~'" : "") +
           " first, then letters, digits, '_' and '/')";
  }
  return "";
}

namespace
{
/// The name as a message quotes it: clipped, control and non-ASCII bytes as '?'.
std::string quoted(const std::string& name)
{
  std::string shown;
  for (const char d : shownText(name, 200))
    shown += d >= ' ' && d < 127 ? d : '?';
  return "'" + shown + "'";
}

std::string characterAt(const std::string& name, std::size_t k)
{
  const char c = name[k];
  const bool printable = c > ' ' && c < 127;
  return (printable ? "'" + std::string(1, c) + "'"
                    : std::string("character code ") + std::to_string(static_cast<unsigned char>(c))) +
         " at position " + std::to_string(k);
}

std::string tooLong(const std::string& name, const char* what)
{
  return quoted(name) + " is too long for " + what + ": " + std::to_string(name.size()) + " characters, at most " +
         std::to_string(kMaxNameLength);
}
}  // namespace

std::string frameIdProblem(const std::string& frame_id)
{
  if (frame_id.empty()) return "is empty, not a frame id";
  if (frame_id.size() > kMaxNameLength) return tooLong(frame_id, "a frame id");
  for (std::size_t k = 0; k < frame_id.size(); ++k)
  {
    const char c = frame_id[k];
    if (c > ' ' && c < 127) continue;
    return quoted(frame_id) + " is not a frame id: " + characterAt(frame_id, k) +
           " (printable ASCII without spaces only)";
  }
  return "";
}

std::string pluginNameProblem(const std::string& name)
{
  if (name.empty()) return "is empty, not a plugin name";
  if (name.size() > kMaxNameLength) return tooLong(name, "a plugin name");
  const auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
  for (std::size_t k = 0; k < name.size(); ++k)
  {
    const char c = name[k];
    const bool part_start = k == 0 || name[k - 1] == '/';
    const bool ok = part_start ? letter(c) || (k > 0 && c == '_')
                               : letter(c) || (c >= '0' && c <= '9') || c == '_' || (c == '/' && k + 1 < name.size());
    if (ok) continue;
    return quoted(name) + " is not a plugin name: " + characterAt(name, k) +
           " (a letter first, then letters, digits and '_', parts separated by single '/')";
  }
  return "";
}

std::string labelProblem(const std::string& name)
{
  if (name.empty()) return "is empty";
  if (name.size() > kMaxNameLength) return tooLong(name, "a name");
  for (std::size_t k = 0; k < name.size(); ++k)
  {
    const auto c = static_cast<unsigned char>(name[k]);
    if (c >= ' ' && c != 127) continue;
    return quoted(name) + " is not a name: " + characterAt(name, k) + " (no control characters)";
  }
  return "";
}
}  // namespace costmap_layers
