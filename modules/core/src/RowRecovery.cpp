// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/RowRecovery.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace dynobj::core {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;
/// [m] Horizontal distance beyond which a point's elevation is its beam's (a laser's vertical
/// offset from the sensor origin tilts near points; at 15 m a 0.1 m offset is 0.4 degrees).
constexpr double kFarRange = 15.0;
/// Points a row needs beyond kFarRange before its table entry uses only far points.
constexpr std::size_t kMinFarPoints = 32;

bool usable(const PointCloud& c, std::size_t i) {
  const float x = c.x[i], y = c.y[i], z = c.z[i];
  return std::isfinite(x) && std::isfinite(y) && std::isfinite(z) &&
         !(x == 0.0f && y == 0.0f && z == 0.0f);
}

double median(std::vector<double>& v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

std::vector<double> measuredElevations(const PointCloud& c, const std::vector<std::uint16_t>& group,
                                       int groups) {
  std::vector<std::vector<double>> near(static_cast<std::size_t>(groups)), far(near.size());
  for (std::size_t i = 0; i < c.size(); i++) {
    if (!usable(c, i) || group[i] >= groups) continue;
    const double h = std::hypot(c.x[i], c.y[i]);
    (h >= kFarRange ? far : near)[group[i]].push_back(std::atan2(c.z[i], h));
  }
  std::vector<double> out(near.size(), std::nan(""));
  for (std::size_t g = 0; g < out.size(); g++) {
    if (far[g].size() >= kMinFarPoints) {
      out[g] = median(far[g]);
    } else {
      far[g].insert(far[g].end(), near[g].begin(), near[g].end());
      if (!far[g].empty()) out[g] = median(far[g]);
    }
  }
  return out;
}

namespace {

/// Groups ordered top-down by elevation: returns group -> row, and fills `table` (row order,
/// strictly decreasing). Empty groups sit just below the group with the next lower id.
std::vector<int> rowsByElevation(std::vector<double> elev, std::vector<double>& table) {
  for (std::size_t g = 0; g < elev.size(); g++)
    if (std::isnan(elev[g])) elev[g] = g > 0 ? elev[g - 1] - 1e-5 : M_PI / 4;
  std::vector<int> order(elev.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return elev[static_cast<std::size_t>(a)] > elev[static_cast<std::size_t>(b)];
  });
  std::vector<int> to_row(elev.size());
  table.resize(elev.size());
  for (std::size_t r = 0; r < order.size(); r++) {
    to_row[static_cast<std::size_t>(order[r])] = static_cast<int>(r);
    double e = elev[static_cast<std::size_t>(order[r])];
    if (r > 0 && e >= table[r - 1]) e = table[r - 1] - 1e-6;  // keep the table strictly ordered
    table[r] = e;
  }
  return to_row;
}

/// Rule 2: the laser of each point from the turned azimuth, or 0 lasers when the order is not
/// laser by laser (fewer than 4 revolutions, or per-laser elevations that do not descend or
/// ascend monotonically in at least 90 % of steps). A laser ends where the azimuth has turned a
/// full revolution since the sweep's first point; the exact split within +-kSeam of that turn
/// (the first point need not lie on the scan's seam) is where the elevation changes from the
/// one laser's to the next's.
int firingOrderLasers(const PointCloud& c, std::vector<std::uint16_t>& laser) {
  constexpr double kSeam = 5.0 * M_PI / 180.0;
  const std::size_t n = c.size();
  std::vector<double> turned(n, 0.0), elev(n, 0.0);
  double total = 0, prev = 0;
  bool started = false;
  for (std::size_t i = 0; i < n; i++) {
    if (usable(c, i)) {
      const double az = std::atan2(c.y[i], c.x[i]);
      if (started) {
        double d = az - prev;
        if (d > M_PI) d -= kTwoPi;
        if (d < -M_PI) d += kTwoPi;
        total += d;
      }
      prev = az;
      started = true;
      elev[i] = std::atan2(c.z[i], std::hypot(c.x[i], c.y[i]));
    }
    turned[i] = total;
  }
  const double sign = total >= 0 ? 1.0 : -1.0;
  const double revolutions = sign * total / kTwoPi;
  if (revolutions < 3.0 || revolutions > 4096.0) return 0;
  laser.resize(n);
  int lasers = 0;
  for (std::size_t i = 0; i < n; i++) {
    turned[i] *= sign;
    const int k = std::max(0, static_cast<int>(std::floor(turned[i] / kTwoPi)));
    laser[i] = static_cast<std::uint16_t>(k);
    lasers = std::max(lasers, k + 1);
  }
  // Each laser's elevation away from the seams, then the split of every seam window.
  std::vector<std::vector<double>> bulk(static_cast<std::size_t>(lasers));
  for (std::size_t i = 0; i < n; i++) {
    const double f = turned[i] - kTwoPi * laser[i];
    if (usable(c, i) && f > kSeam && f < kTwoPi - kSeam) bulk[laser[i]].push_back(elev[i]);
  }
  std::vector<double> med(bulk.size(), 0.0);
  for (std::size_t k = 0; k < bulk.size(); k++) med[k] = bulk[k].empty() ? 0.0 : median(bulk[k]);
  std::size_t i = 0;
  for (int b = 1; b < lasers; b++) {
    const double seam = kTwoPi * b;
    while (i < n && turned[i] < seam - kSeam) i++;
    std::size_t end = i;
    while (end < n && turned[end] <= seam + kSeam) end++;
    // Split s: points [i, s) stay on laser b-1, [s, end) go to laser b; fewest misfits wins.
    const double lo = med[static_cast<std::size_t>(b - 1)], hi = med[static_cast<std::size_t>(b)];
    int misfits = 0;
    for (std::size_t j = i; j < end; j++)
      if (usable(c, j) && std::abs(elev[j] - lo) < std::abs(elev[j] - hi)) misfits++;
    int best = misfits;
    std::size_t split = i;
    for (std::size_t j = i; j < end; j++) {
      if (usable(c, j)) misfits += std::abs(elev[j] - lo) < std::abs(elev[j] - hi) ? -1 : 1;
      if (misfits < best) {
        best = misfits;
        split = j + 1;
      }
    }
    for (std::size_t j = i; j < end; j++)
      laser[j] = static_cast<std::uint16_t>(j < split ? b - 1 : b);
    i = end;
  }
  const std::vector<double> e = measuredElevations(c, laser, lasers);
  int down = 0, up = 0;
  for (std::size_t k = 1; k < e.size(); k++) {
    if (e[k] < e[k - 1]) down++;
    if (e[k] > e[k - 1]) up++;
  }
  const int steps = lasers - 1;
  if (std::max(down, up) < 0.9 * steps) return 0;
  return lasers;
}

/// Rule 3: raw firing order. The points come in the order the lasers fired: one cycle of every
/// laser per firing (less the no-returns), cycle after cycle, about one revolution per sweep (a
/// sweep may hold more: the repeated sector is kept and reported). The lasers are found from the
/// data alone:
///  a. beams: the peaks of the elevation histogram of the far points (>= kFarRange, where a laser's
///     vertical offset tilts its points least), 0.01-degree bins smoothed over +-0.03 degrees;
///  b. the firing cycle: each beam's most frequent successor among consecutive far points; the
///     successors must form one cycle through the beams (a few rare, spurious peaks are dropped);
///  c. each point's laser: the cycle position after the previous point's (up to kMaxSkip
///     no-returns in between) whose beam elevation, tilted by the laser's vertical offset at the
///     point's distance, is nearest; then each laser's elevation and vertical offset are fitted
///     to its points (least squares of z = h tan(elevation) + offset) and (c) runs again.
/// 0 lasers when any step fails (under 4 beams, beams off the cycle, under half of the points
/// coming right after the previous point's laser). `repeated` receives the points in a sector
/// the sweep scanned twice.
int firingCycleLasers(const PointCloud& c, std::vector<std::uint16_t>& laser,
                      std::size_t& repeated) {
  constexpr double kBin = 0.01 * M_PI / 180.0, kSigma = 3.0;  // bins
  constexpr double kMinSeparation = 0.07 * M_PI / 180.0;
  constexpr int kMaxSkip = 12;
  constexpr double kNear = 2.0;  // [m] nearer points (the vehicle, a laser's offset) are not used
  const std::size_t n = c.size();
  std::vector<std::size_t> pts;  // usable points, in stored order
  std::vector<double> elev, hor;
  pts.reserve(n);
  double total = 0, prev = 0;
  for (std::size_t i = 0; i < n; i++) {
    if (!usable(c, i)) continue;
    const double az = std::atan2(c.y[i], c.x[i]);
    if (!pts.empty()) {
      double d = az - prev;
      if (d > M_PI) d -= kTwoPi;
      if (d < -M_PI) d += kTwoPi;
      total += d;
    }
    prev = az;
    pts.push_back(i);
    hor.push_back(std::hypot(c.x[i], c.y[i]));
    elev.push_back(std::atan2(c.z[i], hor.back()));
  }
  const double revolutions = std::abs(total) / kTwoPi;
  if (pts.size() < 256 || revolutions < 0.25 || revolutions > 2.5) return 0;

  // a. Beams from the far points' elevation histogram.
  constexpr int kBins = static_cast<int>(M_PI / kBin) + 1;
  std::vector<double> hist(static_cast<std::size_t>(kBins), 0.0);
  auto binOf = [&](double e) { return static_cast<int>((e + M_PI / 2) / kBin); };
  for (std::size_t k = 0; k < pts.size(); k++)
    if (hor[k] >= kNear) {
      const int b = binOf(elev[k]);
      if (b >= 0 && b < kBins) hist[static_cast<std::size_t>(b)] += 1.0;
    }
  const int half = static_cast<int>(3 * kSigma);
  std::vector<double> kernel(static_cast<std::size_t>(2 * half + 1));
  for (int k = -half; k <= half; k++)
    kernel[static_cast<std::size_t>(k + half)] = std::exp(-0.5 * k * k / (kSigma * kSigma));
  std::vector<double> smooth(hist.size(), 0.0);
  for (int b = half; b + half < kBins; b++)
    if (hist[static_cast<std::size_t>(b)] > 0)
      for (int k = -half; k <= half; k++)
        smooth[static_cast<std::size_t>(b + k)] +=
            hist[static_cast<std::size_t>(b)] * kernel[static_cast<std::size_t>(k + half)];
  std::vector<std::pair<double, int>> peaks;  // (height, bin)
  for (int b = 1; b + 1 < kBins; b++) {
    const double v = smooth[static_cast<std::size_t>(b)];
    if (v >= 3 && v > smooth[static_cast<std::size_t>(b - 1)] &&
        v >= smooth[static_cast<std::size_t>(b + 1)])
      peaks.emplace_back(v, b);
  }
  std::sort(peaks.begin(), peaks.end(), std::greater<>());
  std::vector<double> beam;  // elevation [rad] per beam
  for (const auto& [v, b] : peaks) {
    const double e = (b + 0.5) * kBin - M_PI / 2;
    if (std::all_of(beam.begin(), beam.end(),
                    [&](double t) { return std::abs(t - e) >= kMinSeparation; }))
      beam.push_back(e);
  }
  if (beam.size() < 4 || beam.size() > 1024) return 0;
  std::sort(beam.begin(), beam.end());
  auto nearestBeam = [&](double e) {
    const auto it = std::lower_bound(beam.begin(), beam.end(), e);
    std::size_t j = static_cast<std::size_t>(it - beam.begin());
    if (j == beam.size() || (j > 0 && e - beam[j - 1] < beam[j] - e)) j--;
    return j;
  };

  // b. The firing cycle: each beam's most frequent successor among consecutive far points.
  const std::size_t nb = beam.size();
  std::vector<std::vector<std::size_t>> next(nb, std::vector<std::size_t>(nb, 0));
  std::vector<std::size_t> seen(nb, 0);
  for (std::size_t k = 0; k + 1 < pts.size(); k++)
    if (hor[k] >= kNear && hor[k + 1] >= kNear) {
      const std::size_t a = nearestBeam(elev[k]), b = nearestBeam(elev[k + 1]);
      next[a][b]++;
      seen[a]++;
    }
  std::vector<int> succ(nb, -1);
  for (std::size_t a = 0; a < nb; a++)
    if (seen[a] > 0)
      succ[a] =
          static_cast<int>(std::max_element(next[a].begin(), next[a].end()) - next[a].begin());
  const auto start =
      static_cast<std::size_t>(std::max_element(seen.begin(), seen.end()) - seen.begin());
  // Follow the successors from the most seen beam until one repeats: the loop is the cycle of
  // the beams that (nearly) always return. A beam that often has no return (e.g. the top one,
  // under an open sky) is skipped by its predecessor's most frequent successor: it goes in after
  // the cycle's beam it follows most often.
  std::vector<int> cycle;  // beams in firing order
  std::vector<int> visit(nb, -1);
  for (int a = static_cast<int>(start); a >= 0; a = succ[static_cast<std::size_t>(a)]) {
    if (visit[static_cast<std::size_t>(a)] >= 0) {
      cycle.erase(cycle.begin(), cycle.begin() + visit[static_cast<std::size_t>(a)]);
      break;
    }
    visit[static_cast<std::size_t>(a)] = static_cast<int>(cycle.size());
    cycle.push_back(a);
  }
  if (cycle.size() < 2 ||
      visit[static_cast<std::size_t>(succ[static_cast<std::size_t>(cycle.back())])] < 0)
    return 0;
  std::vector<char> in_cycle(nb, 0);
  for (int a : cycle) in_cycle[static_cast<std::size_t>(a)] = 1;
  std::vector<std::size_t> rest;
  for (std::size_t x = 0; x < nb; x++)
    if (!in_cycle[x]) rest.push_back(x);
  std::sort(rest.begin(), rest.end(),
            [&](std::size_t a, std::size_t b) { return seen[a] > seen[b]; });
  for (std::size_t x : rest) {
    std::size_t best = 0, after = 0;
    for (std::size_t k = 0; k < cycle.size(); k++) {
      const std::size_t v = next[static_cast<std::size_t>(cycle[k])][x];
      if (v > best) {
        best = v;
        after = k;
      }
    }
    if (best == 0) continue;
    cycle.insert(cycle.begin() + static_cast<std::ptrdiff_t>(after + 1), static_cast<int>(x));
    in_cycle[x] = 1;
  }
  if (cycle.size() < 4) return 0;
  std::size_t far_total = 0, far_outside = 0;
  for (std::size_t a = 0; a < nb; a++) {
    far_total += seen[a];
    if (!in_cycle[a]) far_outside += seen[a];
  }
  if (far_outside > far_total / 50) return 0;  // beams off the cycle: not one firing pattern

  // c. Each point's cycle position, twice: with the histogram's beams, then with each laser's
  // fitted elevation and vertical offset.
  const int lasers = static_cast<int>(cycle.size());
  std::vector<double> tan_el(cycle.size()), offset(cycle.size(), 0.0);
  for (std::size_t k = 0; k < cycle.size(); k++)
    tan_el[k] = std::tan(beam[static_cast<std::size_t>(cycle[k])]);
  std::vector<int> pos(pts.size(), 0);
  std::size_t following = 0, far_pairs = 0;
  for (int pass = 0; pass < 2; pass++) {
    int p = -1;
    following = far_pairs = 0;
    for (std::size_t k = 0; k < pts.size(); k++) {
      const double z = c.z[pts[k]], h = hor[k];
      auto miss = [&](int q) {
        const auto qi = static_cast<std::size_t>(q);
        return std::abs(z - (h * tan_el[qi] + offset[qi])) / std::max(h, 1.0);
      };
      int best = -1;
      double best_miss = 0;
      if (p >= 0)
        for (int s = 1; s <= kMaxSkip + 1 && s <= lasers; s++) {
          const int q = (p + s) % lasers;
          const double m = miss(q);
          if (best < 0 || m < best_miss) {
            best = q;
            best_miss = m;
          }
        }
      // Re-synchronize when no position after the previous one fits (a long gap of no-returns).
      const double tolerance = 0.5 * kMinSeparation + (pass == 0 ? 0.3 : 0.05) / std::max(h, 1.0);
      if (best < 0 || best_miss > tolerance)
        for (int q = 0; q < lasers; q++) {
          const double m = miss(q);
          if (best < 0 || m < best_miss) {
            best = q;
            best_miss = m;
          }
        }
      if (k > 0 && h >= kNear && hor[k - 1] >= kNear) {
        far_pairs++;
        if (p >= 0 && (best - p + lasers) % lasers == 1) following++;
      }
      pos[k] = p = best;
    }
    if (pass == 1) break;
    // Fit each laser's elevation and vertical offset (z = h t + v) to its points; the offset only
    // where the distances spread enough to tell it from the elevation.
    for (int q = 0; q < lasers; q++) {
      double s1 = 0, sh = 0, sz = 0, shh = 0, shz = 0, far_t = 0, far_n = 0;
      for (std::size_t k = 0; k < pts.size(); k++) {
        if (pos[k] != q) continue;
        const double h = hor[k], z = c.z[pts[k]];
        s1 += 1;
        sh += h;
        sz += z;
        shh += h * h;
        shz += h * z;
        if (h >= kFarRange) {
          far_t += z / h;
          far_n += 1;
        }
      }
      const auto qi = static_cast<std::size_t>(q);
      const double var = s1 > 0 ? shh / s1 - (sh / s1) * (sh / s1) : 0.0;
      if (s1 >= 16 && var >= 4.0) {  // distances spread over >= 2 m (standard deviation)
        tan_el[qi] = (s1 * shz - sh * sz) / (s1 * shh - sh * sh);
        offset[qi] = (sz - tan_el[qi] * sh) / s1;
      } else if (far_n >= 8) {
        tan_el[qi] = far_t / far_n;
      }
    }
  }
  // In a cycle most points follow the previous one's laser directly; in any other order about
  // one in `lasers` does.
  if (static_cast<double>(following) < std::max(0.5, 3.0 / lasers) * static_cast<double>(far_pairs))
    return 0;
  // Lasers in elevation order are renumbered by rowsByElevation later; here: cycle position.
  laser.assign(n, 0);
  for (std::size_t k = 0; k < pts.size(); k++) laser[pts[k]] = static_cast<std::uint16_t>(pos[k]);
  // Unusable points sit with the laser before them (they are not projected).
  for (std::size_t i = 1; i < n; i++)
    if (!usable(c, i)) laser[i] = laser[i - 1];
  // The repeated sector: each laser's points after it has turned a full revolution.
  repeated = 0;
  std::vector<double> first_az(cycle.size(), std::nan("")), turned(cycle.size(), 0.0),
      last_az(cycle.size(), 0.0);
  for (std::size_t k = 0; k < pts.size(); k++) {
    const auto q = static_cast<std::size_t>(pos[k]);
    const double az = std::atan2(c.y[pts[k]], c.x[pts[k]]);
    if (std::isnan(first_az[q])) {
      first_az[q] = last_az[q] = az;
      continue;
    }
    double d = az - last_az[q];
    if (d > M_PI) d -= kTwoPi;
    if (d < -M_PI) d += kTwoPi;
    turned[q] += d;
    last_az[q] = az;
    if (std::abs(turned[q]) >= kTwoPi) repeated++;
  }
  return lasers;
}

/// Rule 3: `rows` beam elevations from the peaks of the far points' elevation histogram, or an
/// empty table when it does not show `rows` separate peaks.
std::vector<double> histogramTable(const PointCloud& c, int rows) {
  constexpr double kBin = 0.02 * M_PI / 180.0, kMinSeparation = 0.15 * M_PI / 180.0;
  constexpr int kBins = static_cast<int>(M_PI / kBin) + 1;  // -90..+90 degrees
  std::vector<double> hist(static_cast<std::size_t>(kBins), 0.0);
  for (std::size_t i = 0; i < c.size(); i++) {
    if (!usable(c, i)) continue;
    const double h = std::hypot(c.x[i], c.y[i]);
    if (h < kFarRange) continue;
    const int b = static_cast<int>((std::atan2(c.z[i], h) + M_PI / 2) / kBin);
    if (b >= 0 && b < kBins) hist[static_cast<std::size_t>(b)] += 1.0;
  }
  std::vector<double> smooth(hist.size(), 0.0);
  for (int b = 2; b + 2 < kBins; b++)
    for (int k = -2; k <= 2; k++)
      smooth[static_cast<std::size_t>(b)] += hist[static_cast<std::size_t>(b + k)];
  std::vector<std::pair<double, int>> peaks;  // (height, bin)
  for (int b = 1; b + 1 < kBins; b++) {
    const double v = smooth[static_cast<std::size_t>(b)];
    if (v >= 3 && v > smooth[static_cast<std::size_t>(b - 1)] &&
        v >= smooth[static_cast<std::size_t>(b + 1)])
      peaks.emplace_back(v, b);
  }
  std::sort(peaks.begin(), peaks.end(), std::greater<>());
  std::vector<double> table;
  for (const auto& [v, b] : peaks) {
    const double e = (b + 0.5) * kBin - M_PI / 2;
    const bool apart = std::all_of(table.begin(), table.end(),
                                   [&](double t) { return std::abs(t - e) >= kMinSeparation; });
    if (apart) table.push_back(e);
    if (static_cast<int>(table.size()) == rows) break;
  }
  if (static_cast<int>(table.size()) != rows) return {};
  std::sort(table.begin(), table.end(), std::greater<>());
  return table;
}

SensorModel withTable(const std::optional<SensorModel>& hint, std::vector<double> table,
                      const char* model) {
  SensorModel m = hint ? *hint : SensorModel();
  if (!hint) {
    m.model = model;
    m.min_range = 0.3;
    m.max_range = 200.0;
  }
  m.rows = static_cast<int>(table.size());
  m.beam_elevations = std::move(table);
  return m;
}

/// Columns by Eq. (1) for every point of an organized-by-row cloud.
void assignColumns(PointCloud& c, const SensorModel& m) {
  const SphericalProjection eq1(m);
  c.col.resize(c.size());
  for (std::size_t i = 0; i < c.size(); i++)
    c.col[i] = static_cast<std::uint16_t>(usable(c, i) ? eq1.columnOf(c.x[i], c.y[i]) : 0);
}

}  // namespace

const char* toString(RowSource s) {
  switch (s) {
    case RowSource::RingField:
      return "ring field";
    case RowSource::FiringOrder:
      return "firing order";
    case RowSource::FiringCycle:
      return "firing cycle";
    case RowSource::EstimatedTable:
      return "estimated beam table";
    case RowSource::NominalTable:
      return "nominal beam table";
  }
  return "?";
}

int estimateColumns(const PointCloud& cloud, const std::vector<std::uint16_t>& laser, int lasers) {
  const int fallback = lasers <= 16 ? 1800 : 2048;
  std::vector<std::size_t> count(static_cast<std::size_t>(lasers) + 1, 0);
  for (auto l : laser) count[std::min<std::size_t>(l, count.size() - 1)]++;
  const auto best =
      static_cast<std::uint16_t>(std::max_element(count.begin(), count.end() - 1) - count.begin());
  if (count[best] < 64) return fallback;
  std::vector<double> az;
  az.reserve(count[best]);
  for (std::size_t i = 0; i < cloud.size(); i++)
    if (laser[i] == best && usable(cloud, i)) az.push_back(std::atan2(cloud.y[i], cloud.x[i]));
  std::sort(az.begin(), az.end());
  std::vector<double> steps;
  for (std::size_t i = 1; i < az.size(); i++)
    if (az[i] - az[i - 1] > 1e-5) steps.push_back(az[i] - az[i - 1]);
  if (steps.size() < 32) return fallback;
  const double cols = std::round(kTwoPi / median(steps));
  return static_cast<int>(std::clamp(cols, 64.0, 16384.0));
}

RecoveredRows recoverRows(PointCloud& cloud, const std::optional<SensorModel>& hint) {
  cloud.validate();
  cloud.row.clear();
  cloud.col.clear();
  RecoveredRows out;
  std::vector<std::uint16_t> laser;
  int lasers = 0;
  if (cloud.hasRing()) {
    laser = cloud.ring;
    lasers = laser.empty() ? 0 : *std::max_element(laser.begin(), laser.end()) + 1;
    out.source = RowSource::RingField;
  } else {
    lasers = firingOrderLasers(cloud, laser);
    out.source = RowSource::FiringOrder;
    if (lasers == 0) {
      lasers = firingCycleLasers(cloud, laser, out.repeated);
      out.source = RowSource::FiringCycle;
    }
  }
  out.lasers = std::max(lasers, 0);
  if (lasers > 0 && hint && lasers < hint->rows) {
    // Fewer lasers than the sensor has (a partial sweep, blocked beams): each takes the row of
    // the nearest beam of the hint's table, if no two lasers claim the same row.
    const std::vector<double> e = measuredElevations(cloud, laser, lasers);
    const std::vector<double> table = hint->rowElevations();
    const SphericalProjection eq1(*hint);
    std::vector<int> to_row(static_cast<std::size_t>(lasers), -1);
    std::vector<char> taken(table.size(), 0);
    bool ok = true;
    for (std::size_t k = 0; k < e.size() && ok; k++) {
      if (std::isnan(e[k])) continue;
      const int r = eq1.rowOfElevation(e[k]);
      ok = r >= 0 && !taken[static_cast<std::size_t>(r)];
      if (ok) taken[static_cast<std::size_t>(r)] = 1;
      to_row[k] = r;
    }
    if (ok) {
      out.sensor = *hint;
      cloud.row.resize(cloud.size());
      for (std::size_t i = 0; i < cloud.size(); i++)
        cloud.row[i] = static_cast<std::uint16_t>(std::max(0, to_row[laser[i]]));
      assignColumns(cloud, out.sensor);
      return out;
    }
  }
  if (lasers > 0 && (!hint || hint->rows == lasers)) {
    std::vector<double> table;
    const std::vector<int> to_row =
        rowsByElevation(measuredElevations(cloud, laser, lasers), table);
    out.sensor = withTable(hint, std::move(table), "recovered rows");
    if (!hint) out.sensor.cols = estimateColumns(cloud, laser, lasers);
    cloud.row.resize(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); i++)
      cloud.row[i] = static_cast<std::uint16_t>(to_row[laser[i]]);
    assignColumns(cloud, out.sensor);
    return out;
  }
  if (!hint)
    throw std::invalid_argument(
        "the cloud has no ring field and is not stored laser by laser, so its rows cannot be "
        "recovered without a sensor model (rows, cols)");
  std::vector<double> table = histogramTable(cloud, hint->rows);
  if (!table.empty()) {
    out.source = RowSource::EstimatedTable;
    out.sensor = withTable(hint, std::move(table), "estimated table");
    return out;
  }
  out.source = RowSource::NominalTable;
  out.sensor = *hint;
  return out;
}

ProjectionStats projectUnordered(PointCloud& cloud, const std::optional<SensorModel>& hint,
                                 LidarFrame& frame, RowSource* source, int* lasers) {
  const RecoveredRows rows = recoverRows(cloud, hint);
  if (source) *source = rows.source;
  if (lasers) *lasers = rows.lasers;
  const SphericalProjection projection(rows.sensor);
  return cloud.isOrganized() ? projection.organize(cloud, frame) : projection.project(cloud, frame);
}

namespace {

/// Fills the NaN entries of a per-row table by linear interpolation between the nearest measured
/// rows (extrapolated at the ends); false when fewer than two rows were measured or the result
/// does not descend strictly from row to row.
bool completeTable(std::vector<double>& t) {
  std::vector<std::size_t> known;
  for (std::size_t r = 0; r < t.size(); r++)
    if (!std::isnan(t[r])) known.push_back(r);
  if (known.size() < 2) return false;
  for (std::size_t r = 0; r < t.size(); r++) {
    if (!std::isnan(t[r])) continue;
    auto hi = std::lower_bound(known.begin(), known.end(), r);
    if (hi == known.end()) hi--;
    if (hi == known.begin()) hi++;
    const std::size_t a = *(hi - 1), b = *hi;
    t[r] = t[a] + (t[b] - t[a]) * (static_cast<double>(r) - static_cast<double>(a)) /
                      static_cast<double>(b - a);
  }
  for (std::size_t r = 1; r < t.size(); r++)
    if (!(t[r] < t[r - 1])) return false;
  return true;
}

}  // namespace

SensorModel organizedModel(const PointCloud& cloud, int h, int w, double max_range,
                           const std::string& name) {
  SensorModel m;
  m.model = name;
  m.rows = h;
  m.cols = w;
  m.max_range = max_range;
  m.min_range = std::min(0.1, m.max_range / 2);
  std::vector<double> table = measuredElevations(cloud, cloud.row, h);
  if (h > 1 && completeTable(table)) {
    m.beam_elevations = std::move(table);
    return m;
  }
  double s1 = 0, sr = 0, se = 0, srr = 0, sre = 0;
  for (std::size_t i = 0; i < cloud.size(); i++) {
    const double x = cloud.x[i], y = cloud.y[i], z = cloud.z[i];
    const double r = std::sqrt(x * x + y * y + z * z);
    if (!(r > 0) || !std::isfinite(r)) continue;
    const double row = cloud.row[i], el = std::asin(z / r);
    s1 += 1;
    sr += row;
    se += el;
    srr += row * row;
    sre += row * el;
  }
  const double det = s1 * srr - sr * sr;
  const double b = det > 0 ? (s1 * sre - sr * se) / det : 0.0;
  const double a = det > 0 ? (se - b * sr) / s1 : 0.0;
  if (h > 1 && b < 0 && a < M_PI / 2 && a + b * (h - 1) > -M_PI / 2) {
    m.elevation_top = a;
    m.elevation_bottom = a + b * (h - 1);
  } else {  // no usable fit: 1 degree per row around the horizon
    m.elevation_top = 0.5 * (h - 1) * M_PI / 180.0;
    m.elevation_bottom = -m.elevation_top - (h > 1 ? 0.0 : 1e-3);
  }
  return m;
}

}  // namespace dynobj::core
