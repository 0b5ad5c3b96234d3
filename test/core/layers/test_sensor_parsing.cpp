#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "costmap_layers/core/layers/sensor_parsing.hpp"
#include "sensor_test_helpers.hpp"

using namespace costmap_layers;
using namespace costmap_layers_test;

namespace
{
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

ParseResult scanPoints(const LaserScanData& s, bool inf_is_valid, std::vector<Point3f>& pts,
                       std::vector<Point3f>& clear)
{
  pts.clear();
  clear.clear();
  return laserScanToPoints(s, inf_is_valid, pts, clear);
}
}  // namespace

TEST(LaserScanParsing, ProjectsValidBeams)
{
  LaserScanData s = makeScan(3, -1.5707964f, 1.5707964f, 2.0f, 0.1f, 5.0f);
  std::vector<Point3f> pts, clear;
  const ParseResult r = scanPoints(s, false, pts, clear);
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(pts.size(), 3u);
  EXPECT_NEAR(pts[0].y, -2.0f, 1e-5);
  EXPECT_NEAR(pts[1].x, 2.0f, 1e-6);
  EXPECT_NEAR(pts[2].y, 2.0f, 1e-5);
  EXPECT_EQ(r.points, 3u);
  EXPECT_EQ(r.dropped, 0u);
}

TEST(LaserScanParsing, NanInfAndOutOfRangeBeams)
{
  LaserScanData s = makeScan(6, 0.0f, 0.5f, 1.0f, 0.2f, 4.0f);
  s.ranges = {kNaN, kInf, -kInf, 0.1f, 4.0f, 1.0f};
  std::vector<Point3f> pts, clear;
  ParseResult r = scanPoints(s, false, pts, clear);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(pts.size(), 1u);
  EXPECT_TRUE(clear.empty());
  EXPECT_EQ(r.dropped, 5u);
  r = scanPoints(s, true, pts, clear);  // +inf: a clearing-only point at range_max
  EXPECT_EQ(pts.size(), 1u);
  ASSERT_EQ(clear.size(), 1u);
  EXPECT_NEAR(std::hypot(clear[0].x, clear[0].y), 4.0, 1e-5);
  EXPECT_EQ(r.clear_only, 1u);
  EXPECT_EQ(r.dropped, 4u);
}

TEST(LaserScanParsing, RejectsMalformedScans)
{
  std::vector<Point3f> pts, clear;
  auto error = [&](LaserScanData s) { return scanPoints(s, true, pts, clear).error; };
  const LaserScanData good = makeScan(11, -0.5f, 0.5f, 1.0f);
  EXPECT_EQ(error(good), "");
  LaserScanData s = good;
  s.angle_increment = 0.0f;
  EXPECT_NE(error(s).find("angle_increment is zero"), std::string::npos);
  s = good;
  s.angle_increment = kNaN;
  EXPECT_NE(error(s).find("angle_increment"), std::string::npos);
  s = good;
  s.angle_increment = -0.1f;  // wrong sign for min < max
  EXPECT_NE(error(s).find("sign"), std::string::npos);
  s = good;
  s.angle_increment = 1e-12f;  // far too many beams for 11 ranges
  EXPECT_FALSE(error(s).empty());
  s = good;
  s.ranges.resize(5);  // truncated
  EXPECT_NE(error(s).find("ranges has 5 values"), std::string::npos) << error(s);
  s = good;
  s.ranges.resize(12);  // one extra beam is tolerated (drivers disagree on the last one)
  EXPECT_EQ(error(s), "");
  s = good;
  s.range_max = kInf;
  EXPECT_NE(error(s).find("range_max"), std::string::npos);
  s = good;
  s.range_min = kNaN;
  EXPECT_NE(error(s).find("range_min"), std::string::npos);
  s = good;
  s.range_min = 5.0f;
  s.range_max = 1.0f;
  EXPECT_FALSE(error(s).empty());
  s = good;
  s.angle_min = -kInf;
  EXPECT_NE(error(s).find("angle_min"), std::string::npos);
  EXPECT_TRUE(pts.empty());
  // Decreasing angles are fine when the increment is negative.
  s = makeScan(11, 0.5f, -0.5f, 1.0f);
  EXPECT_LT(s.angle_increment, 0.0f);
  EXPECT_EQ(error(s), "");
}

TEST(PointCloud2Parsing, Float32AndFloat64BothByteOrders)
{
  const std::vector<XYZ> in = {{1.0, 2.0, 3.0}, {-4.5, 0.25, 1e-3}};
  for (bool f64 : {false, true})
  {
    for (bool big : {false, true})
    {
      std::vector<Point3f> pts;
      const ParseResult r = pointCloud2ToPoints(makeCloud(in, f64, big), pts);
      ASSERT_TRUE(r.ok()) << r.error;
      ASSERT_EQ(pts.size(), 2u) << f64 << big;
      EXPECT_FLOAT_EQ(pts[0].x, 1.0f);
      EXPECT_FLOAT_EQ(pts[0].y, 2.0f);
      EXPECT_FLOAT_EQ(pts[0].z, 3.0f);
      EXPECT_FLOAT_EQ(pts[1].x, -4.5f);
      EXPECT_FLOAT_EQ(pts[1].y, 0.25f);
      EXPECT_FLOAT_EQ(pts[1].z, 1e-3f);
    }
  }
}

TEST(PointCloud2Parsing, SkipsNonFinitePointsAndHonoursRowPadding)
{
  PointCloud2Data c = makeCloud({{1, 1, 1}, {NAN, 0, 0}, {2, 2, 2}, {0, INFINITY, 0}});
  c.width = 2;
  c.height = 2;
  c.row_step = 2 * c.point_step + 8;  // padded rows
  std::vector<uint8_t> padded;
  for (int row = 0; row < 2; ++row)
  {
    padded.insert(padded.end(), c.data.begin() + row * 2 * c.point_step, c.data.begin() + (row + 1) * 2 * c.point_step);
    padded.insert(padded.end(), 8, 0xEE);
  }
  c.data = padded;
  std::vector<Point3f> pts;
  const ParseResult r = pointCloud2ToPoints(c, pts);
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(pts.size(), 2u);
  EXPECT_EQ(r.dropped, 2u);
  EXPECT_FLOAT_EQ(pts[1].x, 2.0f);
  // Doubles beyond float's range are dropped too.
  std::vector<Point3f> big;
  EXPECT_EQ(pointCloud2ToPoints(makeCloud({{1e300, 0, 0}, {1, 0, 0}}, true), big).dropped, 1u);
  EXPECT_EQ(big.size(), 1u);
}

TEST(PointCloud2Parsing, RejectsHostileLayouts)
{
  const PointCloud2Data good = makeCloud({{1, 2, 3}, {4, 5, 6}});
  auto error = [](const PointCloud2Data& c)
  {
    std::vector<Point3f> pts;
    const ParseResult r = pointCloud2ToPoints(c, pts);
    EXPECT_TRUE(r.ok() || pts.empty());
    return r.error;
  };
  EXPECT_EQ(error(good), "");
  PointCloud2Data c = good;
  c.data.resize(c.data.size() - 1);  // truncated
  EXPECT_NE(error(c).find("data has"), std::string::npos);
  c = good;
  c.width = 0xFFFFFFFFu;  // huge: row_step no longer covers it
  EXPECT_NE(error(c).find("row_step"), std::string::npos);
  c = good;
  c.width = 0xFFFFFFFFu;
  c.height = 0xFFFFFFFFu;
  c.row_step = 0xFFFFFFFFu;
  c.point_step = 1;
  c.fields = {
      {"x", 0, PointFieldData::FLOAT32, 1}, {"y", 0, PointFieldData::FLOAT32, 1}, {"z", 0, PointFieldData::FLOAT32, 1}};
  EXPECT_FALSE(error(c).empty());  // fields do not fit in 1 byte
  c.point_step = 4;
  EXPECT_FALSE(error(c).empty());  // width * point_step overflows 32 bits: above row_step
  c = good;
  c.point_step = 0;
  EXPECT_NE(error(c).find("point_step is 0"), std::string::npos);
  c = good;
  c.fields[2].offset = 0xFFFFFFF0u;  // offset past the end (and overflowing when added)
  EXPECT_NE(error(c).find("'z' at offset"), std::string::npos) << error(c);
  c = good;
  c.fields[1].datatype = PointFieldData::UINT16;
  EXPECT_NE(error(c).find("'y' is not FLOAT32"), std::string::npos);
  c = good;
  c.fields.erase(c.fields.begin());
  EXPECT_NE(error(c).find("no field 'x'"), std::string::npos);
  c = good;
  c.row_step = 3;
  EXPECT_FALSE(error(c).empty());
  c = good;  // an empty cloud is valid
  c.width = 0;
  c.row_step = 0;
  c.data.clear();
  EXPECT_EQ(error(c), "");
  EXPECT_EQ(validatePointCloud2(good), "");
}

TEST(RangeParsing, VariableFixedAndMalformed)
{
  RangeData r;
  r.field_of_view = 0.2f;
  r.min_range = 0.5f;
  r.max_range = 4.0f;
  r.range = 2.0f;
  RangeInterpretation i = interpretRange(r, RangeInputType::All, false);
  EXPECT_TRUE(i.ok());
  EXPECT_TRUE(i.use);
  EXPECT_FALSE(i.clear);
  EXPECT_DOUBLE_EQ(i.range, 2.0);
  r.range = 4.0f;
  EXPECT_FALSE(interpretRange(r, RangeInputType::Variable, false).clear);
  EXPECT_TRUE(interpretRange(r, RangeInputType::Variable, true).clear);
  r.range = 4.5f;  // beyond max: ignored
  EXPECT_FALSE(interpretRange(r, RangeInputType::Variable, true).use);
  r.range = kInf;
  EXPECT_TRUE(interpretRange(r, RangeInputType::All, true).ok());
  EXPECT_FALSE(interpretRange(r, RangeInputType::All, true).use);
  // Fixed rangers (min == max under ALL, or forced).
  r.min_range = r.max_range = 1.0f;
  r.range = -kInf;
  i = interpretRange(r, RangeInputType::All, false);
  EXPECT_TRUE(i.use);
  EXPECT_FALSE(i.clear);
  EXPECT_DOUBLE_EQ(i.range, 1.0);
  r.range = kInf;
  EXPECT_FALSE(interpretRange(r, RangeInputType::All, false).use);
  EXPECT_TRUE(interpretRange(r, RangeInputType::All, true).clear);
  r.range = 0.7f;
  EXPECT_FALSE(interpretRange(r, RangeInputType::Fixed, true).ok());
  // Malformed.
  RangeData bad = r;
  bad.range = kNaN;
  EXPECT_NE(interpretRange(bad, RangeInputType::All, true).error.find("NaN"), std::string::npos);
  bad = r;
  bad.field_of_view = 0.0f;
  EXPECT_NE(interpretRange(bad, RangeInputType::All, true).error.find("field_of_view"), std::string::npos);
  bad.field_of_view = kInf;
  EXPECT_FALSE(interpretRange(bad, RangeInputType::All, true).ok());
  bad = r;
  bad.min_range = -1.0f;
  EXPECT_NE(interpretRange(bad, RangeInputType::All, true).error.find("min_range"), std::string::npos);
  bad = r;
  bad.max_range = kNaN;
  EXPECT_NE(interpretRange(bad, RangeInputType::All, true).error.find("max_range"), std::string::npos);
}
