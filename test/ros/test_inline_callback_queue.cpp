// InlineCallbackQueue, fed callbacks of its own: each runs at once in the adding thread, and one that
// throws or cannot run is reported and counted, never let out into the caller (roscpp's network thread).
#include <gtest/gtest.h>
#include <ros/callback_queue_interface.h>

#include <boost/make_shared.hpp>
#include <functional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "costmap_layers/ros/inline_callback_queue.hpp"

using costmap_layers_ros::InlineCallbackQueue;

namespace
{
struct Callback : ros::CallbackInterface
{
  std::function<CallResult()> body;
  bool is_ready = true;
  explicit Callback(std::function<CallResult()> b) : body(std::move(b)) {}
  CallResult call() override { return body(); }
  bool ready() override { return is_ready; }
};

ros::CallbackInterfacePtr callback(std::function<ros::CallbackInterface::CallResult()> body)
{
  return boost::make_shared<Callback>(std::move(body));
}
}  // namespace

TEST(InlineCallbackQueue, EachCallbackRunsAtOnceInTheAddingThread)
{
  std::vector<std::string> reports;
  InlineCallbackQueue queue([&](const std::string& r) { reports.push_back(r); });
  std::vector<int> ran;
  std::thread::id where;
  queue.addCallback(callback(
                        [&]
                        {
                          ran.push_back(1);
                          where = std::this_thread::get_id();
                          return ros::CallbackInterface::Success;
                        }),
                    7);
  ASSERT_EQ(ran, std::vector<int>{1});  // before addCallback returned
  EXPECT_EQ(where, std::this_thread::get_id());
  queue.addCallback(callback(
                        [&]
                        {
                          ran.push_back(2);
                          return ros::CallbackInterface::Invalid;  // roscpp: nothing left to call; not a fault
                        }),
                    7);
  EXPECT_EQ(ran, (std::vector<int>{1, 2}));
  queue.removeByID(7);  // nothing is kept: nothing to remove, and nothing runs
  EXPECT_EQ(ran, (std::vector<int>{1, 2}));
  EXPECT_TRUE(reports.empty());
  EXPECT_EQ(queue.failures(), 0u);
}

TEST(InlineCallbackQueue, ACallbackThatThrowsIsReportedAndDoesNotEscape)
{
  std::vector<std::string> reports;
  InlineCallbackQueue queue([&](const std::string& r) { reports.push_back(r); });
  EXPECT_NO_THROW(queue.addCallback(
      callback([]() -> ros::CallbackInterface::CallResult { throw std::runtime_error("bad cloud"); }), 1));
  EXPECT_NO_THROW(queue.addCallback(callback([]() -> ros::CallbackInterface::CallResult { throw 42; }), 1));
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_EQ(reports[0], "a callback threw: bad cloud");
  EXPECT_EQ(reports[1], "a callback threw something that is not a std::exception");
  EXPECT_EQ(queue.failures(), 2u);
}

TEST(InlineCallbackQueue, ACallbackThatCannotRunNowIsReportedNotRetried)
{
  std::vector<std::string> reports;
  InlineCallbackQueue queue([&](const std::string& r) { reports.push_back(r); });
  int calls = 0;
  queue.addCallback(callback(
                        [&]
                        {
                          ++calls;
                          return ros::CallbackInterface::TryAgain;
                        }),
                    1);
  EXPECT_EQ(calls, 1);
  auto not_ready = boost::make_shared<Callback>(
      [&]
      {
        ++calls;
        return ros::CallbackInterface::Success;
      });
  not_ready->is_ready = false;
  queue.addCallback(not_ready, 1);
  EXPECT_EQ(calls, 1);
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_EQ(reports[0],
            "a callback asked to be called again (its subscription does not allow concurrent callbacks); dropped");
  EXPECT_EQ(reports[1], "a callback was not ready to run; dropped");
  EXPECT_EQ(queue.failures(), 2u);
}

TEST(InlineCallbackQueue, AReportThatThrowsIsCountedAndDoesNotEscape)
{
  InlineCallbackQueue queue([](const std::string&) { throw std::bad_alloc(); });
  EXPECT_NO_THROW(
      queue.addCallback(callback([]() -> ros::CallbackInterface::CallResult { throw std::runtime_error("x"); }), 1));
  EXPECT_EQ(queue.failures(), 1u);
}
