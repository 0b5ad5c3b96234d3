// zone_server's editing model: what each service request and marker drag does to the shapes in force,
// and what it answers. No publisher, marker server or lock: ZoneServer holds its lock around these
// calls, publishes the mask after an accepted change and logs each refusal (refuse()), so that the
// rules can be tested on plain objects.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "costmap_layers/ZoneShapeDescription.h"
#include "costmap_layers/core/config/input_error.hpp"
#include "costmap_layers/core/zones/zone_shapes.hpp"
#include "costmap_layers/io/zone_file.hpp"

namespace costmap_layers_ros
{
/// The shape a message describes (not yet validated: ZoneSet does that).
/// Throws std::invalid_argument for a type other than "polygon" or "circle".
costmap_layers::ZoneShape fromMsg(const costmap_layers::ZoneShapeDescription& msg);

/// How a marker name maps to a shape handle: "<shape>/<k>" for polygon vertex k, "<shape>/center" and
/// "<shape>/radius" for a circle's handles 0 and 1. @return false for any other name.
bool parseHandleName(const std::string& marker, std::string* shape, std::size_t* index);

/// A service request's outcome: the answer, and for a refusal the error to log (its field is the key).
struct ZoneEdit
{
  bool success = false;
  std::string message;               ///< the service's answer
  costmap_layers::InputError error;  ///< ok() when success
};

/// A marker drag's outcome.
struct ZoneDrag
{
  bool applies = false;                               ///< a handle of a shape in force (else nothing to do)
  costmap_layers::InputError error;                   ///< why it was refused (ok() when it moved)
  std::optional<costmap_layers::ZonePoint> put_back;  ///< refused: where the dragged handle goes back
  std::optional<costmap_layers::ZoneShape> moved;     ///< accepted: the shape as it now is
  std::size_t index = 0;                              ///< the dragged handle's index
  std::string frame;                                  ///< the zones' frame
};

/// Not thread-safe: the caller holds its lock.
class ZoneEditor
{
public:
  /// @param yaml_filename   the file ~save and ~load use when they are sent no name
  /// @param save_directory  where named files may be read and written (io::ZoneFolder); empty: the
  ///                        folder of yaml_filename
  ZoneEditor(costmap_layers::ZoneSet zones, const std::string& yaml_filename, const std::string& save_directory = "");

  const costmap_layers::ZoneSet& zones() const { return zones_; }

  /// ~set_shape: adds the shape or replaces the one of its name. Answers "shape '<name>' in force".
  ZoneEdit set(const costmap_layers::ZoneShapeDescription& shape);
  /// ~remove_shape. Answers "shape '<name>' removed".
  ZoneEdit remove(const std::string& name);
  /// ~save: writes the shapes to filename (empty: yaml_filename), by io::ZoneFolder's rule (inside the
  /// save directory, through a link to its target, only over a zone file). Answers with the path
  /// written; a refused name has the key "save/filename", a failed write "save".
  ZoneEdit save(const std::string& filename) const;
  /// ~load: replaces every shape by the file's (empty: yaml_filename), by the same rule. Answers
  /// "loaded <path>"; keys "load/filename" and "load".
  ZoneEdit load(const std::string& filename);
  /// A drag of the marker named `marker` to (x, y) in frame_id (RViz stamps feedback with the marker's
  /// frame: a pose in no frame, in a malformed one (frameIdProblem()) or in another cannot be placed).
  ZoneDrag drag(const std::string& marker, const std::string& frame_id, double x, double y);

  const costmap_layers::io::ZoneFolder& folder() const { return folder_; }

private:
  costmap_layers::ZoneSet zones_;
  costmap_layers::io::ZoneFolder folder_;
};
}  // namespace costmap_layers_ros
