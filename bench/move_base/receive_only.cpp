// What receiving the bench world's sensor data costs a roscpp process by itself (issue 38): subscribes
// to /scan (sensor_msgs/LaserScan) and /cloud (sensor_msgs/PointCloud2) as a costmap's sensor layers do
// and does nothing with the messages but count them. scripts/bench_move_base_cpu.sh runs it as side R:
// move_base pays at least this for its sensor layers whatever they do with the data (TCP receive on
// roscpp's network thread, deserialisation on the callback thread), on top of its own share (side N).
//   ~subscribe (bool, default true): false subscribes to nothing (the process's own idle cost).
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>

#include <cstdint>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "receive_only");
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  bool subscribe = true;
  pnh.param("subscribe", subscribe, true);
  std::uint64_t scans = 0, clouds = 0, bytes = 0;
  ros::Subscriber scan_sub, cloud_sub;
  if (subscribe)
  {
    scan_sub =
        nh.subscribe<sensor_msgs::LaserScan>("/scan", 5, [&](const sensor_msgs::LaserScan::ConstPtr&) { ++scans; });
    cloud_sub = nh.subscribe<sensor_msgs::PointCloud2>("/cloud", 5,
                                                       [&](const sensor_msgs::PointCloud2::ConstPtr& c)
                                                       {
                                                         ++clouds;
                                                         bytes += c->data.size();
                                                       });
  }
  ros::spin();
  ROS_INFO("receive_only: %llu scans, %llu clouds (%llu bytes of points)", static_cast<unsigned long long>(scans),
           static_cast<unsigned long long>(clouds), static_cast<unsigned long long>(bytes));
  return 0;
}
