#include "costmap_layers/io/param_yaml.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

namespace costmap_layers
{
namespace io
{
namespace
{
constexpr int kMaxDepth = 256;

const std::string kTagStr = "tag:yaml.org,2002:str";
const std::string kTagInt = "tag:yaml.org,2002:int";
const std::string kTagFloat = "tag:yaml.org,2002:float";
const std::string kTagBool = "tag:yaml.org,2002:bool";
const std::string kTagNull = "tag:yaml.org,2002:null";

bool isDigitIn(char c, int base)
{
  if (base == 2) return c == '0' || c == '1';
  if (base == 8) return c >= '0' && c <= '7';
  if (base == 10) return c >= '0' && c <= '9';
  return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}

int digitValue(char c)
{
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return c - 'A' + 10;
}

std::optional<bool> parseBool(const std::string& s)
{
  static const char* const kTrue[] = {"true", "True", "TRUE", "yes", "Yes", "YES", "on", "On", "ON"};
  static const char* const kFalse[] = {"false", "False", "FALSE", "no", "No", "NO", "off", "Off", "OFF"};
  for (const char* t : kTrue)
  {
    if (s == t) return true;
  }
  for (const char* f : kFalse)
  {
    if (s == f) return false;
  }
  return std::nullopt;
}

bool isNullText(const std::string& s)
{
  return s.empty() || s == "~" || s == "null" || s == "Null" || s == "NULL";
}

/// PyYAML's int forms. Returns Int, or Double when the value does not fit int64, or Null (no match).
ParamValue parseInt(const std::string& s)
{
  size_t pos = 0;
  bool negative = false;
  if (pos < s.size() && (s[pos] == '+' || s[pos] == '-'))
  {
    negative = (s[pos] == '-');
    ++pos;
  }
  if (pos >= s.size()) return ParamValue();
  int base = 10;
  if (s[pos] == '0' && pos + 1 < s.size())
  {
    const char p = s[pos + 1];
    if (p == 'x' || p == 'b')
    {
      base = (p == 'x') ? 16 : 2;
      pos += 2;
    }
    else
    {
      base = 8;  // 0[0-7_]+
      pos += 1;
    }
  }
  if (pos >= s.size()) return ParamValue();
  uint64_t magnitude = 0;
  double approx = 0.0;
  bool overflow = false;
  bool any_digit = false;
  for (; pos < s.size(); ++pos)
  {
    const char c = s[pos];
    if (c == '_') continue;
    if (!isDigitIn(c, base)) return ParamValue();
    any_digit = true;
    const auto d = static_cast<uint64_t>(digitValue(c));
    approx = approx * base + static_cast<double>(d);
    if (magnitude > (std::numeric_limits<uint64_t>::max() - d) / static_cast<uint64_t>(base)) overflow = true;
    magnitude = magnitude * static_cast<uint64_t>(base) + d;
  }
  if (!any_digit) return base == 8 ? ParamValue::makeInt(0) : ParamValue();  // "0_" is octal 0
  const uint64_t limit = negative ? uint64_t{1} << 63 : (uint64_t{1} << 63) - 1;
  if (overflow || magnitude > limit) return ParamValue::makeDouble(negative ? -approx : approx);
  if (negative)
    return ParamValue::makeInt(magnitude == (uint64_t{1} << 63) ? std::numeric_limits<int64_t>::min()
                                                                : -static_cast<int64_t>(magnitude));
  return ParamValue::makeInt(static_cast<int64_t>(magnitude));
}

std::optional<double> parseFloat(const std::string& s, bool rosparam_floats)
{
  size_t pos = 0;
  bool negative = false;
  if (pos < s.size() && (s[pos] == '+' || s[pos] == '-'))
  {
    negative = (s[pos] == '-');
    ++pos;
  }
  const std::string rest = s.substr(pos);
  if (rest == ".inf" || rest == ".Inf" || rest == ".INF")
    return negative ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
  if (pos == 0 && (rest == ".nan" || rest == ".NaN" || rest == ".NAN")) return std::numeric_limits<double>::quiet_NaN();

  // [digits] ['.' [digits]] [e|E [sign] digits], with '_' allowed in the mantissa digits;
  // at least one mantissa digit, and a dot or an exponent.
  std::string clean = negative ? "-" : "";
  size_t mantissa_digits = 0;
  bool dot = false;
  bool exponent = false;
  for (; pos < s.size(); ++pos)
  {
    const char c = s[pos];
    if (c >= '0' && c <= '9')
    {
      ++mantissa_digits;
      clean += c;
    }
    else if (c == '_' && mantissa_digits > 0)
    {
    }
    else if (c == '.' && !dot)
    {
      dot = true;
      clean += c;
    }
    else
    {
      break;
    }
  }
  if (mantissa_digits == 0) return std::nullopt;
  if (pos < s.size() && (s[pos] == 'e' || s[pos] == 'E'))
  {
    exponent = true;
    clean += 'e';
    ++pos;
    if (pos < s.size() && (s[pos] == '+' || s[pos] == '-')) clean += s[pos++];
    size_t exp_digits = 0;
    for (; pos < s.size() && s[pos] >= '0' && s[pos] <= '9'; ++pos, ++exp_digits)
      clean += s[pos];
    if (exp_digits == 0) return std::nullopt;
  }
  if (pos != s.size() || (!dot && !exponent)) return std::nullopt;
  if (rosparam_floats)
  {
    // PyYAML's float resolver: a dot always; an exponent with its sign; no sign before a leading dot.
    const std::size_t e = s.find_first_of("eE");
    const bool signed_leading_dot = (s[0] == '+' || s[0] == '-') && s.size() > 1 && s[1] == '.';
    if (!dot || (e != std::string::npos && s[e + 1] != '+' && s[e + 1] != '-') || signed_leading_dot)
      return std::nullopt;
  }
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(clean.c_str(), &end);
  if (end == nullptr || *end != '\0') return std::nullopt;
  return v;  // overflow gives +-inf, as in PyYAML
}

class Converter
{
public:
  Converter(const std::string& what, bool rosparam_floats, std::vector<std::string>* repeated_keys, uint64_t max_nodes)
      : what_(what), rosparam_floats_(rosparam_floats), repeated_keys_(repeated_keys), max_nodes_(max_nodes)
  {
  }

  ParamValue convert(const YAML::Node& node, int depth)
  {
    if (depth > kMaxDepth) fail(node, "nesting deeper than " + std::to_string(kMaxDepth) + " levels");
    // Every value converted counts, however it was reached: an alias is expanded into a copy here.
    if (++nodes_ > max_nodes_)
      fail(node, "the document expands to more than " + std::to_string(max_nodes_) +
                     " values (aliases (*name) are copied each time they are used: is it an alias bomb?)");
    switch (node.Type())
    {
      case YAML::NodeType::Undefined:
      case YAML::NodeType::Null:
        return ParamValue();
      case YAML::NodeType::Scalar:
        return scalar(node);
      case YAML::NodeType::Sequence:
      {
        ParamValue list = ParamValue::makeList();
        for (const YAML::Node& item : node)
          list.push(convert(item, depth + 1));
        return list;
      }
      case YAML::NodeType::Map:
        return map(node, depth);
    }
    return ParamValue();
  }

private:
  [[noreturn]] void fail(const YAML::Node& node, const std::string& problem) const
  {
    const YAML::Mark mark = node.Mark();
    std::string where;
    if (mark.line >= 0) where = " at line " + std::to_string(mark.line + 1);
    throw std::runtime_error(what_ + where + ": " + problem);
  }

  ParamValue scalar(const YAML::Node& node) const
  {
    const std::string& tag = node.Tag();
    const std::string& text = node.Scalar();
    if (tag == "!" || tag == kTagStr) return ParamValue::makeString(text);
    if (tag == kTagInt)
    {
      ParamValue v = parseInt(text);
      if (v.type() != ParamValue::Type::Int) fail(node, "'" + text + "' is not a valid !!int");
      return v;
    }
    if (tag == kTagFloat)
    {
      ParamValue i = parseInt(text);
      if (i.isNumber()) return ParamValue::makeDouble(i.asDouble());
      const auto f = parseFloat(text, false);
      if (!f) fail(node, "'" + text + "' is not a valid !!float");
      return ParamValue::makeDouble(*f);
    }
    if (tag == kTagBool)
    {
      const auto b = parseBool(text);
      if (!b) fail(node, "'" + text + "' is not a valid !!bool");
      return ParamValue::makeBool(*b);
    }
    if (tag == kTagNull)
    {
      if (!isNullText(text)) fail(node, "'" + text + "' is not a valid !!null");
      return ParamValue();
    }
    return typePlainScalar(text, rosparam_floats_);
  }

  ParamValue map(const YAML::Node& node, int depth)
  {
    std::vector<std::pair<std::string, ParamValue>> own;
    std::vector<ParamValue> merged;
    std::map<std::string, int> first_line;  // of each own key (0 when unknown)
    for (const auto& kv : node)
    {
      const YAML::Node& key = kv.first;
      if (!key.IsScalar() && !key.IsNull()) fail(key, "a map key must be a plain value, not a list or map");
      const std::string name = key.IsNull() ? std::string() : key.Scalar();
      if (name == "<<" && key.Tag() != "!")
      {
        const YAML::Node& src = kv.second;
        if (src.IsMap())
        {
          merged.push_back(convert(src, depth + 1));
        }
        else if (src.IsSequence())
        {
          for (const YAML::Node& item : src)
          {
            if (!item.IsMap()) fail(item, "a merge key '<<' needs a map or a list of maps");
            merged.push_back(convert(item, depth + 1));
          }
        }
        else
        {
          fail(src, "a merge key '<<' needs a map or a list of maps");
        }
        continue;
      }
      if (repeated_keys_ != nullptr)  // only asked for: no lookup table otherwise
      {
        const int line = key.Mark().line >= 0 ? key.Mark().line + 1 : 0;
        const auto [seen, is_new] = first_line.emplace(name, line);
        if (!is_new) noteRepeat(name, line, seen->second);
      }
      own.emplace_back(name, convert(kv.second, depth + 1));
    }
    ParamValue out = ParamValue::makeMap();
    // Earlier merged maps win over later ones; the map's own keys win over all of them.
    for (auto it = merged.rbegin(); it != merged.rend(); ++it)
    {
      for (const auto& entry : it->entries())
        out.set(entry.first, entry.second);
    }
    for (auto& entry : own)
      out.set(entry.first, std::move(entry.second));
    return out;
  }

  /// One line per repeated key into repeated_keys_ (set), the first kMaxRepeatedKeyLines of them (a key
  /// cut to 64 characters); finishRepeats() counts the rest.
  void noteRepeat(const std::string& name, int line, int first)
  {
    if (++repeats_ > kMaxRepeatedKeyLines) return;
    const std::string shown = name.size() > 64 ? name.substr(0, 64) + "..." : name;
    repeated_keys_->push_back(what_ + (line > 0 ? " at line " + std::to_string(line) : std::string()) + ": key '" +
                              shown + "' is written twice in one map" +
                              (first > 0 ? " (first at line " + std::to_string(first) + ")" : "") +
                              "; the last value is used");
  }

public:
  void finishRepeats() const
  {
    if (repeated_keys_ != nullptr && repeats_ > kMaxRepeatedKeyLines)
      repeated_keys_->push_back(what_ + ": " + std::to_string(repeats_ - kMaxRepeatedKeyLines) +
                                " more keys written twice (not listed); the last value of each is used");
  }

private:
  static constexpr uint64_t kMaxRepeatedKeyLines = 20;
  const std::string& what_;
  bool rosparam_floats_;  ///< type plain floats as PyYAML does (see parseParamsYaml)
  std::vector<std::string>* repeated_keys_;
  uint64_t repeats_ = 0;
  uint64_t max_nodes_;
  uint64_t nodes_ = 0;
};
}  // namespace

ParamValue typePlainScalar(const std::string& text, bool rosparam_floats)
{
  if (isNullText(text)) return ParamValue();
  if (const auto b = parseBool(text)) return ParamValue::makeBool(*b);
  const char first = text[0];
  if ((first >= '0' && first <= '9') || first == '+' || first == '-' || first == '.')
  {
    ParamValue i = parseInt(text);
    if (i.isNumber()) return i;
    if (const auto f = parseFloat(text, rosparam_floats)) return ParamValue::makeDouble(*f);
  }
  return ParamValue::makeString(text);
}

ParamValue parseParamsYaml(const std::string& text, const std::string& what, bool rosparam_floats,
                           std::vector<std::string>* repeated_keys, uint64_t max_nodes)
{
  YAML::Node root;
  try
  {
    root = YAML::Load(text);
  }
  catch (const YAML::Exception& e)
  {
    throw std::runtime_error(what + ": YAML syntax error at line " + std::to_string(e.mark.line + 1) + ", column " +
                             std::to_string(e.mark.column + 1) + ": " + e.msg);
  }
  try
  {
    Converter converter(what, rosparam_floats, repeated_keys, max_nodes);
    ParamValue tree = converter.convert(root, 0);
    converter.finishRepeats();
    return tree;
  }
  catch (const YAML::Exception& e)
  {
    throw std::runtime_error(what + ": YAML error: " + e.msg);
  }
}

ParamValue loadParamsYamlFile(const std::string& path, uint64_t max_bytes, bool rosparam_floats,
                              std::vector<std::string>* repeated_keys, uint64_t max_nodes)
{
  const std::vector<uint8_t> bytes = readRegularFile(path, "params file", max_bytes);
  return parseParamsYaml(std::string(bytes.begin(), bytes.end()), "'" + path + "'", rosparam_floats, repeated_keys,
                         max_nodes);
}

void refuseRepeatedKeys(const std::vector<std::string>& repeated_keys)
{
  if (repeated_keys.empty()) return;
  throw std::runtime_error(
      repeated_keys.front() + ": a value would be lost, so the file is refused" +
      (repeated_keys.size() > 1 ? " (" + std::to_string(repeated_keys.size() - 1) + " more repeated keys)" : ""));
}

ParamValue loadOwnFormatYamlFile(const std::string& path, uint64_t max_bytes, uint64_t max_nodes)
{
  std::vector<std::string> repeated;
  ParamValue tree = loadParamsYamlFile(path, max_bytes, false, &repeated, max_nodes);
  refuseRepeatedKeys(repeated);
  return tree;
}

namespace
{
/// The shortest text that reads back to v (std::to_chars' round-trip guarantee), with the decimal point
/// and signed exponent PyYAML needs to read it as a float: "3" -> "3.0", "1e-300" -> "1.0e-300",
/// "1e+22" stays signed. Infinities and NaN in YAML's spelling.
std::string doubleText(double v)
{
  if (std::isnan(v)) return ".nan";
  if (std::isinf(v)) return v > 0 ? ".inf" : "-.inf";
  char buf[64];
  const std::to_chars_result res = std::to_chars(buf, buf + sizeof(buf), v);
  const std::string shortest(buf, res.ptr);
  const std::size_t e = shortest.find('e');
  std::string mantissa = shortest.substr(0, e);
  if (mantissa.find('.') == std::string::npos) mantissa += ".0";
  if (e == std::string::npos) return mantissa;
  std::string exponent = shortest.substr(e + 1);
  if (exponent.front() != '+' && exponent.front() != '-') exponent.insert(0, "+");
  return mantissa + "e" + exponent;
}

void emitKey(YAML::Emitter& out, const std::string& key)
{
  // A plain "<<" would read back as a merge key; the reader takes a quoted one as a name.
  if (key == "<<") out << YAML::DoubleQuoted;
  out << YAML::Key << key << YAML::Value;
}

void emitScalar(YAML::Emitter& out, const ParamValue& v)
{
  switch (v.type())
  {
    case ParamValue::Type::Null:
      out << YAML::Null;
      break;
    case ParamValue::Type::Bool:
      out << v.asBool();
      break;
    case ParamValue::Type::Int:
      out << v.asInt();
      break;
    case ParamValue::Type::Double:
      // Written as text: yaml-cpp's own double output drops the ".0" of whole numbers (read back as Int).
      // The text is a valid plain scalar, so the emitter leaves it unquoted.
      out << doubleText(v.asDouble());
      break;
    case ParamValue::Type::String:
      out << YAML::DoubleQuoted << v.asString();
      break;
    default:
      break;
  }
}

/// v and everything in it inline ([...], {...}).
void emitInline(YAML::Emitter& out, const ParamValue& v)
{
  if (v.isList())
  {
    out << YAML::Flow << YAML::BeginSeq;
    for (const ParamValue& item : v.asList())
      emitInline(out, item);
    out << YAML::EndSeq;
  }
  else if (v.isMap())
  {
    out << YAML::Flow << YAML::BeginMap;
    for (const auto& [key, value] : v.entries())
    {
      emitKey(out, key);
      emitInline(out, value);
    }
    out << YAML::EndMap;
  }
  else
  {
    emitScalar(out, v);
  }
}

/// A non-empty map in block style (see paramToYaml for which values stay inline).
void emitBlockMap(YAML::Emitter& out, const ParamValue& map)
{
  out << YAML::Block << YAML::BeginMap;
  for (const auto& [key, value] : map.entries())
  {
    emitKey(out, key);
    const bool holds_map = value.isList() && std::any_of(value.asList().begin(), value.asList().end(),
                                                         [](const ParamValue& item) { return item.isMap(); });
    if (value.isMap() && !value.entries().empty())
    {
      emitBlockMap(out, value);
    }
    else if (holds_map)
    {
      out << YAML::Block << YAML::BeginSeq;
      for (const ParamValue& item : value.asList())
        emitInline(out, item);
      out << YAML::EndSeq;
    }
    else
    {
      emitInline(out, value);
    }
  }
  out << YAML::EndMap;
}
}  // namespace

std::string paramToYaml(const ParamValue& value)
{
  YAML::Emitter out;
  out.SetNullFormat(YAML::LowerNull);  // "null", as rosparam dump writes it (yaml-cpp's default is "~")
  if (value.isMap() && !value.entries().empty())
    emitBlockMap(out, value);
  else
    emitInline(out, value);
  if (!out.good()) throw std::runtime_error("paramToYaml: " + out.GetLastError());
  return std::string(out.c_str(), out.size()) + "\n";
}
}  // namespace io
}  // namespace costmap_layers
