// A callback queue that queues nothing: each callback runs at once, in the thread that adds it. For a
// subscription that is roscpp's network thread, right after the message is read; no spinner thread is
// woken for it. Inside move_base and costmap_node each sensor message and each /tf message went through
// a spinner (a condition variable signalled by the network thread, a thread switch each way), and on a
// robot's virtualised or small CPU those switches cost more than what the callbacks do.
//
// For callbacks that are short and never wait for the network: the network thread reads no other
// topic while one runs (a tf lookup with a timeout inside one would wait for transforms this thread is
// meant to read). The sensor inputs' tf gates and the tf listener are such callbacks.
#pragma once

#include <ros/callback_queue_interface.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

namespace costmap_layers_ros
{
class InlineCallbackQueue : public ros::CallbackQueueInterface
{
public:
  /// `report` gets a line for each callback that threw (it is not let into roscpp's network thread,
  /// which it would end) or asked to be called again; it is called in the adding thread.
  explicit InlineCallbackQueue(std::function<void(const std::string&)> report);

  /// Runs cb now. Subscriptions given this queue must allow concurrent callbacks
  /// (ros::SubscribeOptions::allow_concurrent_callbacks): roscpp's subscription queue then never answers
  /// "try again", which a queue that keeps nothing could not honour.
  void addCallback(const ros::CallbackInterfacePtr& cb, uint64_t owner_id) override;
  /// Nothing is kept, so nothing to remove. roscpp calls this after it took the subscription's callback
  /// out under the lock its network thread holds while running one: none runs after unsubscribing.
  void removeByID(uint64_t owner_id) override;

  /// Callbacks that threw or asked to be called again, since the start.
  uint64_t failures() const { return failures_.load(); }

private:
  std::function<void(const std::string&)> report_;
  std::atomic<uint64_t> failures_{0};
};
}  // namespace costmap_layers_ros
