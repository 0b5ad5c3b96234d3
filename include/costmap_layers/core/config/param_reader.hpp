// Typed, validated reads from one parameter namespace. Each config struct has one parse function
// built on this, so every parameter name is written once, next to its default and its limits.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "costmap_layers/core/config/param_value.hpp"

namespace costmap_layers
{
/// What a parse function read: a parameter's name, type, limits, default and the value it used.
/// Recorded by ParamReader, so a run-time description (dynamic_reconfigure) comes from the same
/// single declaration as the parsing.
struct ParamSpec
{
  std::string name;
  ParamValue::Type type = ParamValue::Type::Null;  ///< Bool, Int, Double or String
  ParamValue default_value;
  ParamValue value;
  double min = 0.0, max = 0.0;       ///< Int and Double only
  std::vector<std::string> choices;  ///< String choices, when limited
  /// What a string names ("topic", "frame id"), or what a parameter read as a whole value holds ("a list
  /// of [x, y] points", ...: type Null); empty for a plain value.
  std::string role;
};

/// Every parameter any ParamReader on this thread reads while the log lives, with the reader's owner
/// (e.g. "obstacle_layer" or "obstacle_layer/scan" for a source's sub-namespace): how the reference
/// (`costmap_tool --describe-params`) learns what a plugin reads from the plugin's own parse functions,
/// so that it cannot drift from them. Logs nest; the innermost records.
class ParamSpecLog
{
public:
  struct Entry
  {
    std::string owner;
    ParamSpec spec;
  };
  ParamSpecLog();
  ~ParamSpecLog();
  ParamSpecLog(const ParamSpecLog&) = delete;
  ParamSpecLog& operator=(const ParamSpecLog&) = delete;

  const std::vector<Entry>& entries() const { return entries_; }
  std::vector<Entry>& entries() { return entries_; }
  /// The log recording on this thread, or nullptr.
  static ParamSpecLog* current();

private:
  std::vector<Entry> entries_;
  ParamSpecLog* previous_ = nullptr;
};

class ParamReader
{
public:
  /// @param ns     the namespace (a Map, or Null for "nothing set")
  /// @param owner  who reads, for error messages (e.g. "gradient_layer_1")
  ParamReader(const ParamValue& ns, std::string owner) : ns_(ns), owner_(std::move(owner)) {}

  bool has(const std::string& name) const { return ns_.find(name) != nullptr; }
  const ParamValue* raw(const std::string& name) const { return ns_.find(name); }
  const ParamValue& ns() const { return ns_; }
  const std::string& owner() const { return owner_; }

  /// Each getter returns the default when the name is absent and throws std::invalid_argument
  /// ("owner: parameter 'name' ...: value") when the value has the wrong type or is out of range.
  bool getBool(const std::string& name, bool def) const;
  int getInt(const std::string& name, int def, int min = std::numeric_limits<int>::min(),
             int max = std::numeric_limits<int>::max()) const;
  /// Rejects NaN and infinities as well as values outside [min, max].
  double getDouble(const std::string& name, double def, double min = std::numeric_limits<double>::lowest(),
                   double max = std::numeric_limits<double>::max()) const;
  std::string getString(const std::string& name, const std::string& def) const;
  /// A topic name: fails naming the parameter unless it is a ROS name (rosNameProblem), or empty when
  /// allow_empty (a topic that may be left out).
  std::string getTopic(const std::string& name, const std::string& def, bool allow_empty = false) const;
  /// A tf frame id: fails naming the parameter unless it is one (frameIdProblem), or empty when
  /// allow_empty (e.g. "use the message's frame").
  std::string getFrameId(const std::string& name, const std::string& def, bool allow_empty = false) const;
  /// Notes, for the reference only, a parameter read whole through raw() (a list, a dictionary, text of
  /// several words): `what` says what it holds, `default_text` what its absence means.
  void declare(const std::string& name, const std::string& what, const std::string& default_text) const;
  /// Accepts one of the given choices only.
  std::string getChoice(const std::string& name, const std::string& def, const std::vector<std::string>& choices) const;

  /// Throws "owner: parameter 'name' <what> (value)".
  [[noreturn]] void fail(const std::string& name, const std::string& what) const;

  /// From now on, every getter call appends what it read to *out (nullptr stops recording).
  void recordInto(std::vector<ParamSpec>* out) { record_ = out; }

private:
  void note(ParamSpec spec) const;
  /// Sets the role of what the last getter noted.
  void markRole(const char* role) const;

  const ParamValue& ns_;
  std::string owner_;
  std::vector<ParamSpec>* record_ = nullptr;
};

/// Runs parse(reader) on params with recording on and returns what it read.
template <class Parse>
std::vector<ParamSpec> recordParameters(const ParamValue& params, const std::string& owner, Parse&& parse)
{
  std::vector<ParamSpec> specs;
  ParamReader reader(params, owner);
  reader.recordInto(&specs);
  parse(reader);
  return specs;
}
}  // namespace costmap_layers
