// The sensor inputs' tf gate: holds each reading until tf can place it, then hands it on in arrival
// order; the readings tf will never place go to a failure callback. Apart from any subscription
// (LayerPorts feeds it from a ros::Subscriber and retries it whenever tf changes, through TfChangeWake),
// so that a test can feed it in-memory messages against a hand-filled tf2::BufferCore and a clock of its
// own.
//
// This replaces tf2_ros::MessageFilter, whose addTransformableRequest() in Debian's tf2 (0.7.6) reads
// tf's frame table without tf's lock, a race with the tf listener adding frames that TSan reports
// (fixed upstream in 0.7.10, ros/geometry2#539). Only tf2's public, locked calls are used here:
// canTransform(), lookupTransform(), getCacheLength() (see tf_verdict.hpp).
#pragma once

#include <ros/time.h>
#include <tf2/buffer_core.h>
#include <boost/signals2/connection.hpp>

#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include "costmap_layers/ros/tf_verdict.hpp"

namespace costmap_layers_ros
{
constexpr std::size_t kGateQueue = 10;  ///< readings that may wait for tf at once

/// Why the gate dropped a reading, as LayerPorts logs it: a throttling key per reason (so that a stale
/// stamp does not hide a wrong frame) and the line.
struct GateFailure
{
  std::string key;      ///< <owner><topic>/tf/{frame_id,stamp,future,wait}
  std::string message;  ///< "<owner>: dropped a reading on <topic>: cannot transform frame ..."
};

/// The report of a reading in `frame_id` stamped `stamp` that the gate dropped with `verdict`, at the
/// time `now`. `owner` is the layer's namespace, `topic` the topic as the layer names it, `global` the
/// gate's target frame, `sensor_frame` the readings' origin frame when not their own (may be empty).
GateFailure gateFailure(const std::string& owner, const std::string& topic, const std::string& global,
                        const std::string& sensor_frame, const std::string& frame_id, const ros::Time& stamp,
                        const ros::Time& now, TfVerdict verdict);

/// Msg: a message with a header (its ConstPtr is what is queued). Thread-safe.
template <class Msg>
class TfGate
{
public:
  using Ptr = typename Msg::ConstPtr;
  using Clock = std::function<ros::Time()>;
  static constexpr std::size_t kQueue = kGateQueue;
  /// [s] how far a reading's stamp may lie ahead of now (see kGateMaxAhead). tf's canTransform() is true
  /// at any stamp between a frame and itself, so without this a reading from the future would pass (and,
  /// buffered, look fresh until the clock caught up with it).
  static constexpr double kMaxAhead = kGateMaxAhead;

  /// @param target        the frame readings must be placed in (the global frame)
  /// @param sensor_frame  the readings' origin frame when not their own (empty: their own)
  /// @param ready         gets each reading tf can place, in arrival order
  /// @param failed        gets each reading tf never will, with the reason
  /// @param clock         "now" for the verdicts; empty: ros::Time::now()
  /// The buffer must outlive the gate.
  TfGate(tf2::BufferCore& tf, std::string target, std::string sensor_frame, std::function<void(const Ptr&)> ready,
         std::function<void(const Ptr&, TfVerdict)> failed, Clock clock = {})
      : tf_(tf),
        target_(std::move(target)),
        sensor_frame_(std::move(sensor_frame)),
        ready_(std::move(ready)),
        failed_(std::move(failed)),
        clock_(std::move(clock))
  {
  }

  /// Queues msg (when not null; null only retries) and hands on, in order, every waiting reading tf
  /// can now place. One lock for queue and delivery: the layer sees one input's readings one at a time
  /// and in order.
  void arrive(const Ptr& msg)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (msg)
      waiting_.push_back(msg);
    else if (waiting_.empty())
      return;  // a retry with nothing waiting: the common case, tf changes far more often than readings wait
    std::deque<Ptr>& still = spare_;  // kept from call to call: nothing allocated per reading
    still.clear();
    for (const Ptr& m : waiting_)
    {
      // Nothing a reading carries may escape into roscpp's thread calling this (that would end the node):
      // a reading the rule or its callbacks throw on is dropped as one tf cannot place.
      try
      {
        const TfVerdict v = check(*m);
        if (v == TfVerdict::Ready)
          ready_(m);
        else if (v == TfVerdict::Wait)
          still.push_back(m);
        else
          failed_(m, v);
      }
      catch (const std::exception&)
      {
        try
        {
          failed_(m, TfVerdict::BadStamp);
        }
        catch (const std::exception&)
        {
          // dropped; the report itself failed (out of memory)
        }
      }
    }
    while (still.size() > kQueue)
    {
      failed_(still.front(), TfVerdict::PushedOut);
      still.pop_front();
    }
    waiting_.swap(still);
    spare_.clear();  // the readings handed on are not kept alive until the next call
  }

  /// How many readings wait for tf.
  std::size_t waiting() const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return waiting_.size();
  }

private:
  TfVerdict check(const Msg& msg) const
  {
    const ros::Time now = clock_ ? clock_() : ros::Time::now();
    return gateVerdict(tf_, target_, msg.header.frame_id, sensor_frame_, msg.header.stamp, now, kMaxAhead);
  }

  tf2::BufferCore& tf_;
  const std::string target_;
  const std::string sensor_frame_;  ///< the readings' origin frame when not their own (may be empty)
  const std::function<void(const Ptr&)> ready_;
  const std::function<void(const Ptr&, TfVerdict)> failed_;
  const Clock clock_;
  mutable std::mutex mutex_;
  std::deque<Ptr> waiting_;  ///< guarded by mutex_
  std::deque<Ptr> spare_;    ///< arrive()'s scratch queue, guarded by mutex_
};

/// Calls `retry` whenever tf gets a transform: tf2's transforms-changed signal (the hook tf's own
/// listener uses), raised by BufferCore::setTransform() in the inserting thread (the tf listener's callback)
/// after tf's locks are released. With it a gate needs no timer: a waiting reading leaves the queue
/// only when tf changes (placed, or older than all tf keeps) or when newer readings push it out; time
/// alone moves none (the stamp-ahead rule only relaxes as the clock goes on). A timer retrying every
/// 20 ms while readings waited was started and stopped for most readings inside move_base (a scan comes
/// just before tf's transform of its stamp) and cost the node four wake-ups per reading.
/// The destructor waits for a retry in flight, and none starts after it.
class TfChangeWake
{
public:
  TfChangeWake(tf2::BufferCore& tf, std::function<void()> retry);
  ~TfChangeWake();
  TfChangeWake(const TfChangeWake&) = delete;
  TfChangeWake& operator=(const TfChangeWake&) = delete;

private:
  struct Shared
  {
    std::mutex mutex;
    bool alive = true;  ///< guarded by mutex
    std::function<void()> retry;
  };
  std::shared_ptr<Shared> shared_;
  boost::signals2::connection connection_;
};
}  // namespace costmap_layers_ros
