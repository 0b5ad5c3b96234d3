#include "costmap_layers/ros/node_params.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "costmap_layers/core/config/input_error.hpp"

namespace costmap_layers_ros
{
namespace
{
/// What the parameter server holds under ns; an invalid value when it holds nothing there.
XmlRpc::XmlRpcValue readTree(const std::string& ns)
{
  XmlRpc::XmlRpcValue all;
  if (!ros::param::get(ns, all)) return XmlRpc::XmlRpcValue();
  return all;
}
}  // namespace

NodeParams::NodeParams(const ros::NodeHandle& private_nh)
    : NodeParams(readTree(private_nh.getNamespace()), private_nh.getNamespace())
{
}

NodeParams::NodeParams(XmlRpc::XmlRpcValue all, const std::string& ns)
{
  if (all.getType() != XmlRpc::XmlRpcValue::TypeStruct) return;
  const std::string own = ns.substr(ns.rfind('/') + 1);
  values_ = all;
  // A section named like the node: the file was loaded with ns="<node name>" (one level down), or with
  // that ns inside the <node> tag (two levels down).
  for (int depth = 0; depth < 2 && !own.empty(); ++depth)
  {
    if (!values_.hasMember(own) || values_[own].getType() != XmlRpc::XmlRpcValue::TypeStruct) break;
    XmlRpc::XmlRpcValue section = values_[own];
    // Scalars beside the section that the section sets too: two places for the same settings.
    for (auto it = values_.begin(); it != values_.end(); ++it)
      if (it->second.getType() != XmlRpc::XmlRpcValue::TypeStruct && section.hasMember(it->first))
        throw std::invalid_argument("parameter " + where_ + it->first + " (" + show(it->second) + ") is set both in " +
                                    where_ + " and in " + where_ + own + "/ (" + show(section[it->first]) +
                                    "): load the parameter file once, either at the top level (its key '" + own +
                                    ":' is then this node's namespace) or with ns=\"" + own + "\"");
    values_ = section;
    where_ += own + "/";
    nested_ = true;
  }
}

bool NodeParams::hasAny(const std::vector<std::string>& names) const
{
  for (const auto& n : names)
    if (has(n)) return true;
  return false;
}

const XmlRpc::XmlRpcValue* NodeParams::find(const std::string& name) const
{
  auto& v = const_cast<XmlRpc::XmlRpcValue&>(values_);
  if (v.getType() != XmlRpc::XmlRpcValue::TypeStruct || !v.hasMember(name)) return nullptr;
  return &v[name];
}

bool NodeParams::has(const std::string& name) const
{
  return find(name) != nullptr;
}

std::string NodeParams::show(const XmlRpc::XmlRpcValue& v)
{
  auto& value = const_cast<XmlRpc::XmlRpcValue&>(v);
  std::ostringstream out;
  switch (value.getType())
  {
    case XmlRpc::XmlRpcValue::TypeBoolean:
      out << (static_cast<bool>(value) ? "true" : "false");
      break;
    case XmlRpc::XmlRpcValue::TypeInt:
      out << static_cast<int>(value);
      break;
    case XmlRpc::XmlRpcValue::TypeDouble:
      out << static_cast<double>(value);
      break;
    case XmlRpc::XmlRpcValue::TypeString:
    {
      // Clipped, and on one line: a value is quoted in an error, which must stay one readable line.
      std::string shown;
      for (const char c : costmap_layers::shownText(static_cast<std::string>(value), 200))
        shown += c >= ' ' && c != 127 ? c : '?';
      out << '"' << shown << '"';
      break;
    }
    case XmlRpc::XmlRpcValue::TypeArray:
      out << "a list of " << value.size();
      break;
    case XmlRpc::XmlRpcValue::TypeStruct:
      out << "a dictionary";
      break;
    default:
      out << "an unsupported value";
  }
  return out.str();
}

void NodeParams::fail(const std::string& name, const std::string& what) const
{
  const XmlRpc::XmlRpcValue* v = find(name);
  throw std::invalid_argument("parameter " + where_ + name + " " + what + (v ? " (got " + show(*v) + ")" : ""));
}

std::string NodeParams::getString(const std::string& name, const std::string& def) const
{
  const XmlRpc::XmlRpcValue* v = find(name);
  if (!v) return def;
  if (v->getType() != XmlRpc::XmlRpcValue::TypeString) fail(name, "must be a string");
  return static_cast<std::string>(const_cast<XmlRpc::XmlRpcValue&>(*v));
}

int NodeParams::getInt(const std::string& name, int def) const
{
  const XmlRpc::XmlRpcValue* v = find(name);
  if (!v) return def;
  if (v->getType() != XmlRpc::XmlRpcValue::TypeInt) fail(name, "must be an integer");
  return static_cast<int>(const_cast<XmlRpc::XmlRpcValue&>(*v));
}

double NodeParams::getDouble(const std::string& name, double def) const
{
  const XmlRpc::XmlRpcValue* v = find(name);
  if (!v) return def;
  auto& value = const_cast<XmlRpc::XmlRpcValue&>(*v);
  double d;
  if (value.getType() == XmlRpc::XmlRpcValue::TypeInt)
    d = static_cast<int>(value);
  else if (value.getType() == XmlRpc::XmlRpcValue::TypeDouble)
    d = static_cast<double>(value);
  else
    fail(name, "must be a number");
  if (!std::isfinite(d)) fail(name, "must be a finite number");
  return d;
}

bool NodeParams::getBool(const std::string& name, bool def) const
{
  const XmlRpc::XmlRpcValue* v = find(name);
  if (!v) return def;
  if (v->getType() != XmlRpc::XmlRpcValue::TypeBoolean) fail(name, "must be true or false");
  return static_cast<bool>(const_cast<XmlRpc::XmlRpcValue&>(*v));
}

void NodeParams::refuse(const std::string& name, const std::string& why) const
{
  throw std::invalid_argument("parameter " + where_ + name + ": " + why);
}

std::string NodeParams::getTopic(const std::string& name, const std::string& def, bool allow_private) const
{
  const std::string topic = getString(name, def);
  if (const std::string why = costmap_layers::rosNameProblem(topic, allow_private); !why.empty())
    refuse(name, "the topic " + (topic.empty() ? std::string("is empty") : why) +
                     (allow_private || topic.empty() || topic[0] != '~'
                          ? ""
                          : " (a private name would be this node's own namespace, not the one it names)"));
  return topic;
}

std::string NodeParams::getFrameId(const std::string& name, const std::string& def) const
{
  const std::string frame = getString(name, def);
  if (const std::string why = costmap_layers::frameIdProblem(frame); !why.empty()) refuse(name, "the frame id " + why);
  return frame;
}

std::string NodeParams::getFile(const std::string& name) const
{
  const std::string file = getString(name, "");
  if (file.empty()) refuse(name, "is not set (a file name is needed)");
  return file;
}

double NodeParams::getDoubleIn(const std::string& name, double def, double min, double max) const
{
  const double v = getDouble(name, def);
  if (v < min || v > max)
  {
    std::ostringstream range;
    range << "must be in [" << min << ", " << max << "]";
    fail(name, range.str());
  }
  return v;
}

std::vector<std::string> NodeParams::unknownKeys(const std::vector<std::string>& known) const
{
  std::vector<std::string> out;
  if (values_.getType() != XmlRpc::XmlRpcValue::TypeStruct) return out;
  auto& v = const_cast<XmlRpc::XmlRpcValue&>(values_);
  for (auto it = v.begin(); it != v.end(); ++it)
  {
    if (it->second.getType() == XmlRpc::XmlRpcValue::TypeStruct || it->first == "use_sim_time") continue;
    bool is_known = false;
    for (const auto& k : known)
      is_known = is_known || k == it->first;
    if (!is_known) out.push_back(it->first);
  }
  return out;
}

void NodeParams::warnUseSimTime(const std::string& node, const std::string& key_owner) const
{
  const XmlRpc::XmlRpcValue* v = find("use_sim_time");
  if (!v) return;
  ROS_WARN(
      "%s: parameter %suse_sim_time (%s) has no effect in ROS 1: it is a ROS 2 node parameter; here the global "
      "/use_sim_time switches every node to simulated time (<param name=\"/use_sim_time\" value=\"true\"/>) "
      "[%s/use_sim_time]",
      node.c_str(), where_.c_str(), show(*v).c_str(), key_owner.c_str());
}
}  // namespace costmap_layers_ros
