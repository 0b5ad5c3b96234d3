#include "costmap_layers/ros/inline_callback_queue.hpp"

#include <exception>
#include <utility>

namespace costmap_layers_ros
{
InlineCallbackQueue::InlineCallbackQueue(std::function<void(const std::string&)> report) : report_(std::move(report)) {}

void InlineCallbackQueue::addCallback(const ros::CallbackInterfacePtr& cb, uint64_t /*owner_id*/)
{
  std::string problem;
  try
  {
    if (!cb->ready())
      problem = "a callback was not ready to run; dropped";
    else if (cb->call() == ros::CallbackInterface::TryAgain)
      problem = "a callback asked to be called again (its subscription does not allow concurrent callbacks); dropped";
  }
  catch (const std::exception& e)
  {
    problem = std::string("a callback threw: ") + e.what();
  }
  catch (...)
  {
    problem = "a callback threw something that is not a std::exception";
  }
  if (problem.empty()) return;
  ++failures_;
  try
  {
    if (report_) report_(problem);
  }
  catch (...)
  {
    // the report itself failed (out of memory): counted above
  }
}

void InlineCallbackQueue::removeByID(uint64_t /*owner_id*/) {}
}  // namespace costmap_layers_ros
