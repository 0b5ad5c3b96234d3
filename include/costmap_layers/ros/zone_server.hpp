// zone_server: zones drawn as shapes, served as a mask. Loads a zone file (io/zone_file.hpp), rasterises
// it with the core (core/zone_shapes.hpp) and publishes the mask latched, as mask_server publishes a
// mask file; shapes change at run time through services and through interactive markers in RViz (one
// handle per polygon vertex, a centre and a radius handle per circle), and are saved back to a file.
//
// Parameters:
//   ~yaml_filename   the zone file (required); ~save and ~load with an empty filename use it
//   ~topic           where the mask is published (default /map_filter)
//   ~markers         offer the interactive markers (default true)
//   ~save_directory  the folder ~save and ~load may name files in (default: the folder of
//                    ~yaml_filename): relative names inside it, or absolute paths inside it; no '..'
//                    part; folders and links resolved before the check (io::ZoneFolder). A file is
//                    replaced only when it is a zone file, through its link, keeping mode and owner.
//   ~publish_rate    [Hz] the most masks published a second (default 10, 0.001..1000): changes (a
//                    drag moves a handle dozens of times a second) are published at the next tick of
//                    a timer at this rate, so the state in force is on the topic within one period
//
// Topics and services (the node's private namespace is ~):
//   <topic> (~topic, default /map_filter)  nav_msgs/OccupancyGrid, latched: the mask, republished
//                                          within 1 / ~publish_rate after an accepted change
//   ~update, ~update_full, ~feedback       the interactive marker server's topics (RViz: add an
//                                          "InteractiveMarkers" display on ~update)
//   ~set_shape     costmap_layers/SetZoneShape     add a shape or replace the one of the same name
//   ~remove_shape  costmap_layers/RemoveZoneShape
//   ~save          costmap_layers/SaveZones        write the shapes to a zone file
//   ~load          costmap_layers/LoadZones        replace every shape by a zone file's
// Every refused change (a service request, a marker drag that would make a self-intersecting polygon,
// a file that does not load) keeps the shapes in force, is answered with the reason (services) or
// logged with a stable key "[<node>/<field>]" (markers), and a refused drag puts the handle back.
// Markers: a handle per vertex "<shape>/<k>" (a circle's "<shape>/center" and "<shape>/radius"), and
// the outline "<shape>/outline" (no handle ends so: any shape name may hold '/'). The mask's INFO line
// is written at most once a second ("[<node>/published]"). What
// each request does to the shapes is ZoneEditor's (zone_editor.hpp); this class is its ROS wiring.
#pragma once

#include <interactive_markers/interactive_marker_server.h>
#include <nav_msgs/OccupancyGrid.h>
#include <ros/ros.h>
#include <visualization_msgs/InteractiveMarkerFeedback.h>

#include <memory>
#include <mutex>
#include <string>

#include "costmap_layers/LoadZones.h"
#include "costmap_layers/RemoveZoneShape.h"
#include "costmap_layers/SaveZones.h"
#include "costmap_layers/SetZoneShape.h"
#include "costmap_layers/ZoneShapeDescription.h"
#include "costmap_layers/core/zones/zone_shapes.hpp"
#include "costmap_layers/ros/ros_layer_context.hpp"
#include "costmap_layers/ros/zone_editor.hpp"

namespace costmap_layers_ros
{
/// The mask as a message: frame, resolution, origin, cells; stamped now.
nav_msgs::OccupancyGrid toMaskMsg(const costmap_layers::OccupancyGridData& grid, const ros::Time& stamp);

class ZoneServer
{
public:
  struct Options
  {
    std::string yaml_filename;  ///< the zone file (required)
    std::string topic = "/map_filter";
    bool markers = true;         ///< offer the interactive markers
    std::string save_directory;  ///< where ~save and ~load may name files; empty: yaml_filename's folder
    double publish_rate = 10.0;  ///< [Hz] the most masks published a second
    std::string file_parameter = "~yaml_filename";  ///< how errors name the file's parameter
  };
  /// Reads the options from the private parameters; throws std::invalid_argument naming one.
  static Options readOptions(const ros::NodeHandle& pnh);

  /// Loads the file and starts publishing; throws (naming the file and the field) when it does not load.
  ZoneServer(ros::NodeHandle nh, ros::NodeHandle pnh, Options options);

private:
  /// Publishes the mask of the shapes in force. mutex_ held.
  void publish();
  /// Marks the shapes changed: the next tick of publish_timer_ publishes them. mutex_ held.
  void changed();
  void onPublishTimer(const ros::SteadyTimerEvent& event);
  /// Redraws every outline and handle of layout l. mutex_ not held: the marker server calls
  /// onFeedback holding its own lock, and onFeedback takes mutex_, so the opposite order is never taken.
  void rebuildMarkers(const costmap_layers::ZoneLayout& l);
  /// Takes a copy of the shapes in force, releases the lock and redraws them; returns true (a service's
  /// answer was set).
  bool redraw(std::unique_lock<std::mutex>& lock);
  void onFeedback(const visualization_msgs::InteractiveMarkerFeedbackConstPtr& feedback);
  /// Redraws the handles of the shape whose handle `marker` is, at the end of its drag: their labels go
  /// to the outside of the corners as they now are (not during the drag: that would replace the marker
  /// the user holds). mutex_ not held.
  void relabel(const std::string& marker);
  bool onSet(costmap_layers::SetZoneShape::Request& req, costmap_layers::SetZoneShape::Response& res);
  bool onRemove(costmap_layers::RemoveZoneShape::Request& req, costmap_layers::RemoveZoneShape::Response& res);
  bool onSave(costmap_layers::SaveZones::Request& req, costmap_layers::SaveZones::Response& res);
  bool onLoad(costmap_layers::LoadZones::Request& req, costmap_layers::LoadZones::Response& res);
  /// Logs a refusal with the key <node>/<field>.
  void refuse(const std::string& what, const costmap_layers::InputError& error);

  ros::NodeHandle nh_, pnh_;
  Options options_;
  std::string node_;
  std::shared_ptr<ThrottledLog> log_;
  ThrottledLog info_log_;  ///< the mask's INFO line: at most once a second
  std::mutex mutex_;
  ZoneEditor editor_;   ///< the shapes in force and what requests do to them; guarded by mutex_
  bool dirty_ = false;  ///< the shapes changed since the mask was last published; guarded by mutex_
  ros::SteadyTimer publish_timer_;
  ros::Publisher mask_pub_;
  std::unique_ptr<interactive_markers::InteractiveMarkerServer> markers_;
  ros::ServiceServer set_srv_, remove_srv_, save_srv_, load_srv_;
};
}  // namespace costmap_layers_ros
