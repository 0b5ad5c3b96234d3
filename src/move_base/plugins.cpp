// The costmap_2d plugins: each costmap_layers layer and filter hosted by LayerBridge, exported for
// base class costmap_2d::Layer (move_base_plugins.xml), built only when costmap_2d is found.
#include <pluginlib/class_list_macros.hpp>

#include "costmap_layers/core/layers/asymmetric_inflation_layer.hpp"
#include "costmap_layers/core/filters/binary_filter.hpp"
#include "costmap_layers/core/layers/denoise_layer.hpp"
#include "costmap_layers/core/layers/gradient_layer.hpp"
#include "costmap_layers/core/layers/inflation_layer.hpp"
#include "costmap_layers/core/filters/keepout_filter.hpp"
#include "costmap_layers/core/filters/lanes_filter.hpp"
#include "costmap_layers/core/layers/obstacle_layer.hpp"
#include "costmap_layers/core/layers/plugin_container_layer.hpp"
#include "costmap_layers/core/layers/range_sensor_layer.hpp"
#include "costmap_layers/core/filters/speed_filter.hpp"
#include "costmap_layers/core/layers/static_layer.hpp"
#include "costmap_layers/core/layers/voxel_layer.hpp"
#include "costmap_layers/core/filters/zone_parameter_filter.hpp"
#include "costmap_layers/move_base/layer_bridge.hpp"

// One class per core type, named as the core class, in namespace costmap_layers::move_base. The
// clearable sensor layers are costmap_2d::CostmapLayers (ClearableLayerBridge), as costmap_2d's own are,
// so that move_base's clear-costmap recovery clears them.
#define COSTMAP_LAYERS_MOVE_BASE_PLUGIN(Type, Bridge)                   \
  namespace costmap_layers                                              \
  {                                                                     \
  namespace move_base                                                   \
  {                                                                     \
  class Type : public Bridge                                            \
  {                                                                     \
  public:                                                               \
    Type() : Bridge(std::make_shared<costmap_layers::Type>(), #Type) {} \
  };                                                                    \
  }                                                                     \
  }                                                                     \
  PLUGINLIB_EXPORT_CLASS(costmap_layers::move_base::Type, costmap_2d::Layer)

COSTMAP_LAYERS_MOVE_BASE_PLUGIN(StaticLayer, LayerBridge)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(InflationLayer, LayerBridge)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(ObstacleLayer, ClearableLayerBridge)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(VoxelLayer, ClearableLayerBridge)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(RangeSensorLayer, ClearableLayerBridge)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(GradientLayer, LayerBridge)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(KeepoutFilter, LayerBridge)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(SpeedFilter, LayerBridge)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(LanesFilter, LayerBridge)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(ZoneParameterFilter, LayerBridge)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(BinaryFilter, LayerBridge)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(DenoiseLayer, LayerBridge)
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(AsymmetricInflationLayer, LayerBridge)
// Clearable as its plugins are: clear_costmap_recovery clears the container's clearable plugins.
COSTMAP_LAYERS_MOVE_BASE_PLUGIN(PluginContainerLayer, ClearableLayerBridge)
