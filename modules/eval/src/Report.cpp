// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/eval/Report.h"

#include <dynobj/io/AtomicFile.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

namespace dynobj::eval {
namespace {

using Metric = SequenceMetrics::Metric;

std::string num(double v, int decimals = 3) {
  char b[64];
  std::snprintf(b, sizeof(b), "%.*f", decimals, v);
  return b;
}

std::string opt(const std::optional<double>& v, const std::string& none = "n/a") {
  return v ? num(*v) : none;
}

std::string percent(const std::optional<double>& v) {
  return v ? num(100.0 * *v, 3) + " %" : "n/a";
}

std::string objectRecall(const RunResult& r) {
  if (!r.objects) return "n/a";
  const ObjectTally& t = r.objects->total();
  return opt(t.recall()) + " (" + std::to_string(t.detected) + "/" + std::to_string(t.present) +
         ")";
}

std::string timing(const RunResult& r) {
  if (!r.timing) return "—";
  return num(r.timing->percentile("total", 50), 1) + " / " +
         num(r.timing->percentile("total", 99), 1);
}

std::string jsonOpt(const std::optional<double>& v) {
  return v ? num(*v, 6) : "null";
}

std::string escapeHtml(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

std::string escapeJson(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

std::string base64(const std::vector<std::uint8_t>& data) {
  static const char* kTable = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((data.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < data.size(); i += 3) {
    const std::uint32_t b =
        (static_cast<std::uint32_t>(data[i]) << 16) |
        (i + 1 < data.size() ? static_cast<std::uint32_t>(data[i + 1]) << 8 : 0u) |
        (i + 2 < data.size() ? static_cast<std::uint32_t>(data[i + 2]) : 0u);
    out += kTable[(b >> 18) & 63];
    out += kTable[(b >> 12) & 63];
    out += i + 1 < data.size() ? kTable[(b >> 6) & 63] : '=';
    out += i + 2 < data.size() ? kTable[b & 63] : '=';
  }
  return out;
}

std::optional<double> metricOf(const eval::Confusion& c, Metric m) {
  switch (m) {
    case Metric::Precision:
      return c.precision();
    case Metric::Recall:
      return c.recall();
    case Metric::IoU:
      return c.iou();
    case Metric::F1:
      return c.f1();
  }
  return std::nullopt;
}

/// Per-sweep polyline plot as inline SVG. y(v) maps a value to [0, 1] (bottom to top).
struct Series {
  std::string name, colour;
  std::vector<std::optional<double>> values;
};

std::string svgPlot(const std::string& title, const std::vector<Series>& series,
                    const std::function<double(double)>& y,
                    const std::vector<std::pair<double, std::string>>& grid,
                    const std::optional<std::pair<double, std::string>>& line) {
  constexpr int W = 720, H = 220, L = 48, R = 10, T = 24, B = 28;
  std::size_t n = 1;
  for (const auto& s : series) n = std::max(n, s.values.size());
  const auto px = [&](std::size_t i) {
    return L + (W - L - R) * (n > 1 ? static_cast<double>(i) / static_cast<double>(n - 1) : 0.0);
  };
  const auto py = [&](double v) { return T + (H - T - B) * (1.0 - std::clamp(y(v), 0.0, 1.0)); };
  std::ostringstream s;
  s << "<svg xmlns='http://www.w3.org/2000/svg' width='" << W << "' height='" << H
    << "' class='plot'>"
    << "<text x='" << L << "' y='16' font-size='13' font-weight='bold'>" << escapeHtml(title)
    << "</text>";
  for (const auto& [v, label] : grid)
    s << "<line x1='" << L << "' x2='" << W - R << "' y1='" << num(py(v), 1) << "' y2='"
      << num(py(v), 1) << "' stroke='#ddd'/><text x='" << L - 4 << "' y='" << num(py(v) + 4, 1)
      << "' font-size='10' text-anchor='end'>" << label << "</text>";
  s << "<text x='" << (W + L) / 2 << "' y='" << H - 6
    << "' font-size='10' text-anchor='middle'>sweep (0 … " << n - 1 << ")</text>";
  if (line)
    s << "<line x1='" << L << "' x2='" << W - R << "' y1='" << num(py(line->first), 1) << "' y2='"
      << num(py(line->first), 1) << "' stroke='#c00' stroke-dasharray='6,3'/><text x='" << W - R
      << "' y='" << num(py(line->first) - 4, 1) << "' font-size='10' fill='#c00' text-anchor='end'>"
      << escapeHtml(line->second) << "</text>";
  int legend_x = L + 260;
  for (const auto& ser : series) {
    s << "<polyline fill='none' stroke-width='1.3' stroke='" << ser.colour << "' points='";
    for (std::size_t i = 0; i < ser.values.size(); i++)
      if (ser.values[i]) s << num(px(i), 1) << "," << num(py(*ser.values[i]), 1) << " ";
    s << "'/><text x='" << legend_x << "' y='16' font-size='11' fill='" << ser.colour << "'>"
      << escapeHtml(ser.name) << "</text>";
    legend_x += 8 * static_cast<int>(ser.name.size()) + 16;
  }
  s << "</svg>";
  return s.str();
}

std::string metricsPlot(const RunResult& r) {
  const std::pair<Metric, std::pair<const char*, const char*>> defs[] = {
      {Metric::Precision, {"precision", "#1f77b4"}},
      {Metric::Recall, {"recall", "#2ca02c"}},
      {Metric::IoU, {"IoU", "#9467bd"}},
      {Metric::F1, {"F1", "#d62728"}}};
  std::vector<Series> series;
  for (const auto& [m, d] : defs) {
    Series s{d.first, d.second, {}};
    for (const auto& sw : r.metrics.sweeps) s.values.push_back(metricOf(sw.counts, m));
    series.push_back(std::move(s));
  }
  return svgPlot(
      "per-sweep metrics", series, [](double v) { return v; },
      {{0, "0"}, {0.25, "0.25"}, {0.5, "0.5"}, {0.75, "0.75"}, {1, "1"}}, std::nullopt);
}

std::string timingPlot(const RunResult& r) {
  Series s{"ms per frame", "#333", {}};
  for (const auto& sw : r.metrics.sweeps)
    s.values.push_back(sw.ms >= 0 ? std::optional<double>(sw.ms) : std::nullopt);
  const double budget = 1000.0 / r.rate_hz;
  // Log scale from 0.1 ms to 2x the budget, so both the frame times and the budget show.
  const double lo = std::log10(0.1), hi = std::log10(2 * budget);
  return svgPlot(
      "detector time per frame (log scale)", {s},
      [=](double v) { return (std::log10(std::max(v, 0.1)) - lo) / (hi - lo); },
      {{0.1, "0.1"}, {1, "1"}, {10, "10"}, {100, "100"}},
      std::make_pair(budget,
                     "real-time budget " + num(budget, 0) + " ms (" + num(r.rate_hz, 0) + " Hz)"));
}

std::string pngDataUri(const cv::Mat& img) {
  std::vector<std::uint8_t> buf;
  if (!cv::imencode(".png", img, buf))
    throw std::runtime_error("cannot encode an overlay image as PNG");
  return "data:image/png;base64," + base64(buf);
}

}  // namespace

std::string markdownTable(const std::vector<RunResult>& runs) {
  std::ostringstream s;
  s << "| sequence | method | precision | IoU | recall | F1 | object recall | static flagged | ms "
       "median / p99 |\n"
    << "|---|---|---|---|---|---|---|---|---|\n";
  for (const RunResult& r : runs) {
    const eval::Confusion& c = r.metrics.total;
    s << "| " << r.sequence << " | " << r.description << " | " << opt(c.precision()) << " | "
      << opt(c.iou()) << " | " << opt(c.recall()) << " | " << opt(c.f1()) << " | "
      << objectRecall(r) << " | " << percent(r.metrics.staticFlagged()) << " | " << timing(r)
      << " |\n";
  }
  return s.str();
}

void writeSweepCsv(const std::string& path, const RunResult& run) {
  std::ostringstream s;
  s << "sweep,timestamp_ns,tp,fp,fn,tn,precision,recall,iou,f1,ms\n";
  for (std::size_t i = 0; i < run.metrics.sweeps.size(); i++) {
    const SweepMetrics& sw = run.metrics.sweeps[i];
    const eval::Confusion& c = sw.counts;
    s << i << "," << sw.timestamp_ns << "," << c.tp << "," << c.fp << "," << c.fn << "," << c.tn
      << "," << opt(c.precision(), "") << "," << opt(c.recall(), "") << "," << opt(c.iou(), "")
      << "," << opt(c.f1(), "") << "," << (sw.ms >= 0 ? num(sw.ms, 3) : "") << "\n";
  }
  io::writeFileAtomically(path, s.str());
}

void writeJsonSummary(const std::string& path, const std::vector<RunResult>& runs) {
  std::ostringstream s;
  s << "{\n  \"runs\": [";
  for (std::size_t k = 0; k < runs.size(); k++) {
    const RunResult& r = runs[k];
    const eval::Confusion& c = r.metrics.total;
    s << (k ? "," : "") << "\n    {\"sequence\": \"" << escapeJson(r.sequence) << "\", \"mode\": \""
      << escapeJson(r.mode) << "\", \"description\": \"" << escapeJson(r.description)
      << "\", \"sweeps\": " << r.metrics.sweeps.size() << ", \"rows\": " << r.rows
      << ", \"cols\": " << r.cols << ",\n     \"tp\": " << c.tp << ", \"fp\": " << c.fp
      << ", \"fn\": " << c.fn << ", \"precision\": " << jsonOpt(c.precision())
      << ", \"recall\": " << jsonOpt(c.recall()) << ", \"iou\": " << jsonOpt(c.iou())
      << ", \"f1\": " << jsonOpt(c.f1())
      << ", \"static_flagged\": " << jsonOpt(r.metrics.staticFlagged())
      << ",\n     \"per_sweep\": {";
    const std::pair<Metric, const char*> names[] = {{Metric::Precision, "precision"},
                                                    {Metric::Recall, "recall"},
                                                    {Metric::IoU, "iou"},
                                                    {Metric::F1, "f1"}};
    for (std::size_t i = 0; i < 4; i++) {
      const Distribution d = r.metrics.distribution(names[i].first);
      s << (i ? ", " : "") << "\"" << names[i].second << "\": {\"sweeps\": " << d.sweeps
        << ", \"q1\": " << jsonOpt(d.q1) << ", \"median\": " << jsonOpt(d.median)
        << ", \"q3\": " << jsonOpt(d.q3) << "}";
    }
    s << "},\n     \"object_recall\": ";
    if (r.objects) {
      s << "{\"min_points\": " << r.objects->minPoints()
        << ", \"present\": " << r.objects->total().present
        << ", \"detected\": " << r.objects->total().detected
        << ", \"recall\": " << jsonOpt(r.objects->total().recall()) << ", \"by_class\": {";
      bool first = true;
      for (const auto& [cls, t] : r.objects->byClass()) {
        s << (first ? "" : ", ") << "\"" << escapeJson(cls) << "\": {\"present\": " << t.present
          << ", \"detected\": " << t.detected << ", \"recall\": " << jsonOpt(t.recall()) << "}";
        first = false;
      }
      s << "}}";
    } else {
      s << "null";
    }
    s << ",\n     \"ms\": ";
    if (r.timing) {
      s << "{";
      const auto& stages = eval::TimingStats::stages();
      for (std::size_t i = 0; i < stages.size(); i++)
        s << (i ? ", " : "") << "\"" << stages[i]
          << "\": {\"median\": " << num(r.timing->percentile(stages[i], 50), 4)
          << ", \"p99\": " << num(r.timing->percentile(stages[i], 99), 4) << "}";
      s << "}, \"ego_motion_failed\": " << r.ego_failed;
    } else {
      s << "null";
    }
    s << "}";
  }
  s << "\n  ]\n}\n";
  io::writeFileAtomically(path, s.str());
}

void writeHtmlReport(const std::string& path, const std::string& title, const std::string& command,
                     const std::vector<RunResult>& runs) {
  std::ostringstream s;
  s << "<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'><title>" << escapeHtml(title)
    << "</"
       "title>\n<style>body{font-family:sans-serif;margin:24px;max-width:1100px}table{border-"
       "collapse:collapse}"
       "td,th{border:1px solid #bbb;padding:3px "
       "8px;font-size:13px}th{background:#eee}img{max-width:100%;"
       "image-rendering:pixelated;border:1px solid #888}code{background:#f4f4f4;padding:2px 4px}"
       ".legend span{padding:1px 6px;margin-right:8px}</style></head>\n<body>\n<h1>"
    << escapeHtml(title) << "</h1>\n<p>Regenerate: <code>" << escapeHtml(command)
    << "</code></p>\n<p id='image-check'></p>\n<h2>Summary (per point, summed over the "
       "sequence)</h2>\n<table><tr>"
       "<th>sequence</th><th>method</th><th>precision</th><th>IoU</th><th>recall</th><th>F1</th>"
       "<th>object recall</th><th>static flagged</th><th>ms median / p99</th></tr>\n";
  for (const RunResult& r : runs) {
    const eval::Confusion& c = r.metrics.total;
    s << "<tr><td>" << escapeHtml(r.sequence) << "</td><td>" << escapeHtml(r.description)
      << "</td><td>" << opt(c.precision()) << "</td><td>" << opt(c.iou()) << "</td><td>"
      << opt(c.recall()) << "</td><td>" << opt(c.f1()) << "</td><td>" << objectRecall(r)
      << "</td><td>" << percent(r.metrics.staticFlagged()) << "</td><td>" << timing(r)
      << "</td></tr>\n";
  }
  s << "</table>\n<p>Paper (Du &amp; Beltrame, Table I, four real sequences): precision "
       "0.871–0.911, IoU "
       "0.842–0.876, recall 0.883–0.899, F1 0.875–0.888.</p>\n<p class='legend'>Overlays: <span "
       "style='background:#f00;color:#fff'>true positive</span><span style='background:#ff0'>false "
       "positive</span><span style='background:#00f;color:#fff'>missed</span> numbers = track "
       "ids.</p>\n";
  for (const RunResult& r : runs) {
    s << "<h2>" << escapeHtml(r.sequence) << ": " << escapeHtml(r.description) << "</h2>\n";
    s << "<p>" << r.metrics.sweeps.size() << " sweeps of " << r.rows << "×" << r.cols;
    for (const auto m : {Metric::Precision, Metric::IoU, Metric::Recall, Metric::F1}) {
      const Distribution d = r.metrics.distribution(m);
      const char* name = m == Metric::Precision ? "precision"
                         : m == Metric::IoU     ? "IoU"
                         : m == Metric::Recall  ? "recall"
                                                : "F1";
      s << "; " << name << " per sweep median " << opt(d.median) << " [" << opt(d.q1) << ", "
        << opt(d.q3) << "] over " << d.sweeps << " sweeps";
    }
    s << "</p>\n";
    if (r.objects && !r.objects->byClass().empty()) {
      s << "<p>Object recall by class (objects with at least " << r.objects->minPoints()
        << " points in a sweep; detected / present object-sweeps):";
      for (const auto& [cls, t] : r.objects->byClass())
        s << " " << escapeHtml(cls) << " " << opt(t.recall()) << " (" << t.detected << "/"
          << t.present << ");";
      s << "</p>\n";
    }
    s << metricsPlot(r) << "\n";
    if (r.timing) s << timingPlot(r) << "\n";
    for (const auto& [sweep, img] : r.overlays)
      s << "<figure><img alt='sweep " << sweep << "' src='" << pngDataUri(img)
        << "'><figcaption>sweep " << sweep << "</figcaption></figure>\n";
  }
  // Says on the page whether every image decoded (and marks the body for headless checks).
  s << "<script>window.addEventListener('load',function(){var imgs=document.images,ok=0;"
       "for(var i=0;i<imgs.length;i++)if(imgs[i].complete&&imgs[i].naturalWidth>0)ok++;"
       "document.body.setAttribute('data-images',imgs.length);document.body.setAttribute('data-"
       "images-ok',ok);"
       "document.getElementById('image-check').textContent=(ok==imgs.length?'':'WARNING: ')+ok+' "
       "of '+"
       "imgs.length+' images loaded';});</script>\n</body></html>\n";
  io::writeFileAtomically(path, s.str());
}

}  // namespace dynobj::eval
