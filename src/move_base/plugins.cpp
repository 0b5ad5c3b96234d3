// The costmap_2d plugins: each costmap_layers layer and filter hosted by LayerBridge, exported for
// base class costmap_2d::Layer (move_base_plugins.xml), built only when costmap_2d is found.
#include <pluginlib/class_list_macros.hpp>

#include "costmap_layers/core/binary_filter.hpp"
#include "costmap_layers/core/gradient_layer.hpp"
#include "costmap_layers/core/inflation_layer.hpp"
#include "costmap_layers/core/keepout_filter.hpp"
#include "costmap_layers/core/lanes_filter.hpp"
#include "costmap_layers/core/obstacle_layer.hpp"
#include "costmap_layers/core/range_sensor_layer.hpp"
#include "costmap_layers/core/speed_filter.hpp"
#include "costmap_layers/core/static_layer.hpp"
#include "costmap_layers/core/voxel_layer.hpp"
#include "costmap_layers/core/zone_parameter_filter.hpp"
#include "costmap_layers/move_base/layer_bridge.hpp"

// One class per core type, named as the core class, in namespace costmap_layers::move_base.
#define COSTMAP_LAYERS_MOVE_BASE_PLUGIN(Type)                                \
  namespace costmap_layers                                                   \
  {                                                                          \
  namespace move_base                                                        \
  {                                                                          \
  class Type : public LayerBridge                                            \
  {                                                                          \
  public:                                                                    \
    Type() : LayerBridge(std::make_shared<costmap_layers::Type>(), #Type) {} \
  };                                                                         \
  }                                                                          \
  }                                                                          \
  PLUGINLIB_EXPORT_CLASS(costmap_layers::move_base::Type, costmap_2d::Layer)

COSTMAP_LAYERS_MOVE_BASE_PLUGIN(StaticLayer)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(InflationLayer)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(ObstacleLayer)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(VoxelLayer)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(RangeSensorLayer)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(GradientLayer)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(KeepoutFilter)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(SpeedFilter)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(LanesFilter)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(ZoneParameterFilter)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(BinaryFilter)
