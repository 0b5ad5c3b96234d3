#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <thread>
#include <vector>

#include "costmap_layers/core/layers/observation_buffer.hpp"

using namespace costmap_layers;

namespace
{
constexpr uint64_t kSec = 1'000'000'000ull;

std::shared_ptr<const Observation> obs(uint64_t stamp, double ox = 0.0, double oy = 0.0)
{
  auto o = std::make_shared<Observation>();
  o->stamp_ns = stamp;
  o->origin_x = ox;
  o->origin_y = oy;
  o->points = {{1.0f, 0.0f, 0.0f}};
  return o;
}

std::size_t fetch(ObservationBuffer& b, uint64_t now, double rx = 0.0, double ry = 0.0)
{
  std::vector<std::shared_ptr<const Observation>> out;
  b.getObservations(out, now, rx, ry);
  return out.size();
}
}  // namespace

TEST(ObservationBuffer, ZeroPersistenceKeepsOnlyTheNewest)
{
  ObservationBuffer b("scan", {}, 0);
  b.add(obs(1 * kSec), 1 * kSec);
  auto newest = obs(2 * kSec);
  b.add(newest, 2 * kSec);
  std::vector<std::shared_ptr<const Observation>> out;
  b.getObservations(out, 100 * kSec, 0, 0);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0], newest);
  EXPECT_EQ(fetch(b, 1000 * kSec), 1u);  // the newest stays however old
}

TEST(ObservationBuffer, PersistenceDropsOldObservations)
{
  ObservationBufferConfig c;
  c.observation_persistence = 1.0;
  ObservationBuffer b("cloud", c, 0);
  b.add(obs(10 * kSec), 10 * kSec);
  b.add(obs(10 * kSec + kSec / 2), 10 * kSec + kSec / 2);
  EXPECT_EQ(fetch(b, 11 * kSec), 2u);             // ages 1.0 and 0.5: both kept
  EXPECT_EQ(fetch(b, 11 * kSec + kSec / 4), 1u);  // 1.25 s old: dropped
  EXPECT_EQ(fetch(b, 12 * kSec), 0u);
  b.add(obs(15 * kSec + kSec / 4), 15 * kSec);  // stamped a little ahead (skew between hosts): fresh
  EXPECT_EQ(fetch(b, 15 * kSec), 1u);
}

TEST(ObservationBuffer, KeepDistanceDropsFarObservations)
{
  ObservationBufferConfig c;
  c.observation_persistence = 10.0;
  c.observation_keep_distance = 2.0;
  ObservationBuffer b("cloud", c, 0);
  b.add(obs(kSec, 0.0, 0.0), kSec);
  b.add(obs(kSec, 3.0, 0.0), kSec);
  EXPECT_EQ(fetch(b, kSec, 1.0, 0.0), 2u);
  EXPECT_EQ(fetch(b, kSec, 4.5, 0.0), 1u);  // 4.5 m from the first
  EXPECT_EQ(b.size(), 1u);
  EXPECT_EQ(fetch(b, kSec, 4.5, 3.0), 0u);  // 3.35 m from the second
}

TEST(ObservationBuffer, ExpectedUpdateRateIsAPeriod)
{
  ObservationBufferConfig c;
  c.expected_update_rate = 0.5;
  ObservationBuffer b("scan", c, 2 * kSec);
  EXPECT_TRUE(b.isCurrent(2 * kSec + kSec / 2));
  EXPECT_FALSE(b.isCurrent(2 * kSec + kSec / 2 + 1));  // never updated since creation
  b.add(obs(3 * kSec), 3 * kSec);
  EXPECT_TRUE(b.isCurrent(3 * kSec + kSec / 4));
  EXPECT_NEAR(b.secondsSinceUpdate(4 * kSec), 1.0, 1e-9);
  EXPECT_FALSE(b.isCurrent(4 * kSec));
  b.resetLastUpdated(4 * kSec);
  EXPECT_TRUE(b.isCurrent(4 * kSec));
  ObservationBuffer unchecked("x", {}, 0);
  EXPECT_TRUE(unchecked.isCurrent(1000 * kSec));
}

TEST(ObservationBuffer, ConcurrentAddAndGet)
{
  ObservationBufferConfig c;
  c.observation_persistence = 0.001;
  ObservationBuffer b("cloud", c, 0);
  std::atomic<bool> stop{false};
  std::atomic<uint64_t> now{kSec};
  std::thread producer(
      [&]
      {
        while (!stop)
          b.add(obs(now.load()), now.load());
      });
  while (b.size() == 0)
    std::this_thread::yield();
  std::size_t seen = 0;
  for (int i = 0; i < 2000; ++i)
  {
    now += kSec / 10000;
    seen += fetch(b, now.load());
  }
  stop = true;
  producer.join();
  EXPECT_GT(seen, 0u);
  EXPECT_EQ(fetch(b, now.load() + kSec), 0u);  // all older than the 1 ms persistence by then
  b.clear();
  EXPECT_EQ(b.size(), 0u);
}

TEST(ObservationBuffer, StampsFarAheadOfNowExpireAndDoNotShieldOthers)
{
  ObservationBufferConfig c;
  c.observation_persistence = 1.0;
  ObservationBuffer b("cloud", c, 0);
  // 90 s ahead of the clock: not a reading of this time line. It used to count as fresh and, at the
  // front of the buffer, to stop the purge: the 10 s reading behind it never expired either.
  b.add(obs(100 * kSec), 10 * kSec);
  b.add(obs(10 * kSec), 10 * kSec);
  EXPECT_EQ(fetch(b, 10 * kSec), 1u);
  EXPECT_EQ(fetch(b, 12 * kSec), 0u);
  // Within half a second ahead (skew between hosts): kept, and aged from its stamp.
  b.add(obs(20 * kSec + 400'000'000), 20 * kSec);
  EXPECT_EQ(fetch(b, 20 * kSec), 1u);
  EXPECT_EQ(fetch(b, 21 * kSec + 300'000'000), 1u);
  EXPECT_EQ(fetch(b, 21 * kSec + 500'000'000), 0u);
  // The worst stamp a sender can write.
  b.add(obs(UINT64_MAX), 30 * kSec);
  EXPECT_EQ(fetch(b, 30 * kSec), 0u);
}

TEST(ObservationBuffer, PurgeDropsEveryExpiredReadingNotOnlyTheFrontOnes)
{
  ObservationBufferConfig c;
  c.observation_persistence = 1.0;
  ObservationBuffer b("cloud", c, 0);
  b.add(obs(11 * kSec), 11 * kSec);
  b.add(obs(9 * kSec), 11 * kSec);  // arrived late: older than the one before it
  EXPECT_EQ(fetch(b, 11 * kSec + kSec / 2), 1u);
}

TEST(ObservationBuffer, ClockJumpBackClearsTheBufferAndRestartsTheUpdateRateCheck)
{
  ObservationBufferConfig c;
  c.observation_persistence = 5.0;
  c.expected_update_rate = 1.0;
  ObservationBuffer b("scan", c, 990 * kSec);
  b.add(obs(1000 * kSec), 1000 * kSec);
  // The clock restarts at 3 s: the reading of 1000 s is from another time line.
  EXPECT_EQ(fetch(b, 3 * kSec), 0u);
  EXPECT_EQ(b.size(), 0u);
  EXPECT_TRUE(b.isCurrent(3 * kSec));                                 // the check restarts at the jump
  EXPECT_NEAR(b.secondsSinceUpdate(4 * kSec + kSec / 2), 1.5, 1e-9);  // not 0 until 1000 s again
  EXPECT_FALSE(b.isCurrent(4 * kSec + kSec / 2));
  b.add(obs(5 * kSec), 5 * kSec);
  EXPECT_TRUE(b.isCurrent(5 * kSec));
  EXPECT_EQ(fetch(b, 5 * kSec), 1u);
}

TEST(ObservationBuffer, ClockJumpBackSeenFirstByTheUpdateRateCheck)
{
  ObservationBufferConfig c;
  c.expected_update_rate = 1.0;
  ObservationBuffer b("scan", c, 0);
  b.add(obs(1000 * kSec), 1000 * kSec);
  EXPECT_TRUE(b.isCurrent(5 * kSec));
  EXPECT_FALSE(b.isCurrent(6 * kSec + kSec / 2));  // silent for 1.5 s on the new clock
  EXPECT_EQ(fetch(b, 6 * kSec + kSec / 2), 0u);
}

TEST(ObservationBuffer, SmallStepsBackAndForwardJumps)
{
  ObservationBufferConfig c;
  c.observation_persistence = 2.0;
  c.expected_update_rate = 1.0;
  ObservationBuffer b("scan", c, 0);
  b.add(obs(100 * kSec), 100 * kSec);
  // 0.2 s back: threads reading the clock a moment apart, not a jump.
  EXPECT_EQ(fetch(b, 100 * kSec - 200'000'000), 1u);
  EXPECT_TRUE(b.isCurrent(100 * kSec - 200'000'000));
  // A jump forward: everything aged by it.
  EXPECT_EQ(fetch(b, 10'000 * kSec), 0u);
  EXPECT_FALSE(b.isCurrent(10'000 * kSec));
  // The clock at its extremes.
  b.add(obs(0), UINT64_MAX);
  EXPECT_EQ(fetch(b, UINT64_MAX), 0u);  // stamped 0, now at the end of time: ~584 years old
  EXPECT_TRUE(b.isCurrent(UINT64_MAX));
  b.add(obs(kSec), kSec);  // and back to the start: a jump
  EXPECT_EQ(fetch(b, kSec), 1u);
  EXPECT_TRUE(b.isCurrent(kSec));
}

// A 1 kHz flood with a 10 s persistence would keep 10 000 readings, each raytraced every update.
// The buffer keeps at most kMaxObservations, the newest, and counts what it pushed out.
TEST(ObservationBuffer, AFloodKeepsTheNewestAndCountsTheRest)
{
  ObservationBufferConfig c;
  c.observation_persistence = 10.0;
  ObservationBuffer b("scan", c, 0);
  const uint64_t t0 = 100 * kSec;
  std::shared_ptr<const Observation> last;
  for (uint64_t k = 0; k < 10000; ++k)
  {
    last = obs(t0 + k * kSec / 1000);
    ASSERT_TRUE(b.add(last, t0 + k * kSec / 1000));
  }
  EXPECT_EQ(b.size(), ObservationBuffer::kMaxObservations);
  EXPECT_EQ(b.takeDropped(), 10000u - ObservationBuffer::kMaxObservations);
  EXPECT_EQ(b.takeDropped(), 0u);  // counted once
  std::vector<std::shared_ptr<const Observation>> out;
  b.getObservations(out, t0 + 10 * kSec, 0, 0);
  ASSERT_EQ(out.size(), ObservationBuffer::kMaxObservations);
  EXPECT_EQ(out.back(), last);
  EXPECT_EQ(out.front()->stamp_ns, t0 + (10000 - ObservationBuffer::kMaxObservations) * kSec / 1000);
}
