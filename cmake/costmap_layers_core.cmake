# The one definition of the ROS-free core library, used by the package (CMakeLists.txt), the sanitizer
# build (test/sanitize) and the fuzz build (test/fuzz), so that the three compile the same sources with
# the same Highway targets and the same include paths.
#
#   costmap_layers_add_core(<target> <SHARED|STATIC> <package root>)
#       the core library: every src/core/**/*.cpp, std + Eigen in its headers, Highway inside
#   costmap_layers_core_tests(<out variable> <package root>)
#       the core's plain-gtest sources: every test/core/**/test_*.cpp
#
# The configure step fails when a core file includes a ROS header (on Debian those headers sit in
# /usr/include, so the compiler alone cannot tell).

function(costmap_layers_add_core target type root)
  find_package(Eigen3 REQUIRED)
  find_package(hwy REQUIRED)
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${root}/src/core/*.cpp)
  file(GLOB_RECURSE headers CONFIGURE_DEPENDS ${root}/include/costmap_layers/core/*.hpp)
  foreach(f ${sources} ${headers})
    file(STRINGS ${f} ros_includes
         REGEX "#include *[<\"](ros|roscpp|tf2|tf2_ros|tf2_msgs|pluginlib|class_loader|nav_msgs|std_msgs|geometry_msgs|sensor_msgs|map_msgs|xmlrpcpp|yaml-cpp)/")
    if(ros_includes)
      message(FATAL_ERROR "The ROS-free core includes a ROS header: ${f}: ${ros_includes}")
    endif()
  endforeach()
  add_library(${target} ${type} ${sources})
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${root}/include> ${EIGEN3_INCLUDE_DIRS})
  # The kernel files include themselves once per Highway target (HWY_TARGET_INCLUDE, a path from the
  # package root). Every target Highway attains is compiled, the scalar one included, so that the tests
  # can run each (kernels/simd_targets.hpp); Highway's dispatcher picks the best one the CPU runs.
  # HWY_WANT_AVX3_DL adds AVX-512 with VBMI (Ice Lake and later), whose byte permute the distance
  # engine uses for one lookup per column offset (Highway 1.0.3 compiles that target only when asked).
  target_include_directories(${target} PRIVATE ${root})
  target_compile_definitions(${target} PRIVATE HWY_COMPILE_ALL_ATTAINABLE HWY_WANT_AVX3_DL)
  target_link_libraries(${target} PUBLIC pthread PRIVATE hwy::hwy)
endfunction()

function(costmap_layers_core_tests out root)
  file(GLOB_RECURSE tests CONFIGURE_DEPENDS ${root}/test/core/test_*.cpp)
  set(${out} ${tests} PARENT_SCOPE)
endfunction()
