// SPDX-License-Identifier: BSD-3-Clause
// Damaged-input test driver: copies of a rawlog with seeded damage (bits flipped, bytes zeroed,
// bytes inserted, file truncated; in the gzip file as stored, or in the uncompressed stream) are
// given to a tool, e.g. `rawlog-dynobj -i {in} -o {out} --mode drop`. Every case must end in
//   exit 0 with the output complete (MRPT reads it to its end) and no `.partial`, or
//   exit 1 with a message naming the entry or byte, no output and no `.partial`;
// never a signal, the crash guard's exit code 3, or a hang.
//
//   damaged_rawlogs --base in.rawlog [--entries K] --work DIR --first I --count N
//                   [--results FILE] [--timeout S] -- tool args... ({in}, {out} replaced)
// Case i: kind = i % 8 (flip, zero, insert, truncate; even = gzip file, odd = uncompressed
// stream), seed = i. With --results, one line per case is appended and cases already listed
// are skipped (resumable). Prints a summary; exit code 0 if no case failed.
#include <dynobj/mrptio/RawlogReader.h>
#include <dynobj/mrptio/RawlogWriter.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileInputStream.h>
#include <mrpt/serialization/CArchive.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;
using Bytes = std::vector<unsigned char>;

namespace {

const char* const kKinds[] = {"flip-gz",   "flip-raw",   "zero-gz",     "zero-raw",
                              "insert-gz", "insert-raw", "truncate-gz", "truncate-raw"};

Bytes readFile(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(f), {});
}
void writeFile(const std::string& path, const Bytes& b) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}
Bytes uncompressed(const std::string& path) {
  mrpt::io::CFileGZInputStream in(path);
  Bytes out, chunk(1 << 16);
  for (;;) {
    const std::size_t n = in.Read(chunk.data(), chunk.size());
    if (n == 0 || n > chunk.size()) break;
    out.insert(out.end(), chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(n));
  }
  return out;
}

/// The first `entries` entries of `src` (all if 0), as a gzip rawlog.
void makeBase(const std::string& src, std::size_t entries, const std::string& dst) {
  dynobj::mrptio::RawlogReader in(src);
  dynobj::mrptio::RawlogWriter out(dst);
  dynobj::mrptio::RawlogEntry e;
  while ((entries == 0 || in.entriesRead() < entries) && in.next(e)) {
    if (e.actions) out.write(*e.actions);
    if (e.sensory_frame) out.write(*e.sensory_frame);
    if (e.observation) out.write(*e.observation);
  }
  out.commit();
}

Bytes mutate(Bytes d, int kind, std::uint64_t seed) {
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ULL + static_cast<std::uint64_t>(kind));
  const auto pick = [&](std::size_t n) {
    return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
  };
  switch (kind / 2) {
    case 0:  // flip 1-8 bits
      for (std::size_t k = 1 + pick(8); k > 0; k--) d[pick(d.size())] ^= 1u << pick(8);
      break;
    case 1: {  // zero a run of 1-256 bytes
      const std::size_t at = pick(d.size()), n = std::min(1 + pick(256), d.size() - at);
      std::fill_n(d.begin() + static_cast<std::ptrdiff_t>(at), n, 0);
      break;
    }
    case 2: {  // insert 1-16 random bytes
      const std::size_t at = pick(d.size() + 1), n = 1 + pick(16);
      Bytes ins(n);
      for (auto& b : ins) b = static_cast<unsigned char>(pick(256));
      d.insert(d.begin() + static_cast<std::ptrdiff_t>(at), ins.begin(), ins.end());
      break;
    }
    default:  // truncate (keep at least one byte)
      d.resize(1 + pick(d.size() - 1));
  }
  return d;
}

struct Run {
  int status = 0;
  bool timed_out = false;
  std::string err;
};

Run runTool(std::vector<std::string> args, const std::string& log, int timeout_s) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  Run r;
  const pid_t pid = fork();
  if (pid == 0) {
    FILE* f = std::freopen(log.c_str(), "w", stderr);
    if (!f) _exit(126);
    if (!std::freopen("/dev/null", "w", stdout)) _exit(126);
    execv(argv[0], argv.data());
    _exit(127);
  }
  const auto t0 = std::chrono::steady_clock::now();
  for (;;) {
    const pid_t w = waitpid(pid, &r.status, WNOHANG);
    if (w == pid) break;
    if (std::chrono::steady_clock::now() - t0 > std::chrono::seconds(timeout_s)) {
      kill(pid, SIGKILL);
      waitpid(pid, &r.status, 0);
      r.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  std::ifstream f(log);
  std::stringstream ss;
  ss << f.rdbuf();
  r.err = ss.str();
  return r;
}

/// MRPT's own reader gets through the whole output: returns the object count, or -1.
long readsToEnd(const std::string& path, std::string& why) {
  try {
    mrpt::io::CFileGZInputStream in(path);
    auto arch = mrpt::serialization::archiveFrom(in);
    long n = 0;
    for (;;) {
      try {
        if (!arch.ReadObject()) return why = "null object", -1;
      } catch (const mrpt::serialization::CExceptionEOF&) {
        return n;
      }
      n++;
    }
  } catch (const std::exception& e) {
    why = e.what();
    return -1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::map<std::string, std::string> opt;
  std::vector<std::string> tool;
  for (int i = 1; i < argc; i++) {
    const std::string a = argv[i];
    if (a == "--") {
      tool.assign(argv + i + 1, argv + argc);
      break;
    }
    if (a.rfind("--", 0) == 0 && i + 1 < argc) opt[a.substr(2)] = argv[++i];
  }
  if (!opt.count("base") || !opt.count("work") || tool.empty()) {
    std::cerr << "usage: damaged_rawlogs --base in.rawlog [--entries K] --work DIR [--first I] "
                 "[--count N] [--results FILE] [--timeout S] -- tool args ({in} {out})\n";
    return 2;
  }
  const std::string work = opt["work"];
  fs::create_directories(work);
  const std::size_t entries = opt.count("entries") ? std::stoul(opt["entries"]) : 0;
  const std::uint64_t first = opt.count("first") ? std::stoull(opt["first"]) : 0;
  const std::uint64_t count = opt.count("count") ? std::stoull(opt["count"]) : 8;
  const int timeout_s = opt.count("timeout") ? std::stoi(opt["timeout"]) : 120;

  const std::string base = work + "/base.rawlog";
  if (!fs::exists(base)) makeBase(opt["base"], entries, base);
  const Bytes gz = readFile(base), raw = uncompressed(base);

  std::set<std::uint64_t> done;
  std::ofstream results;
  if (opt.count("results")) {
    std::ifstream prev(opt["results"]);
    std::string line;
    while (std::getline(prev, line)) {
      std::uint64_t c = 0;
      if (std::sscanf(line.c_str(), "%lu", &c) == 1) done.insert(c);
    }
    results.open(opt["results"], std::ios::app);
  }

  const std::regex names_where(R"((entry|byte|line|offset) [0-9]+)");
  std::map<std::string, int> tally;
  int failures = 0;
  std::uint64_t ran = 0;
  for (std::uint64_t c = first; c < first + count; c++) {
    if (done.count(c)) continue;
    ran++;
    const int kind = static_cast<int>(c % 8);
    const std::string in = work + "/case.rawlog", out = work + "/case-out.rawlog";
    fs::remove(out);
    writeFile(in, mutate(kind % 2 ? raw : gz, kind, c));
    std::vector<std::string> args;
    for (auto a : tool) {
      for (const auto& [key, val] :
           {std::pair<std::string, std::string>{"{in}", in}, {"{out}", out}})
        if (const auto p = a.find(key); p != std::string::npos) a.replace(p, key.size(), val);
      args.push_back(a);
    }
    const Run r = runTool(args, work + "/case.stderr", timeout_s);
    std::string verdict, problem;
    const bool partial = fs::exists(out + ".partial");
    if (r.timed_out) {
      problem = "timed out";
    } else if (WIFSIGNALED(r.status)) {
      problem = std::string("killed by signal ") + strsignal(WTERMSIG(r.status));
    } else if (WEXITSTATUS(r.status) == 0) {
      std::string why;
      const long n = fs::exists(out) ? readsToEnd(out, why) : -1;
      verdict = "ok";
      if (!fs::exists(out))
        problem = "exit 0 without an output";
      else if (n <= 0)
        problem = "exit 0 but the output is not readable to its end: " + why;
    } else if (WEXITSTATUS(r.status) == 1) {
      verdict = "error";
      if (!std::regex_search(r.err, names_where))
        problem = "the message names no entry/byte";
      else if (fs::exists(out))
        problem = "an output was left after an error";
    } else {
      problem = "exit code " + std::to_string(WEXITSTATUS(r.status));
    }
    if (partial) problem += problem.empty() ? "a .partial was left" : "; a .partial was left";
    if (!problem.empty()) verdict = "FAIL";
    tally[std::string(kKinds[kind]) + " " + verdict]++;
    std::string first_line = r.err.substr(0, r.err.find('\n'));
    if (results.is_open())
      results << c << ' ' << kKinds[kind] << ' ' << verdict << " | " << first_line << std::endl;
    if (!problem.empty()) {
      failures++;
      const std::string keep = work + "/fail-" + std::to_string(c) + ".rawlog";
      fs::copy_file(in, keep, fs::copy_options::overwrite_existing);
      std::cout << "case " << c << " (" << kKinds[kind] << "): " << problem << "; input kept as "
                << keep << "\n  stderr: " << r.err.substr(0, 600) << "\n";
    }
    fs::remove(out + ".partial");
  }
  for (const auto& [k, n] : tally) std::cout << k << ": " << n << "\n";
  std::cout << (failures ? "FAILED: " : "passed: ") << failures << " failing case(s) of " << ran
            << " run\n";
  return failures ? 1 : 0;
}
