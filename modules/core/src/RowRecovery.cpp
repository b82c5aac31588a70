// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/RowRecovery.h"

#include <algorithm>
#include <cmath>
#include <map>
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

/// Each point's angles, computed once for every rule: the azimuth (atan2 of the float
/// coordinates; empty when not asked for), the horizontal distance and the elevation over it
/// [rad, m]; `ok` = usable.
struct Angles {
  std::vector<char> ok;
  std::vector<double> az, h, el;
};

Angles anglesOf(const PointCloud& c, bool azimuth = true) {
  Angles a;
  const std::size_t n = c.size();
  a.ok.assign(n, 0);
  if (azimuth) a.az.assign(n, 0.0);
  a.h.assign(n, 0.0);
  a.el.assign(n, 0.0);
  for (std::size_t i = 0; i < n; i++) {
    if (!usable(c, i)) continue;
    a.ok[i] = 1;
    if (azimuth) a.az[i] = std::atan2(c.y[i], c.x[i]);
    a.h[i] = std::hypot(c.x[i], c.y[i]);
    a.el[i] = std::atan2(static_cast<double>(c.z[i]), a.h[i]);
  }
  return a;
}

std::vector<double> measuredElevations(const Angles& a, const std::vector<std::uint16_t>& group,
                                       int groups) {
  std::vector<std::vector<double>> near(static_cast<std::size_t>(groups)), far(near.size());
  for (std::size_t i = 0; i < a.ok.size(); i++) {
    if (!a.ok[i] || group[i] >= groups) continue;
    (a.h[i] >= kFarRange ? far : near)[group[i]].push_back(a.el[i]);
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

}  // namespace

std::vector<double> measuredElevations(const PointCloud& c, const std::vector<std::uint16_t>& group,
                                       int groups) {
  return measuredElevations(anglesOf(c, false), group, groups);
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
int firingOrderLasers(const PointCloud& c, const Angles& a, std::vector<std::uint16_t>& laser) {
  constexpr double kSeam = 5.0 * M_PI / 180.0;
  const std::size_t n = c.size();
  std::vector<double> turned(n, 0.0), elev(n, 0.0);
  double total = 0, prev = 0;
  bool started = false;
  for (std::size_t i = 0; i < n; i++) {
    if (a.ok[i]) {
      const double az = a.az[i];
      if (started) {
        double d = az - prev;
        if (d > M_PI) d -= kTwoPi;
        if (d < -M_PI) d += kTwoPi;
        total += d;
      }
      prev = az;
      started = true;
    }
    turned[i] = total;
  }
  const double sign = total >= 0 ? 1.0 : -1.0;
  const double revolutions = sign * total / kTwoPi;
  if (revolutions < 3.0 || revolutions > 4096.0) return 0;
  for (std::size_t i = 0; i < n; i++)  // (in float, as this rule was tuned)
    if (a.ok[i]) elev[i] = std::atan2(c.z[i], std::hypot(c.x[i], c.y[i]));
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
  const std::vector<double> e = measuredElevations(a, laser, lasers);
  int down = 0, up = 0;
  for (std::size_t k = 1; k < e.size(); k++) {
    if (e[k] < e[k - 1]) down++;
    if (e[k] > e[k - 1]) up++;
  }
  const int steps = lasers - 1;
  if (std::max(down, up) < 0.9 * steps) return 0;
  return lasers;
}

/// Marks the points of each laser after it has turned a full revolution since its first point
/// (the sector a sweep of more than 360 degrees scans a second time); returns how many.
std::size_t markRepeated(const Angles& a, const std::vector<std::uint16_t>& laser, int lasers,
                         std::vector<std::uint8_t>& repeated) {
  std::size_t count = 0;
  const auto nl = static_cast<std::size_t>(lasers);
  std::vector<double> turned(nl, 0.0), last_az(nl, std::nan(""));
  repeated.assign(a.ok.size(), 0);
  for (std::size_t i = 0; i < a.ok.size(); i++) {
    if (!a.ok[i] || laser[i] >= nl) continue;
    const auto q = laser[i];
    const double az = a.az[i];
    if (!std::isnan(last_az[q])) {
      double d = az - last_az[q];
      if (d > M_PI) d -= kTwoPi;
      if (d < -M_PI) d += kTwoPi;
      turned[q] += d;
    }
    last_az[q] = az;
    if (std::abs(turned[q]) >= kTwoPi) {
      repeated[i] = 1;
      count++;
    }
  }
  if (count == 0) repeated.clear();
  return count;
}

/// The local maxima (>= 3) of a smoothed elevation histogram (`bin` [rad] a bin, from -90
/// degrees), highest first, each kept when at least `min_separation` [rad] from every one kept
/// before; at most `max_peaks`. Elevations [rad] in the order kept.
std::vector<double> histogramPeaks(const std::vector<double>& smooth, double bin,
                                   double min_separation, std::size_t max_peaks) {
  std::vector<std::pair<double, int>> peaks;  // (height, bin)
  for (std::size_t b = 1; b + 1 < smooth.size(); b++) {
    const double v = smooth[b];
    if (v >= 3 && v > smooth[b - 1] && v >= smooth[b + 1])
      peaks.emplace_back(v, static_cast<int>(b));
  }
  std::sort(peaks.begin(), peaks.end(), std::greater<>());
  std::vector<double> kept;
  for (const auto& [v, b] : peaks) {
    if (kept.size() == max_peaks) break;
    const double e = (b + 0.5) * bin - M_PI / 2;
    if (std::all_of(kept.begin(), kept.end(),
                    [&](double t) { return std::abs(t - e) >= min_separation; }))
      kept.push_back(e);
  }
  return kept;
}

/// Rule 3, step b: the anchor is the isolated beam (no other within kIsolated) with the most
/// complete cycles among the 8 most populated ones whose returns step one firing in azimuth (the
/// median step, under 2 degrees); the period is the largest gap between its returns one firing
/// apart seen at least 3 times. Each cycle position's elevation and vertical offset: least squares
/// of z = h tan(elevation) + offset over the complete cycles (the elevation alone where the
/// distances spread less than 2 m). The points between consecutive anchor returns n firings
/// apart take positions 1 .. n x period - 1 in increasing order, with the fewest elevation
/// misfits (dynamic programming). Fills `laser` (cycle position) and `elevations`.
int firingPeriodLasers(const PointCloud& c, const Angles& a, const std::vector<double>& beam,
                       std::vector<std::uint16_t>& laser, std::vector<double>& elevations) {
  constexpr double kIsolated = 0.25 * M_PI / 180.0;
  const std::size_t n = c.size();
  // The anchor: the most populated beam with no other beam within kIsolated.
  std::vector<std::size_t> count(beam.size(), 0);
  for (std::size_t i = 0; i < n; i++) {
    if (!a.ok[i]) continue;
    const double e = a.el[i];
    const auto it = std::lower_bound(beam.begin(), beam.end(), e);
    std::size_t j = static_cast<std::size_t>(it - beam.begin());
    if (j == beam.size() || (j > 0 && e - beam[j - 1] < beam[j] - e)) j--;
    if (std::abs(e - beam[j]) < 0.3 * kIsolated) count[j]++;
  }
  std::vector<std::size_t> candidates;  // isolated beams, most populated first
  for (std::size_t j = 0; j < beam.size(); j++) {
    const bool lo = j == 0 || beam[j] - beam[j - 1] >= kIsolated;
    const bool hi = j + 1 == beam.size() || beam[j + 1] - beam[j] >= kIsolated;
    if (lo && hi) candidates.push_back(j);
  }
  std::sort(candidates.begin(), candidates.end(),
            [&](std::size_t x, std::size_t y) { return count[x] > count[y]; });
  if (candidates.size() > 8) candidates.resize(8);
  // Each candidate: its returns, the azimuth step of one firing, the period; the candidate with
  // the most complete cycles is the anchor.
  std::vector<std::size_t> occ;  // stored indices of the anchor's returns
  std::vector<double> steps;     // azimuth from each return to the next
  double step = 0;
  std::size_t period = 0, complete = 0;
  for (std::size_t cand : candidates) {
    const double ae = beam[cand];
    std::vector<std::size_t> o;
    std::vector<double> az;
    for (std::size_t i = 0; i < n; i++)
      if (a.ok[i] && std::abs(a.el[i] - ae) < 0.3 * kIsolated) {
        o.push_back(i);
        az.push_back(a.az[i]);
      }
    if (o.size() < 64) continue;
    std::vector<double> st;
    for (std::size_t k = 1; k < o.size(); k++) {
      double d = az[k] - az[k - 1];
      if (d > M_PI) d -= kTwoPi;
      if (d < -M_PI) d += kTwoPi;
      st.push_back(std::abs(d));
    }
    std::vector<double> sorted = st;
    const double sp = median(sorted);
    if (!(sp > 0) || sp > 2.0 * M_PI / 180.0) continue;  // not one laser: returns all around
    std::map<std::size_t, int> gaps;  // gap (stored points) of one-firing intervals -> count
    for (std::size_t k = 1; k < o.size(); k++)
      if (std::abs(st[k - 1] - sp) < 0.4 * sp) gaps[o[k] - o[k - 1]]++;
    std::size_t per = 0;
    for (auto it = gaps.rbegin(); it != gaps.rend(); ++it)
      if (it->second >= 3) {
        per = it->first;
        break;
      }
    if (per < 4 || per > 1024) continue;
    const auto full = static_cast<std::size_t>(gaps[per]);
    if (full > complete) {
      complete = full;
      period = per;
      occ = std::move(o);
      steps = std::move(st);
      step = sp;
    }
  }
  if (period == 0 || complete < 8) return 0;
  const int P = static_cast<int>(period);
  // Each position's elevation and vertical offset from the complete cycles.
  std::vector<double> s1(period, 0), sh(period, 0), sz(period, 0), shh(period, 0), shz(period, 0);
  for (std::size_t k = 1; k < occ.size(); k++) {
    if (occ[k] - occ[k - 1] != period || std::abs(steps[k - 1] - step) >= 0.4 * step) continue;
    for (std::size_t q = 0; q < period; q++) {
      const std::size_t i = occ[k - 1] + q;
      if (!a.ok[i]) continue;
      const double h = a.h[i];
      s1[q] += 1;
      sh[q] += h;
      sz[q] += c.z[i];
      shh[q] += h * h;
      shz[q] += h * c.z[i];
    }
  }
  std::vector<double> tan_el(period, 0.0), offset(period, 0.0);
  for (std::size_t q = 0; q < period; q++) {
    if (s1[q] == 0) continue;
    const double var = shh[q] / s1[q] - (sh[q] / s1[q]) * (sh[q] / s1[q]);
    if (s1[q] >= 8 && var >= 4.0) {
      tan_el[q] = (s1[q] * shz[q] - sh[q] * sz[q]) / (s1[q] * shh[q] - sh[q] * sh[q]);
      offset[q] = (sz[q] - tan_el[q] * sh[q]) / s1[q];
    } else {
      tan_el[q] = sz[q] / sh[q];
    }
  }
  elevations.assign(period, std::nan(""));
  for (std::size_t q = 0; q < period; q++)
    if (s1[q] > 0) elevations[q] = std::atan(tan_el[q]);
  auto misfit = [&](std::size_t i, int q) {
    if (!a.ok[i]) return 0.0;
    const double h = std::max(1.0, a.h[i]);
    const auto qi = static_cast<std::size_t>(q % P);
    return std::abs(c.z[i] - (h * tan_el[qi] + offset[qi])) / h;
  };
  // Align the points between consecutive anchor returns (and before the first / after the last)
  // to the positions in order. Point j of m can only take positions j .. slots - m + j: the
  // dynamic programme runs over that band (as wide as the no-returns in the interval, plus one).
  laser.assign(n, 0);
  std::vector<double> prev, cur;
  std::vector<std::uint16_t> back;
  auto align = [&](std::size_t from, std::size_t to, int first_slot, int slots) {
    const std::size_t m = to - from;
    if (m == 0) return;
    if (static_cast<int>(m) > slots) {  // more points than positions: nearest position each
      for (std::size_t i = from; i < to; i++) {
        int best = 0;
        for (int q = 1; q < P; q++)
          if (misfit(i, q) < misfit(i, best)) best = q;
        laser[i] = static_cast<std::uint16_t>(best);
      }
      return;
    }
    const std::size_t W = static_cast<std::size_t>(slots) - m + 1;  // band width
    prev.assign(W, 0.0);
    cur.assign(W, 0.0);
    back.resize(m * W);
    for (std::size_t d = 0; d < W; d++) prev[d] = misfit(from, first_slot + static_cast<int>(d));
    for (std::size_t j = 1; j < m; j++) {
      double best = 1e300;
      std::size_t arg = 0;
      for (std::size_t d = 0; d < W; d++) {  // position j + d, after j - 1 + d' with d' <= d
        if (prev[d] < best) {
          best = prev[d];
          arg = d;
        }
        cur[d] = best + misfit(from + j, first_slot + static_cast<int>(j + d));
        back[j * W + d] = static_cast<std::uint16_t>(arg);
      }
      std::swap(prev, cur);
    }
    std::size_t d =
        static_cast<std::size_t>(std::min_element(prev.begin(), prev.end()) - prev.begin());
    for (std::size_t j = m; j-- > 0;) {
      laser[from + j] = static_cast<std::uint16_t>((first_slot + static_cast<int>(j + d)) % P);
      if (j > 0) d = back[j * W + d];
    }
  };
  align(0, occ.front(), 1, P - 1);  // the tail of a cycle before the first anchor return
  for (std::size_t k = 0; k < occ.size(); k++) {
    laser[occ[k]] = 0;
    const std::size_t end = k + 1 < occ.size() ? occ[k + 1] : n;
    int firings = 1;
    if (k + 1 < occ.size()) firings = std::max(1, static_cast<int>(std::lround(steps[k] / step)));
    align(occ[k] + 1, end, 1, std::min(4, firings) * P - 1);
  }
  return P;
}

/// Rule 3: raw firing order. The points come in the order the lasers fired: every laser once per
/// firing (less the no-returns), firing after firing, about one revolution per sweep (a sweep may
/// hold more: the points of the sector scanned twice are marked in `out.second_pass`). From the
/// data alone:
///  a. beams: the peaks of the elevation histogram of the points beyond kNear (0.01-degree bins
///     smoothed over +-0.03 degrees, peaks >= 0.07 degrees apart);
///  b. the period (firingPeriodLasers): an isolated beam is one laser, firing once per cycle;
///     its returns one firing apart are `lasers` stored points apart when no other laser had a
///     no-return in between; those complete cycles give every cycle position's elevation and
///     vertical offset, and the points of the other cycles are aligned to the positions in order.
/// 0 lasers when it fails (under 4 beams, no isolated beam firing once per firing, fewer than 8
/// complete cycles). `elevations` receives each laser's fitted elevation [rad].
int firingCycleLasers(const PointCloud& c, const Angles& a, std::vector<std::uint16_t>& laser,
                      RecoveredRows& out, std::vector<double>& elevations) {
  constexpr double kBin = 0.01 * M_PI / 180.0, kSigma = 3.0;  // bins
  constexpr double kMinSeparation = 0.07 * M_PI / 180.0;
  constexpr double kNear = 2.0;  // [m] nearer points (the vehicle, a laser's offset) are not used
  std::size_t usable_points = 0;
  double total = 0, prev = 0;
  for (std::size_t i = 0; i < c.size(); i++) {
    if (!a.ok[i]) continue;
    if (usable_points++ > 0) {
      double d = a.az[i] - prev;
      if (d > M_PI) d -= kTwoPi;
      if (d < -M_PI) d += kTwoPi;
      total += d;
    }
    prev = a.az[i];
  }
  const double revolutions = std::abs(total) / kTwoPi;
  if (usable_points < 256 || revolutions < 0.25 || revolutions > 2.5) return 0;

  // a. Beams from the far points' elevation histogram.
  constexpr int kBins = static_cast<int>(M_PI / kBin) + 1;
  std::vector<double> hist(static_cast<std::size_t>(kBins), 0.0);
  auto binOf = [&](double e) { return static_cast<int>((e + M_PI / 2) / kBin); };
  for (std::size_t i = 0; i < c.size(); i++)
    if (a.ok[i] && a.h[i] >= kNear) {
      const int b = binOf(a.el[i]);
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
  std::vector<double> beam = histogramPeaks(smooth, kBin, kMinSeparation, 1025);  // [rad]
  if (beam.size() < 4 || beam.size() > 1024) return 0;
  std::sort(beam.begin(), beam.end());
  const int lasers = firingPeriodLasers(c, a, beam, laser, elevations);
  if (lasers > 0) out.repeated = markRepeated(a, laser, lasers, out.second_pass);
  return lasers;
}

/// Rule 3: `rows` beam elevations from the peaks of the far points' elevation histogram, or an
/// empty table when it does not show `rows` separate peaks.
std::vector<double> histogramTable(const Angles& a, int rows) {
  constexpr double kBin = 0.02 * M_PI / 180.0, kMinSeparation = 0.15 * M_PI / 180.0;
  constexpr int kBins = static_cast<int>(M_PI / kBin) + 1;  // -90..+90 degrees
  std::vector<double> hist(static_cast<std::size_t>(kBins), 0.0);
  for (std::size_t i = 0; i < a.ok.size(); i++) {
    if (!a.ok[i] || a.h[i] < kFarRange) continue;
    const int b = static_cast<int>((a.el[i] + M_PI / 2) / kBin);
    if (b >= 0 && b < kBins) hist[static_cast<std::size_t>(b)] += 1.0;
  }
  std::vector<double> smooth(hist.size(), 0.0);
  for (int b = 2; b + 2 < kBins; b++)
    for (int k = -2; k <= 2; k++)
      smooth[static_cast<std::size_t>(b)] += hist[static_cast<std::size_t>(b + k)];
  std::vector<double> table =
      histogramPeaks(smooth, kBin, kMinSeparation, static_cast<std::size_t>(rows));
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

namespace {

/// estimateColumns() with `azimuth(i)`: point i's azimuth [rad], NaN when it is not usable (only
/// the best-covered laser's points are asked).
template <class Azimuth>
int columnsFromAzimuths(const std::vector<std::uint16_t>& laser, int lasers, Azimuth&& azimuth) {
  const int fallback = lasers <= 16 ? 1800 : 2048;
  std::vector<std::size_t> count(static_cast<std::size_t>(lasers) + 1, 0);
  for (auto l : laser) count[std::min<std::size_t>(l, count.size() - 1)]++;
  const auto best =
      static_cast<std::uint16_t>(std::max_element(count.begin(), count.end() - 1) - count.begin());
  if (count[best] < 64) return fallback;
  std::vector<double> az;
  az.reserve(count[best]);
  for (std::size_t i = 0; i < laser.size(); i++)
    if (laser[i] == best) {
      const double v = azimuth(i);
      if (!std::isnan(v)) az.push_back(v);
    }
  std::sort(az.begin(), az.end());
  std::vector<double> steps;
  for (std::size_t i = 1; i < az.size(); i++)
    if (az[i] - az[i - 1] > 1e-5) steps.push_back(az[i] - az[i - 1]);
  if (steps.size() < 32) return fallback;
  const double cols = std::round(kTwoPi / median(steps));
  return static_cast<int>(std::clamp(cols, 64.0, 16384.0));
}

int estimateColumns(const PointCloud& c, const Angles& a, const std::vector<std::uint16_t>& laser,
                    int lasers) {
  return columnsFromAzimuths(laser, lasers, [&](std::size_t i) {
    if (!a.ok[i]) return std::nan("");
    return a.az.empty() ? static_cast<double>(std::atan2(c.y[i], c.x[i])) : a.az[i];
  });
}

}  // namespace

int estimateColumns(const PointCloud& cloud, const std::vector<std::uint16_t>& laser, int lasers) {
  return columnsFromAzimuths(laser, lasers, [&](std::size_t i) {
    return usable(cloud, i) ? static_cast<double>(std::atan2(cloud.y[i], cloud.x[i]))
                            : std::nan("");
  });
}

RecoveredRows recoverRows(PointCloud& cloud, const std::optional<SensorModel>& hint) {
  cloud.validate();
  cloud.row.clear();
  cloud.col.clear();
  RecoveredRows out;
  const Angles angles = anglesOf(cloud, !cloud.hasRing());  // rules 2-3 need the azimuths
  std::vector<std::uint16_t> laser;
  std::vector<double> fitted;  // rule 3: each laser's fitted elevation (its vertical offset apart)
  int lasers = 0;
  if (cloud.hasRing()) {
    laser = cloud.ring;
    lasers = laser.empty() ? 0 : *std::max_element(laser.begin(), laser.end()) + 1;
    out.source = RowSource::RingField;
  } else {
    lasers = firingOrderLasers(cloud, angles, laser);
    out.source = RowSource::FiringOrder;
    if (lasers == 0) {
      lasers = firingCycleLasers(cloud, angles, laser, out, fitted);
      out.source = RowSource::FiringCycle;
    }
  }
  out.lasers = std::max(lasers, 0);
  if (lasers > 0 && hint && lasers < hint->rows) {
    // Fewer lasers than the sensor has (a partial sweep, blocked beams): each takes the row of
    // the nearest beam of the hint's table, if no two lasers claim the same row.
    const std::vector<double> e = measuredElevations(angles, laser, lasers);
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
        rowsByElevation(fitted.empty() ? measuredElevations(angles, laser, lasers) : fitted, table);
    out.sensor = withTable(hint, std::move(table), "recovered rows");
    if (!hint) out.sensor.cols = estimateColumns(cloud, angles, laser, lasers);
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
  std::vector<double> table = histogramTable(angles, hint->rows);
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
  return cloud.isOrganized()
             ? projection.organize(cloud, frame,
                                   rows.second_pass.empty() ? nullptr : &rows.second_pass)
             : projection.project(cloud, frame);
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
