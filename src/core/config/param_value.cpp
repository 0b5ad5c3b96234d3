#include "costmap_layers/core/config/param_value.hpp"

#include <sstream>
#include <stdexcept>

namespace costmap_layers
{
ParamValue ParamValue::makeBool(bool v)
{
  ParamValue p;
  p.type_ = Type::Bool;
  p.b_ = v;
  return p;
}

ParamValue ParamValue::makeInt(int64_t v)
{
  ParamValue p;
  p.type_ = Type::Int;
  p.i_ = v;
  return p;
}

ParamValue ParamValue::makeDouble(double v)
{
  ParamValue p;
  p.type_ = Type::Double;
  p.d_ = v;
  return p;
}

ParamValue ParamValue::makeString(std::string v)
{
  ParamValue p;
  p.type_ = Type::String;
  p.s_ = std::move(v);
  return p;
}

ParamValue ParamValue::makeList(std::vector<ParamValue> items)
{
  ParamValue p;
  p.type_ = Type::List;
  p.list_ = std::move(items);
  return p;
}

ParamValue ParamValue::makeMap()
{
  ParamValue p;
  p.type_ = Type::Map;
  return p;
}

namespace
{
[[noreturn]] void wrongType(const ParamValue& v, const char* wanted)
{
  throw std::invalid_argument(std::string("expected ") + wanted + ", got " + ParamValue::typeName(v.type()) + " " +
                              v.toString());
}
}  // namespace

bool ParamValue::asBool() const
{
  if (type_ != Type::Bool) wrongType(*this, "a boolean");
  return b_;
}

int64_t ParamValue::asInt() const
{
  if (type_ == Type::Int) return i_;
  wrongType(*this, "an integer");
}

double ParamValue::asDouble() const
{
  if (type_ == Type::Double) return d_;
  if (type_ == Type::Int) return static_cast<double>(i_);
  wrongType(*this, "a number");
}

const std::string& ParamValue::asString() const
{
  if (type_ != Type::String) wrongType(*this, "a string");
  return s_;
}

const std::vector<ParamValue>& ParamValue::asList() const
{
  if (type_ != Type::List) wrongType(*this, "a list");
  return list_;
}

const ParamValue* ParamValue::find(const std::string& key) const
{
  if (type_ != Type::Map) return nullptr;
  if (ParamReadLog* log = ParamReadLog::current()) log->note(this, key);
  for (const auto& kv : map_)
  {
    if (kv.first == key) return &kv.second;
  }
  return nullptr;
}

ParamValue* ParamValue::findMutable(const std::string& key)
{
  if (type_ != Type::Map) return nullptr;
  for (auto& kv : map_)
  {
    if (kv.first == key) return &kv.second;
  }
  return nullptr;
}

bool ParamValue::erase(const std::string& key)
{
  if (type_ != Type::Map) return false;
  for (auto it = map_.begin(); it != map_.end(); ++it)
  {
    if (it->first == key)
    {
      map_.erase(it);
      return true;
    }
  }
  return false;
}

const ParamValue* ParamValue::findPath(const std::string& path) const
{
  const ParamValue* node = this;
  std::string::size_type start = 0;
  while (node != nullptr && start <= path.size())
  {
    const auto slash = path.find('/', start);
    const std::string part = path.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
    if (!part.empty()) node = node->find(part);
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return node;
}

ParamValue& ParamValue::set(const std::string& key, ParamValue v)
{
  if (type_ == Type::Null) type_ = Type::Map;
  if (type_ != Type::Map) wrongType(*this, "a map");
  for (auto& kv : map_)
  {
    if (kv.first == key)
    {
      kv.second = std::move(v);
      return kv.second;
    }
  }
  map_.emplace_back(key, std::move(v));
  return map_.back().second;
}

void ParamValue::push(ParamValue v)
{
  if (type_ == Type::Null) type_ = Type::List;
  if (type_ != Type::List) wrongType(*this, "a list");
  list_.push_back(std::move(v));
}

std::string ParamValue::toString() const
{
  std::ostringstream out;
  switch (type_)
  {
    case Type::Null:
      out << "null";
      break;
    case Type::Bool:
      out << (b_ ? "true" : "false");
      break;
    case Type::Int:
      out << i_;
      break;
    case Type::Double:
      out << d_;
      break;
    case Type::String:
      out << '"' << s_ << '"';
      break;
    case Type::List:
    {
      out << '[';
      for (std::size_t k = 0; k < list_.size() && k < 8; ++k)
        out << (k ? ", " : "") << list_[k].toString();
      if (list_.size() > 8) out << ", ...";
      out << ']';
      break;
    }
    case Type::Map:
    {
      out << '{';
      for (std::size_t k = 0; k < map_.size() && k < 8; ++k)
        out << (k ? ", " : "") << map_[k].first << ": " << map_[k].second.toString();
      if (map_.size() > 8) out << ", ...";
      out << '}';
      break;
    }
  }
  return out.str();
}

namespace
{
thread_local ParamReadLog* g_read_log = nullptr;
}

ParamReadLog::ParamReadLog() : previous_(g_read_log)
{
  g_read_log = this;
}

ParamReadLog::~ParamReadLog()
{
  g_read_log = previous_;
}

ParamReadLog* ParamReadLog::current()
{
  return g_read_log;
}

void ParamReadLog::note(const ParamValue* map, const std::string& key)
{
  asked_[map].insert(key);
}

bool ParamReadLog::asked(const ParamValue* map, const std::string& key) const
{
  const auto it = asked_.find(map);
  return it != asked_.end() && it->second.count(key) != 0;
}

std::vector<std::string> ParamReadLog::askedKeys(const ParamValue* map) const
{
  const auto it = asked_.find(map);
  if (it == asked_.end()) return {};
  return std::vector<std::string>(it->second.begin(), it->second.end());
}

const char* ParamValue::typeName(Type t)
{
  switch (t)
  {
    case Type::Null:
      return "null";
    case Type::Bool:
      return "boolean";
    case Type::Int:
      return "integer";
    case Type::Double:
      return "double";
    case Type::String:
      return "string";
    case Type::List:
      return "list";
    case Type::Map:
      return "map";
  }
  return "?";
}
}  // namespace costmap_layers
