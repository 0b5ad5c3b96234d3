// A small, ROS-free tree of parameter values (what a params YAML or the ROS parameter server holds).
// The adapter converts XmlRpcValue into it, costmap_tool converts yaml-cpp nodes into it, and every
// layer reads its configuration from it, so the node and the tool configure layers the same way.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace costmap_layers
{
class ParamValue
{
public:
  enum class Type
  {
    Null,
    Bool,
    Int,
    Double,
    String,
    List,
    Map
  };

  ParamValue() = default;
  static ParamValue makeBool(bool v);
  static ParamValue makeInt(int64_t v);
  static ParamValue makeDouble(double v);
  static ParamValue makeString(std::string v);
  static ParamValue makeList(std::vector<ParamValue> items = {});
  static ParamValue makeMap();

  Type type() const { return type_; }
  bool isNull() const { return type_ == Type::Null; }
  bool isMap() const { return type_ == Type::Map; }
  bool isList() const { return type_ == Type::List; }
  /// True for Int and Double.
  bool isNumber() const { return type_ == Type::Int || type_ == Type::Double; }

  /// Each accessor throws std::invalid_argument when the value is of another type.
  bool asBool() const;
  int64_t asInt() const;
  /// Int values convert to double.
  double asDouble() const;
  const std::string& asString() const;
  const std::vector<ParamValue>& asList() const;

  /// Map access: nullptr when absent (or when this is not a map).
  const ParamValue* find(const std::string& key) const;
  /// Follows a '/'-separated path of map keys ("a/b/c"); nullptr when any part is absent.
  const ParamValue* findPath(const std::string& path) const;
  /// Map access for changing a value in place (not noted by a ParamReadLog); nullptr when absent.
  ParamValue* findMutable(const std::string& key);
  /// Removes a key from a map; false when it was not there.
  bool erase(const std::string& key);
  /// Inserts or replaces a key; turns a Null value into a Map first.
  ParamValue& set(const std::string& key, ParamValue v);
  const std::vector<std::pair<std::string, ParamValue>>& entries() const { return map_; }
  /// Appends to a list; turns a Null value into a List first.
  void push(ParamValue v);

  /// Short human-readable rendering for error messages (strings quoted, long lists cut).
  std::string toString() const;
  static const char* typeName(Type t);

private:
  Type type_ = Type::Null;
  bool b_ = false;
  int64_t i_ = 0;
  double d_ = 0.0;
  std::string s_;
  std::vector<ParamValue> list_;
  std::vector<std::pair<std::string, ParamValue>> map_;
};

/// Which keys were asked of which maps. While an instance lives, every ParamValue::find() on a map
/// made by the same thread is noted in it (instances nest: the innermost one records). The node
/// starts one before the costmap and its layers read their parameters, then reports every key
/// nobody asked for (see unknownKeys()). The log holds the maps' addresses: the trees read must not
/// change while it is in use.
class ParamReadLog
{
public:
  ParamReadLog();
  ~ParamReadLog();
  ParamReadLog(const ParamReadLog&) = delete;
  ParamReadLog& operator=(const ParamReadLog&) = delete;

  void note(const ParamValue* map, const std::string& key);
  /// True when key was looked up in map (present or not).
  bool asked(const ParamValue* map, const std::string& key) const;
  /// True when anything was looked up in map.
  bool readFrom(const ParamValue* map) const { return asked_.count(map) != 0; }
  /// Every key looked up in map, present or not, sorted.
  std::vector<std::string> askedKeys(const ParamValue* map) const;

  /// The log recording on this thread, or nullptr.
  static ParamReadLog* current();

private:
  std::map<const ParamValue*, std::set<std::string>> asked_;
  ParamReadLog* previous_ = nullptr;
};
}  // namespace costmap_layers
