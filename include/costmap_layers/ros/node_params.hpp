// The private parameters of a small node (mask_server, costmap_filter_info_server) read the way Nav2's
// parameter files are written: a file whose top-level key is the node's name ("costmap_filter_info_server:"
// with its `ros__parameters:` level removed) may be loaded at the launch file's top level (the key then
// IS the node's private namespace) or with ns="<node name>" (the key lands one level deeper, as
// ~<node name>/...): both work. Values are checked by type, and every error names the parameter and
// its value.
#pragma once

#include <ros/ros.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <string>
#include <vector>

namespace costmap_layers_ros
{
class NodeParams
{
public:
  /// Reads ~ (the node's private namespace). When it holds a dictionary named like the node itself,
  /// the parameters are read from there ("nested"; twice when the file was loaded with that ns inside
  /// the <node> tag); parameters both there and beside it are an error (std::invalid_argument naming
  /// both).
  explicit NodeParams(const ros::NodeHandle& private_nh);
  /// The same rules on a tree already read: `all` is what the parameter server holds under `ns` (the
  /// node's private namespace, e.g. "/mask_server"); anything but a dictionary is no parameters. For
  /// tests, which have no parameter server.
  NodeParams(XmlRpc::XmlRpcValue all, const std::string& ns);

  /// "~" or "~<node name>/": where the parameters were read from (for messages).
  const std::string& where() const { return where_; }
  bool nested() const { return nested_; }
  bool has(const std::string& name) const;
  /// Whether any of `names` is set (none: the node runs on its defaults, which it should say).
  bool hasAny(const std::vector<std::string>& names) const;

  /// Typed reads; std::invalid_argument "parameter ~name must be ... (got <value>)" on a wrong type.
  std::string getString(const std::string& name, const std::string& def) const;
  int getInt(const std::string& name, int def) const;
  /// An int or a double; NaN and infinities are refused.
  double getDouble(const std::string& name, double def) const;
  bool getBool(const std::string& name, bool def) const;
  /// A topic name by ROS's rule (rosNameProblem); a private '~name' only when allow_private. A space,
  /// a non-ASCII letter or an empty name is an error naming the parameter, never roscpp's abort later.
  std::string getTopic(const std::string& name, const std::string& def, bool allow_private = true) const;
  /// A tf frame id (frameIdProblem: printable ASCII, no spaces).
  std::string getFrameId(const std::string& name, const std::string& def) const;
  /// A file name: a non-empty string (whether it loads is the loader's to say, with the path).
  std::string getFile(const std::string& name) const;
  /// A number in [min, max]; the error names the range.
  double getDoubleIn(const std::string& name, double def, double min, double max) const;

  /// The scalar keys not in `known` (sub-dictionaries are other nodes' sections of the same file, or
  /// not ours: left alone), and `use_sim_time`, which is reported separately.
  std::vector<std::string> unknownKeys(const std::vector<std::string>& known) const;
  /// Logs one warning when the node's namespace holds use_sim_time: in ROS 1 it is the global
  /// /use_sim_time that switches the clock, a node's private copy does nothing. The line starts with
  /// `node` and ends with the stable key "[<key_owner>/use_sim_time]".
  void warnUseSimTime(const std::string& node, const std::string& key_owner) const;

  /// A value as the user wrote it: 5, 2.5, "text", true, a list, a dictionary.
  static std::string show(const XmlRpc::XmlRpcValue& v);

private:
  const XmlRpc::XmlRpcValue* find(const std::string& name) const;
  [[noreturn]] void fail(const std::string& name, const std::string& what) const;
  /// fail() with the value shown by `why` (the rule's reason quotes it, clipped).
  [[noreturn]] void refuse(const std::string& name, const std::string& why) const;

  XmlRpc::XmlRpcValue values_;
  std::string where_ = "~";
  bool nested_ = false;
};
}  // namespace costmap_layers_ros
