// The distance engine (see distance_transform.hpp): scratch buffers, the bands a window is cut into
// and the threads that run them, the kernels' jobs (distance_kernels.cpp, SIMD), and the envelope
// path for reaches beyond the banded kernels. The cost table is in distance_costs.cpp.
#include "costmap_layers/core/kernels/distance_transform.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <exception>
#include <functional>
#include <stdexcept>
#include <string>
#include <thread>

#include "src/core/kernels/distance_job.hpp"

namespace costmap_layers
{
namespace
{
constexpr uint32_t kNoSourceInColumn = 0x7FFFFFFFu;

int64_t floorDiv(int64_t num, int64_t den)
{
  return num >= 0 ? num / den : -((-num + den - 1) / den);
}

template <class T>
void grow(std::vector<T>& v, std::size_t size)
{
  if (v.size() < size) v.resize(size);
}
}  // namespace

// ---- Scratch ------------------------------------------------------------------------------------

struct DistanceTransformScratch::Buffers
{
  std::vector<uint8_t> rows;  // stripe rows (+ alignment)
  std::vector<uint8_t> run, up, out_row, costs;
  std::vector<uint16_t> sq, acc, squares;
  std::vector<int32_t> paint_list;
  std::vector<int> paint_counts;
  std::vector<uint8_t> gather_est;
  std::vector<const uint8_t*> src_rows;
  std::vector<uint8_t> snapshot;  // other bands' rows (threads)
  std::vector<uint32_t> exact;    // the envelope path: vertical distances of the padded window
  std::vector<int64_t> f;
  std::vector<int32_t> s, t;
  std::vector<uint8_t> envelope_costs;
  std::vector<DistanceTransformScratch> workers;  // one per extra thread
};

DistanceTransformScratch::DistanceTransformScratch() : buffers(std::make_unique<Buffers>()) {}
DistanceTransformScratch::~DistanceTransformScratch() = default;
DistanceTransformScratch::DistanceTransformScratch(DistanceTransformScratch&&) noexcept = default;
DistanceTransformScratch& DistanceTransformScratch::operator=(DistanceTransformScratch&&) noexcept = default;

namespace
{
struct Call
{
  const uint8_t* grid;
  uint8_t* target;  // merge mode, else nullptr
  int width, height;
  std::ptrdiff_t stride;
  SourceRange source;
  const DistanceCosts* costs;
  DistanceWindow win;  // clipped, non-empty
  CostMergeRule rule;
  const CostRowSink* sink;
  int cap;  // the reach, clamped to the grid's diagonal
};

/// Rows [b0, b1) of the window by the vector engine. Rows of the window outside the band (written by
/// other threads) are read from `snapshot_from` (a copy taken before any thread started) when given.
void runBand(const Call& c, int b0, int b1, DistanceTransformScratch::Buffers& b, const uint8_t* snapshot_base,
             int snapshot_y0, std::ptrdiff_t snapshot_stride)
{
  const int cap = c.cap;
  dt::Job j{};
  j.win = c.win;
  j.win.y0 = b0;
  j.win.y1 = b1;
  j.cx0 = std::max(0, c.win.x0 - cap);
  j.cx1 = std::min(c.width, c.win.x1 + cap);
  j.ry0 = std::max(0, b0 - cap);
  j.ry1 = std::min(c.height, b1 + cap);
  j.source = c.source;
  j.cap = cap;
  j.offset_tables = c.costs->offsetTables();
  j.table16 = c.costs->table16();
  j.wide_tables = c.costs->wideTables();
  j.paint = c.costs->paintTables();
  j.paint_shift = c.costs->paintShift();
  j.paint_center = c.costs->paintCenter();
  j.target = c.target;
  j.target_stride = c.stride;
  j.rule = c.rule;
  j.sink = c.sink;
  const int n = c.win.x1 - c.win.x0;
  const int cw = j.cx1 - j.cx0;
  // Listing a row's columns (listPainted) reads up to two vectors past the reach on the right.
  j.pad = cap + (j.paint != nullptr ? 2 : 1) * dt::kMaxLanes;
  // Rows start on a cache line, and so does window column 0.
  j.row_stride = (n + 2 * j.pad + dt::kMaxLanes - 1) / dt::kMaxLanes * dt::kMaxLanes;
  // A stripe of about 256 KiB stays in the level-2 cache between the two sweeps; at least 2 * cap rows
  // so that the lookahead of cap rows per stripe stays a small part of the reads.
  j.stripe = std::max({16, 2 * cap, (256 << 10) / j.row_stride});
  j.stripe = std::min(j.stripe, b1 - b0);
  const std::size_t rows_size = static_cast<std::size_t>(j.stripe) * static_cast<std::size_t>(j.row_stride);
  // Slack past the last row: the 16-bit row pass reads up to one vector beyond a row's padding.
  grow(b.rows, rows_size + 3 * dt::kMaxLanes);
  const std::size_t misalign = reinterpret_cast<std::uintptr_t>(b.rows.data() + j.pad) % dt::kMaxLanes;
  j.rows = b.rows.data() + (misalign == 0 ? 0 : dt::kMaxLanes - misalign);
  grow(b.run, static_cast<std::size_t>(cw));
  grow(b.up, static_cast<std::size_t>(cw));
  j.run = b.run.data();
  j.up = b.up.data();
  if (cap > dt::kMaxCostDomainReach)
  {
    grow(b.sq, static_cast<std::size_t>(j.row_stride + dt::kMaxLanes));
    grow(b.acc, static_cast<std::size_t>(dt::kMaxLanes));
    grow(b.costs, static_cast<std::size_t>(dt::kMaxLanes));
    j.sq = b.sq.data();
    grow(b.squares, static_cast<std::size_t>(8 * (cap + 1)));
    for (int dx = 0; dx <= cap; ++dx)
      std::fill_n(b.squares.begin() + 8 * dx, 8, static_cast<uint16_t>(dx * dx));
    j.squares = b.squares.data();
    j.acc = b.acc.data();
    j.costs = b.costs.data();
  }
  if (j.paint != nullptr)
  {
    // At most one entry per column listed (n rounded up to a vector, 2 cap, one chunk), and a vector
    // of slack for the compressing store; a count per column at most.
    const std::size_t columns = static_cast<std::size_t>(n + 2 * cap + 2 * dt::kMaxLanes);
    grow(b.paint_list, columns + dt::kMaxLanes);
    grow(b.paint_counts, columns + 1);
    // Before the first row every block is taken to need every offset.
    b.gather_est.assign(static_cast<std::size_t>(n) + 1, static_cast<uint8_t>(cap));
    j.gather_est = b.gather_est.data();
    j.paint_list = b.paint_list.data();
    j.paint_counts = b.paint_counts.data();
  }
  if (c.sink != nullptr)
  {
    grow(b.out_row, static_cast<std::size_t>(n));
    j.out_row = b.out_row.data();
  }
  b.src_rows.resize(static_cast<std::size_t>(j.ry1 - j.ry0));
  for (int y = j.ry0; y < j.ry1; ++y)
  {
    const bool other = snapshot_base != nullptr && (y < b0 || y >= b1) && y >= c.win.y0 && y < c.win.y1;
    b.src_rows[static_cast<std::size_t>(y - j.ry0)] =
        other ? snapshot_base + (y - snapshot_y0) * snapshot_stride : c.grid + y * c.stride + j.cx0;
  }
  j.src_rows = b.src_rows.data();
  runDistanceJob(j);
}

/// The envelope path (reach beyond the banded engines): exact vertical distances of the padded window,
/// then the lower envelope of parabolas per row (Meijster, Roerdink and Hesselink), in integers.
void runEnvelope(const Call& c, DistanceTransformScratch::Buffers& b)
{
  const int cap = c.cap;
  const DistanceWindow& win = c.win;
  const int px0 = std::max(0, win.x0 - cap), px1 = std::min(c.width, win.x1 + cap);
  const int py0 = std::max(0, win.y0 - cap), py1 = std::min(c.height, win.y1 + cap);
  const int pw = px1 - px0, ph = py1 - py0;
  grow(b.exact, static_cast<std::size_t>(pw) * static_cast<std::size_t>(ph));
  uint32_t* g = b.exact.data();
  const SourceRange src = c.source;
  for (int y = 0; y < ph; ++y)
  {
    const uint8_t* row = c.grid + (py0 + y) * c.stride + px0;
    uint32_t* gy = g + static_cast<std::size_t>(y) * pw;
    const uint32_t* prev = y > 0 ? gy - pw : nullptr;
    for (int x = 0; x < pw; ++x)
    {
      const uint32_t above = prev != nullptr ? std::min(prev[x] + 1u, kNoSourceInColumn) : kNoSourceInColumn;
      gy[x] = src.contains(row[x]) ? 0u : above;
    }
  }
  for (int y = ph - 2; y >= 0; --y)
  {
    uint32_t* gy = g + static_cast<std::size_t>(y) * pw;
    const uint32_t* next = gy + pw;
    for (int x = 0; x < pw; ++x)
      gy[x] = std::min(gy[x], std::min(next[x] + 1u, kNoSourceInColumn));
  }
  grow(b.f, static_cast<std::size_t>(pw));
  grow(b.s, static_cast<std::size_t>(pw));
  grow(b.t, static_cast<std::size_t>(pw));
  const int n = win.x1 - win.x0;
  grow(b.envelope_costs, static_cast<std::size_t>(n));
  int64_t* f = b.f.data();
  int32_t* s = b.s.data();
  int32_t* t = b.t.data();
  uint8_t* costs = b.envelope_costs.data();
  const uint64_t reach_sq = c.costs->reachSquared();
  for (int y = win.y0; y < win.y1; ++y)
  {
    const uint32_t* gy = g + static_cast<std::size_t>(y - py0) * pw;
    for (int x = 0; x < pw; ++x)
      f[x] = gy[x] == kNoSourceInColumn ? -1 : static_cast<int64_t>(gy[x]) * gy[x];
    int q = -1;
    for (int u = 0; u < pw; ++u)
    {
      if (f[u] < 0) continue;
      while (q >= 0)
      {
        const int64_t a = static_cast<int64_t>(t[q] - s[q]) * (t[q] - s[q]) + f[s[q]];
        const int64_t bb = static_cast<int64_t>(t[q] - u) * (t[q] - u) + f[u];
        if (a <= bb) break;
        --q;
      }
      if (q < 0)
      {
        q = 0;
        s[0] = u;
        t[0] = 0;
        continue;
      }
      const int64_t i = s[q];
      const int64_t w = floorDiv(static_cast<int64_t>(u) * u - i * i + f[u] - f[i], 2 * (u - i)) + 1;
      if (w < pw)
      {
        ++q;
        s[q] = u;
        t[q] = static_cast<int32_t>(w);
      }
    }
    for (int x = pw - 1; x >= 0; --x)
    {
      const int wx = x + px0 - win.x0;
      if (q < 0)
      {
        if (wx >= 0 && wx < n) costs[wx] = 0;
        continue;
      }
      if (wx >= 0 && wx < n)
      {
        const int64_t dx = x - s[q];
        const uint64_t d2 = static_cast<uint64_t>(dx * dx + f[s[q]]);
        costs[wx] = d2 <= reach_sq ? c.costs->at(d2) : uint8_t{0};
      }
      if (x == t[q]) --q;
    }
    if (c.sink != nullptr)
    {
      (*c.sink)(y, costs);
      continue;
    }
    uint8_t* out = c.target + y * c.stride + win.x0;
    for (int k = 0; k < n; ++k)
    {
      const uint8_t old = out[k], cost = costs[k];
      const uint8_t for_special = cost >= c.rule.special_threshold ? cost : c.rule.special;
      out[k] = old == c.rule.special ? for_special : std::max(old, cost);
    }
  }
}

void run(const Call& call_in, DistanceTransformScratch& scratch, int threads)
{
  Call c = call_in;
  DistanceTransformScratch::Buffers& b = *scratch.buffers;
  if (c.target != nullptr && c.rule.special_threshold == 0)
    throw std::invalid_argument("distanceCostMerge: special_threshold must be >= 1");
  if (threads < 1) throw std::invalid_argument("distanceCostMerge: threads must be >= 1");
  c.win.x0 = std::max(0, c.win.x0);
  c.win.y0 = std::max(0, c.win.y0);
  c.win.x1 = std::min(c.width, c.win.x1);
  c.win.y1 = std::min(c.height, c.win.y1);
  if (c.win.x0 >= c.win.x1 || c.win.y0 >= c.win.y1) return;
  if (!c.costs->any())
  {
    // Nothing costs anything: merging 0 changes no cell; the sink gets zero rows.
    if (c.sink == nullptr) return;
    grow(b.out_row, static_cast<std::size_t>(c.win.x1 - c.win.x0));
    std::fill(b.out_row.begin(), b.out_row.end(), 0);
    for (int y = c.win.y0; y < c.win.y1; ++y)
      (*c.sink)(y, b.out_row.data());
    return;
  }
  if (c.costs->reach() > dt::kMaxBandedReach)
  {
    // No two cells of the grid are farther apart than its diagonal: a larger reach changes nothing.
    const double diagonal = std::ceil(std::hypot(static_cast<double>(c.width), static_cast<double>(c.height)));
    c.cap = static_cast<int>(std::min<double>(static_cast<double>(c.costs->reach()), diagonal));
    runEnvelope(c, b);
    return;
  }
  // The banded engines use the reach itself: their tables say "far" (cost 0) at reach + 1.
  c.cap = static_cast<int>(c.costs->reach());
  const int rows = c.win.y1 - c.win.y0;
  // Bands of at least 64 rows and 2 * cap (shorter ones spend more on their lookahead of cap rows
  // than they save), about four per thread: the threads take the next band as they finish one, so
  // that a band of busy rows (a dense part of the map) does not leave the other threads waiting.
  const int max_bands = std::max(1, rows / std::max(64, 2 * c.cap));
  threads = c.sink != nullptr ? 1 : std::min(threads, max_bands);
  if (threads == 1)
  {
    runBand(c, c.win.y0, c.win.y1, b, nullptr, 0, 0);
    return;
  }
  const int bands = std::min(max_bands, 4 * threads);
  // Each band reads the rows within reach of it; those of other bands are written concurrently, so
  // they are read from a copy taken now (only the sources matter, and writing does not change them).
  const int cx0 = std::max(0, c.win.x0 - c.cap), cx1 = std::min(c.width, c.win.x1 + c.cap);
  const std::ptrdiff_t snap_stride = cx1 - cx0;
  std::vector<int> bounds(static_cast<std::size_t>(bands) + 1);
  for (int k = 0; k <= bands; ++k)
    bounds[static_cast<std::size_t>(k)] = c.win.y0 + static_cast<int>(static_cast<int64_t>(rows) * k / bands);
  // Copy every window row within reach of a band boundary.
  grow(b.snapshot, static_cast<std::size_t>(rows) * static_cast<std::size_t>(snap_stride));
  std::vector<char> copied(static_cast<std::size_t>(rows), 0);
  for (int k = 1; k < bands; ++k)
  {
    const int at = bounds[static_cast<std::size_t>(k)];
    for (int y = std::max(c.win.y0, at - c.cap); y < std::min(c.win.y1, at + c.cap); ++y)
    {
      if (copied[static_cast<std::size_t>(y - c.win.y0)]) continue;
      copied[static_cast<std::size_t>(y - c.win.y0)] = 1;
      std::memcpy(b.snapshot.data() + static_cast<std::size_t>(y - c.win.y0) * snap_stride, c.grid + y * c.stride + cx0,
                  static_cast<std::size_t>(snap_stride));
    }
  }
  if (b.workers.size() < static_cast<std::size_t>(threads - 1)) b.workers.resize(static_cast<std::size_t>(threads - 1));
  std::vector<std::thread> pool;
  pool.reserve(static_cast<std::size_t>(threads - 1));
  const uint8_t* snap = b.snapshot.data();
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(threads));
  std::atomic<int> next_band{0};
  auto worker = [&](int k, DistanceTransformScratch::Buffers& buffers)
  {
    try
    {
      for (int i = next_band.fetch_add(1); i < bands; i = next_band.fetch_add(1))
        runBand(c, bounds[static_cast<std::size_t>(i)], bounds[static_cast<std::size_t>(i) + 1], buffers, snap,
                c.win.y0, snap_stride);
    }
    catch (...)
    {
      errors[static_cast<std::size_t>(k)] = std::current_exception();
      next_band.store(bands);  // the others stop after their current band
    }
  };
  for (int k = 1; k < threads; ++k)
    pool.emplace_back(worker, k, std::ref(*b.workers[static_cast<std::size_t>(k - 1)].buffers));
  worker(0, b);
  for (auto& t : pool)
    t.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}
}  // namespace

void distanceCostMerge(uint8_t* grid, int width, int height, std::ptrdiff_t stride, SourceRange source,
                       const DistanceCosts& costs, const DistanceWindow& window, CostMergeRule rule,
                       DistanceTransformScratch& scratch, int threads)
{
  run(Call{grid, grid, width, height, stride, source, &costs, window, rule, nullptr, 0}, scratch, threads);
}

void distanceCostRows(const uint8_t* grid, int width, int height, std::ptrdiff_t stride, SourceRange source,
                      const DistanceCosts& costs, const DistanceWindow& window, DistanceTransformScratch& scratch,
                      const CostRowSink& sink)
{
  run(Call{grid, nullptr, width, height, stride, source, &costs, window, CostMergeRule{255, 255}, &sink, 0}, scratch,
      1);
}
}  // namespace costmap_layers
