// ZoneParameterFilter: which state the robot's cell gives, which complete set of setpoints each change
// emits, and the configuration checks. Expected sets are written out by hand from the configuration
// below (two states and three nominal defaults).
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/filters/zone_parameter_filter.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;
using costmap_layers_test::GridKind;

namespace
{
ParamValue entry(const std::string& node, const std::string& parameter, ParamValue value)
{
  ParamValue e = ParamValue::makeMap();
  e.set("node", ParamValue::makeString(node));
  e.set("parameter", ParamValue::makeString(parameter));
  e.set("value", std::move(value));
  return e;
}

ParamValue names(const std::vector<std::string>& n)
{
  ParamValue l = ParamValue::makeList();
  for (const auto& s : n)
    l.push(ParamValue::makeString(s));
  return l;
}

const std::string kDwa = "/move_base/DWAPlannerROS";
const std::string kInfl = "/costmap_node/inflation_layer";

/// slow (id 1): max_vel_x 0.3; crowded (id 7): max_vel_x 0.5 and inflation_radius 1.0.
/// Nominal: max_vel_x 0.8, inflation_radius 0.55, rotate false.
ParamValue params()
{
  ParamValue p = ParamValue::makeMap();
  p.set("mask_topic", ParamValue::makeString("/zones"));
  p.set("states", names({"slow", "crowded"}));
  ParamValue slow = ParamValue::makeMap();
  slow.set("id", ParamValue::makeInt(1));
  slow.set("setpoints", names({"speed"}));
  slow.set("speed", entry(kDwa, "max_vel_x", ParamValue::makeDouble(0.3)));
  p.set("slow", slow);
  ParamValue crowded = ParamValue::makeMap();
  crowded.set("id", ParamValue::makeInt(7));
  crowded.set("setpoints", names({"speed", "radius"}));
  crowded.set("speed", entry(kDwa, "max_vel_x", ParamValue::makeDouble(0.5)));
  crowded.set("radius", entry(kInfl, "inflation_radius", ParamValue::makeDouble(1.0)));
  p.set("crowded", crowded);
  ParamValue nominal = ParamValue::makeMap();
  nominal.set("speed", entry(kDwa, "max_vel_x", ParamValue::makeDouble(0.8)));
  nominal.set("radius", entry(kInfl, "inflation_radius", ParamValue::makeDouble(0.55)));
  nominal.set("rotate", entry(kDwa, "rotate_in_place", ParamValue::makeBool(false)));
  p.set("nominal_defaults", nominal);
  return p;
}

/// 4 x 1 cells at 1 m from (0, 0): values 0, 1, 7, -1; then 9 (no state) and 120 (invalid).
OccupancyGridData mask()
{
  OccupancyGridData m;
  m.frame_id = "map";
  m.width = 6;
  m.height = 1;
  m.resolution = 1.0;
  m.data = {0, 1, 7, -1, 9, static_cast<int8_t>(120)};
  return m;
}

struct Rig
{
  LayeredCostmap lc{"map", false, false};
  std::shared_ptr<FakeContext> ctx;
  std::shared_ptr<ZoneParameterFilter> filter = std::make_shared<ZoneParameterFilter>();
  std::vector<OutputEvent> events;

  explicit Rig(ParamValue p = params()) : ctx(std::make_shared<FakeContext>(std::move(p)))
  {
    filter->initialize(&lc, "zone_filter", ctx);
    ctx->bind(*filter);
    filter->setOutputListener([this](const OutputEvent& e) { events.push_back(e); });
  }
  /// One cycle with the robot at (x, 0.5); the events it emitted.
  std::vector<OutputEvent> at(double x)
  {
    const std::size_t before = events.size();
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    filter->updateBounds(x, 0.5, 0.0, &x0, &y0, &x1, &y1);
    return {events.begin() + static_cast<long>(before), events.end()};
  }
};

/// The (node, parameter, value text) of a set, for comparisons.
std::vector<std::string> describe(const std::vector<Setpoint>& set)
{
  std::vector<std::string> out;
  for (const auto& s : set)
    out.push_back(s.node + " " + s.parameter + " = " + s.value.toString());
  return out;
}

const std::vector<std::string> kNominal = {kDwa + " max_vel_x = 0.8", kInfl + " inflation_radius = 0.55",
                                           kDwa + " rotate_in_place = false"};
const std::vector<std::string> kSlow = {kDwa + " max_vel_x = 0.3", kInfl + " inflation_radius = 0.55",
                                        kDwa + " rotate_in_place = false"};
const std::vector<std::string> kCrowded = {kDwa + " max_vel_x = 0.5", kInfl + " inflation_radius = 1",
                                           kDwa + " rotate_in_place = false"};

/// The state id and setpoints of one change: exactly two events, Setpoints then ZoneState.
void expectChange(const std::vector<OutputEvent>& ev, int id, const std::vector<std::string>& set,
                  const std::string& label)
{
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[0].kind, OutputKind::Setpoints);
  EXPECT_EQ(describe(ev[0].setpoints), set);
  EXPECT_EQ(ev[0].label, label);
  EXPECT_EQ(ev[1].kind, OutputKind::ZoneState);
  EXPECT_EQ(ev[1].topic, "zone_filter_state");
  EXPECT_EQ(ev[1].value, id);
}
}  // namespace

TEST(ZoneParameterFilter, DeclaresItsPorts)
{
  Rig r;
  ASSERT_EQ(r.ctx->grid_subs.size(), 1u);
  EXPECT_EQ(r.ctx->grid_subs[0].topic, "/zones");
  ASSERT_EQ(r.filter->outputs().size(), 2u);
  EXPECT_EQ(r.filter->outputs()[0].kind, OutputKind::ZoneState);
  EXPECT_EQ(r.filter->outputs()[0].topic, "zone_filter_state");
  EXPECT_EQ(r.filter->outputs()[1].kind, OutputKind::Setpoints);
  EXPECT_DOUBLE_EQ(r.filter->outputs()[1].timeout, 5.0);
}

TEST(ZoneParameterFilter, EnteringAndLeavingZonesEmitsCompleteSets)
{
  Rig r;
  // No mask yet: state 0, the nominal defaults, once.
  expectChange(r.at(0.5), 0, kNominal, "nominal");
  EXPECT_TRUE(r.at(0.5).empty());
  r.ctx->publishGrid(GridKind::Mask, mask());
  EXPECT_TRUE(r.at(0.5).empty());  // a 0 cell: still state 0, nothing new
  expectChange(r.at(1.5), 1, kSlow, "slow");
  EXPECT_TRUE(r.at(1.9).empty());  // same cell
  // slow -> crowded directly: both of crowded's values, and the rest nominal.
  expectChange(r.at(2.5), 7, kCrowded, "crowded");
  // -1 keeps the state in force.
  EXPECT_TRUE(r.at(3.5).empty());
  EXPECT_EQ(r.filter->stateInForce(), 7);
  // crowded -> slow: inflation_radius back to its default in the same set.
  expectChange(r.at(1.5), 1, kSlow, "slow");
  // Leaving the mask: nominal.
  expectChange(r.at(-3.0), 0, kNominal, "nominal");
  for (const auto& rep : r.ctx->reports)
    EXPECT_NE(rep.severity, Severity::Error) << rep.key << ": " << rep.message;
}

TEST(ZoneParameterFilter, UndeclaredAndInvalidValuesAreNominalWithOneErrorEach)
{
  Rig r;
  r.ctx->publishGrid(GridKind::Mask, mask());
  r.at(2.5);                                        // crowded
  expectChange(r.at(4.5), 0, kNominal, "nominal");  // 9: no state
  r.at(2.5);
  r.at(4.5);
  r.at(5.5);  // 120: invalid
  int errors_9 = 0, errors_120 = 0;
  for (const auto& rep : r.ctx->reports)
  {
    EXPECT_EQ(rep.key, "mask/state");
    EXPECT_EQ(rep.severity, Severity::Error);
    if (rep.message.find("value 9,") != std::string::npos) ++errors_9;
    if (rep.message.find("value 120,") != std::string::npos) ++errors_120;
  }
  EXPECT_EQ(errors_9, 1);
  EXPECT_EQ(errors_120, 1);
  EXPECT_EQ(r.filter->stateInForce(), 0);
}

TEST(ZoneParameterFilter, SwitchedOffRestoresTheNominalDefaults)
{
  Rig r;
  r.ctx->publishGrid(GridKind::Mask, mask());
  expectChange(r.at(1.5), 1, kSlow, "slow");
  // Switched off (the ~toggle service's thread): the nominal defaults at once, not at a later cycle,
  // since the host calls a disabled filter no more.
  const std::size_t before = r.events.size();
  r.filter->setEnabled(false);
  expectChange({r.events.begin() + static_cast<long>(before), r.events.end()}, 0, kNominal, "nominal");
  r.filter->setEnabled(true);
  expectChange(r.at(1.5), 1, kSlow, "slow");
}

TEST(ZoneParameterFilter, FilterInfoOfTypeFourOnly)
{
  ParamValue p = params();
  p.erase("mask_topic");
  p.set("filter_info_topic", ParamValue::makeString("/zone_info"));
  Rig r(p);
  ASSERT_EQ(r.ctx->info_subs.size(), 1u);
  FilterInfoData info;
  info.type = 0;
  info.filter_mask_topic = "/zones";
  EXPECT_FALSE(r.filter->setFilterInfo(std::make_shared<FilterInfoData>(info)).empty());
  info.type = 4;
  info.base = 3.0;
  EXPECT_TRUE(r.filter->setFilterInfo(std::make_shared<FilterInfoData>(info)).empty());
  bool warned = false;
  for (const auto& rep : r.ctx->reports)
    warned = warned || rep.key == "filter_info/base";
  EXPECT_TRUE(warned);
}

TEST(ZoneParameterFilterRule, StateForEachKindOfCell)
{
  const ZoneParameterConfig c = parseZoneParameterConfig(ParamReader(params(), "z"));
  bool unknown = true;
  EXPECT_EQ(zoneStateFor(std::nullopt, 7, c, &unknown), 0);
  EXPECT_FALSE(unknown);
  EXPECT_EQ(zoneStateFor(0, 7, c, &unknown), 0);
  EXPECT_EQ(zoneStateFor(-1, 7, c, &unknown), 7);
  EXPECT_EQ(zoneStateFor(1, 7, c, &unknown), 1);
  EXPECT_EQ(zoneStateFor(7, 0, c, &unknown), 7);
  EXPECT_FALSE(unknown);
  EXPECT_EQ(zoneStateFor(2, 7, c, &unknown), 0);
  EXPECT_TRUE(unknown);
  EXPECT_EQ(zoneStateFor(-5, 7, c, &unknown), 0);
  EXPECT_TRUE(unknown);
  EXPECT_EQ(describe(zoneSetpoints(c, 7)), kCrowded);
  EXPECT_EQ(describe(zoneSetpoints(c, 0)), kNominal);
  EXPECT_EQ(zoneStateName(c, 7), "crowded");
  EXPECT_EQ(zoneStateName(c, 0), "nominal");
}

TEST(ZoneParameterFilterConfig, BadConfigurationsAreRefusedNamingTheParameter)
{
  auto refused = [](const ParamValue& p, const std::string& needle)
  {
    try
    {
      parseZoneParameterConfig(ParamReader(p, "zone_filter"));
      ADD_FAILURE() << "accepted; expected an error with " << needle;
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  auto edit = [](const std::string& path, ParamValue v)
  {
    ParamValue p = params();
    // path "state/key" or "key"
    const auto slash = path.find('/');
    if (slash == std::string::npos)
      p.set(path, std::move(v));
    else
      p.findMutable(path.substr(0, slash))->set(path.substr(slash + 1), std::move(v));
    return p;
  };
  refused(edit("slow/id", ParamValue::makeInt(0)), "'id'");
  refused(edit("slow/id", ParamValue::makeInt(101)), "'id'");
  refused(edit("slow/id", ParamValue::makeInt(7)), "the id of state 'slow' too");
  refused(edit("slow/speed", entry("", "max_vel_x", ParamValue::makeDouble(0.3))), "speed/node");
  refused(edit("slow/speed", entry("/a b", "max_vel_x", ParamValue::makeDouble(0.3))), "speed/node");
  refused(edit("slow/speed", entry(kDwa, "", ParamValue::makeDouble(0.3))), "speed/parameter");
  refused(edit("slow/speed", entry(kDwa, "max_vel_x", ParamValue::makeDouble(std::nan("")))), "must be finite");
  refused(edit("slow/speed", entry(kDwa, "max_vel_x", ParamValue::makeList())), "speed/value");
  refused(edit("slow/speed", entry(kDwa, "max_vel_x", ParamValue::makeInt(1))), "write both the same way");
  refused(edit("slow/speed", entry(kDwa, "max_vel_theta", ParamValue::makeDouble(1.0))),
          "nominal_defaults has no value for it");
  refused(edit("slow/stray", ParamValue::makeInt(1)), "parameter 'stray'");
  refused(edit("slow/setpoints", names({"speed", "missing"})), "missing");
  refused(edit("states", names({"slow", "ghost"})), "ghost");
  refused(edit("states", names({"slow", "slow"})), "twice");
  refused(edit("states", names({"enabled"})), "is a parameter of the filter");
  refused(edit("nominal_defaults", names({"speed"})), "must be a map");
  ParamValue twice = params();
  twice.findMutable("nominal_defaults")->set("again", entry(kDwa, "max_vel_x", ParamValue::makeDouble(0.9)));
  refused(twice, "a second time");
  ParamValue extra = params();
  ParamValue e = entry(kDwa, "max_vel_x", ParamValue::makeDouble(0.3));
  e.set("unit", ParamValue::makeString("m/s"));
  extra.findMutable("slow")->set("speed", e);
  refused(extra, "speed/unit");
  refused(edit("setpoint_timeout", ParamValue::makeDouble(0.0)), "setpoint_timeout");
}
