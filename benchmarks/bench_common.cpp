// SPDX-License-Identifier: GPL-3.0-or-later
#include "bench_common.h"

#include <pcl/pcl_config.h>

#include <CGAL/version.h>
#include <CGAL/version_macros.h>
#include <Eigen/Core>
#include <oneapi/tbb/version.h>

#include <malloc.h>
#include <poll.h>
#include <signal.h>
#include <sys/utsname.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace pcl {
namespace cocone {
namespace bench {

namespace {

/** A field of /proc/self/status in kB ("VmHWM", "VmRSS"); NaN when absent. */
double
statusKb(const std::string& field)
{
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.compare(0, field.size() + 1, field + ":") == 0)
      return std::stod(line.substr(field.size() + 1));
  return kNaN;
}

std::string
oneLine(std::string text)
{
  for (char& c : text)
    if (c == '\n' || c == '\t' || c == '\r')
      c = ' ';
  return text;
}

std::string
serialize(const Measurement& m)
{
  std::ostringstream out;
  out << std::setprecision(17);
  out << "o\t" << (m.ok ? 1 : 0) << "\n";
  out << "s\t" << m.seconds << "\n";
  out << "p\t" << m.peak_mb << "\n";
  if (!m.error.empty())
    out << "e\t" << oneLine(m.error) << "\n";
  for (const auto& kv : m.values)
    out << "v\t" << oneLine(kv.first) << "\t" << kv.second << "\n";
  for (const auto& kv : m.texts)
    out << "t\t" << oneLine(kv.first) << "\t" << oneLine(kv.second) << "\n";
  return out.str();
}

double
parseDouble(const std::string& text)
{
  if (text == "nan" || text == "-nan")
    return kNaN;
  if (text == "inf")
    return std::numeric_limits<double>::infinity();
  if (text == "-inf")
    return -std::numeric_limits<double>::infinity();
  try {
    return std::stod(text);
  }
  catch (...) {
    return kNaN;
  }
}

Measurement
deserialize(const std::string& text)
{
  Measurement m;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t tab = line.find('\t');
    if (tab == std::string::npos)
      continue;
    const std::string kind = line.substr(0, tab);
    const std::string rest = line.substr(tab + 1);
    if (kind == "o")
      m.ok = rest == "1";
    else if (kind == "s")
      m.seconds = parseDouble(rest);
    else if (kind == "p")
      m.peak_mb = parseDouble(rest);
    else if (kind == "e")
      m.error = rest;
    else {
      const std::size_t tab2 = rest.find('\t');
      if (tab2 == std::string::npos)
        continue;
      const std::string key = rest.substr(0, tab2);
      const std::string value = rest.substr(tab2 + 1);
      if (kind == "v")
        m.values[key] = parseDouble(value);
      else if (kind == "t")
        m.texts[key] = value;
    }
  }
  return m;
}

const std::chrono::steady_clock::time_point kProgramStart =
    std::chrono::steady_clock::now();

std::string
readFirstLine(const std::string& path)
{
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

} // namespace

double
Measurement::value(const std::string& key) const
{
  const auto it = values.find(key);
  return it == values.end() ? kNaN : it->second;
}

std::string
Measurement::text(const std::string& key, const std::string& fallback) const
{
  const auto it = texts.find(key);
  return it == texts.end() ? fallback : it->second;
}

AlgorithmMeter::AlgorithmMeter()
{
  // Reset the peak to the current resident size (Linux >= 4.0), so that whatever the
  // run prepared and freed before the algorithm does not count.
  {
    std::ofstream clear("/proc/self/clear_refs");
    if (clear)
      clear << "5";
  }
  baseline_kb_ = statusKb("VmRSS");
  start_ = std::chrono::steady_clock::now();
}

double
AlgorithmMeter::elapsed() const
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_)
      .count();
}

void
AlgorithmMeter::stop(Measurement& m)
{
  m.seconds = elapsed();
  const double peak_kb = statusKb("VmHWM");
  m.peak_mb = std::max(0.0, peak_kb - baseline_kb_) / 1024.0;
}

Measurement
runIsolated(const std::function<void(Measurement&)>& body, double timeout_seconds)
{
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  // Give the parent's free heap pages back to the system: a child inherits them as
  // resident, and an algorithm that reused them would show no growth of its resident
  // set (its peak memory would be hidden).
  malloc_trim(0);
  int fds[2];
  if (pipe(fds) != 0)
    throw std::runtime_error(std::string("pipe failed: ") + std::strerror(errno));
  const pid_t pid = fork();
  if (pid < 0)
    throw std::runtime_error(std::string("fork failed: ") + std::strerror(errno));
  if (pid == 0) {
    close(fds[0]);
    Measurement m;
    try {
      body(m);
      m.ok = m.error.empty();
    }
    catch (const std::bad_alloc&) {
      m.ok = false;
      m.error = "out of memory";
    }
    catch (const std::exception& e) {
      m.ok = false;
      m.error = e.what();
    }
    catch (...) {
      m.ok = false;
      m.error = "unknown exception";
    }
    const std::string text = serialize(m);
    std::size_t written = 0;
    while (written < text.size()) {
      const ssize_t w = write(fds[1], text.data() + written, text.size() - written);
      if (w <= 0)
        break;
      written += static_cast<std::size_t>(w);
    }
    close(fds[1]);
    std::fflush(stderr);
    _exit(0); // no static destructors: they belong to the parent
  }
  close(fds[1]);
  std::string received;
  const auto start = std::chrono::steady_clock::now();
  bool timed_out = false;
  char buffer[4096];
  for (;;) {
    const double left =
        timeout_seconds -
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (left <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready =
        poll(&p, 1, static_cast<int>(std::min(left * 1000.0, 60000.0)) + 1);
    if (ready < 0 && errno == EINTR)
      continue;
    if (ready <= 0)
      continue;
    const ssize_t r = read(fds[0], buffer, sizeof(buffer));
    if (r < 0 && errno == EINTR)
      continue;
    if (r <= 0)
      break;
    received.append(buffer, static_cast<std::size_t>(r));
  }
  close(fds[0]);
  if (timed_out)
    kill(pid, SIGKILL);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  Measurement m = deserialize(received);
  if (timed_out) {
    m.ok = false;
    std::ostringstream why;
    why << "timeout after " << timeout_seconds << " s";
    m.error = why.str();
  }
  else if (WIFSIGNALED(status)) {
    m.ok = false;
    m.error = std::string("killed by signal ") + strsignal(WTERMSIG(status));
  }
  else if (received.empty()) {
    m.ok = false;
    m.error = "child reported nothing";
  }
  return m;
}

void
BestRun::add(const Measurement& m)
{
  spent_ += std::max(0.0, m.seconds);
  if (runs_++ == 0)
    best_ = m;
  else if (best_.ok && m.ok && m.seconds < best_.seconds) {
    // Keep the quality values of the first run, take the better time.
    best_.seconds = m.seconds;
    for (const auto& kv : m.values)
      if (kv.first.rfind("t_", 0) == 0) // sub-timings travel with the time
        best_.values[kv.first] = kv.second;
  }
  if (m.ok) {
    times_.push_back(m.seconds);
    smallest_peak_ =
        smallest_peak_ < 0 ? m.peak_mb : std::min(smallest_peak_, m.peak_mb);
  }
}

Measurement
BestRun::result() const
{
  Measurement out = best_;
  if (out.ok && smallest_peak_ >= 0)
    out.peak_mb = smallest_peak_;
  out.values["repeats"] = static_cast<double>(times_.size());
  if (!times_.empty())
    out.values["worst_seconds"] = *std::max_element(times_.begin(), times_.end());
  return out;
}

std::vector<Measurement>
takeTurns(int repeats, const std::vector<Contestant>& contestants,
          double timeout_seconds)
{
  std::vector<BestRun> best(contestants.size());
  for (int r = 0; r < std::max(1, repeats); ++r)
    for (std::size_t k = 0; k < contestants.size(); ++k) {
      if (r > 0 &&
          (best[k].failed() || best[k].spent() >= contestants[k].budget_seconds))
        continue;
      best[k].add(runIsolated([&](Measurement& out) { contestants[k].body(r, out); },
                              timeout_seconds));
    }
  std::vector<Measurement> results;
  for (const BestRun& b : best)
    results.push_back(b.result());
  return results;
}

Measurement
bestOf(int repeats, const std::function<void(int, Measurement&)>& body,
       double timeout_seconds, double budget_seconds)
{
  return takeTurns(repeats, {{body, budget_seconds}}, timeout_seconds).front();
}

LoadSample
sampleLoad()
{
  LoadSample s;
  {
    std::istringstream in(readFirstLine("/proc/loadavg"));
    std::string a, b, c;
    in >> a >> b >> c;
    s.loadavg = a + " " + b + " " + c;
  }
  std::istringstream in(readFirstLine("/proc/stat"));
  std::string cpu;
  in >> cpu;
  unsigned long long v[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  for (int i = 0; i < 10 && (in >> v[i]); ++i) {
  }
  // user nice system idle iowait irq softirq steal guest guest_nice; guest time is
  // already counted in user.
  for (int i = 0; i < 8; ++i)
    s.total += v[i];
  s.steal = v[7];
  s.idle = v[3] + v[4];
  return s;
}

double
stealShare(const LoadSample& from, const LoadSample& to)
{
  if (to.total <= from.total)
    return kNaN;
  return static_cast<double>(to.steal - from.steal) /
         static_cast<double>(to.total - from.total);
}

double
busyShare(const LoadSample& from, const LoadSample& to)
{
  if (to.total <= from.total)
    return kNaN;
  const double idle = static_cast<double>(to.idle - from.idle);
  return 1.0 - idle / static_cast<double>(to.total - from.total);
}

std::vector<std::pair<std::string, std::string>>
machineFacts()
{
  std::vector<std::pair<std::string, std::string>> facts;
  std::string model = "unknown";
  {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
      if (line.rfind("model name", 0) == 0) {
        model = line.substr(line.find(':') + 2);
        break;
      }
  }
  facts.emplace_back("CPU", model);
  facts.emplace_back("logical cores", std::to_string(sysconf(_SC_NPROCESSORS_ONLN)));
  {
    std::ifstream in("/proc/meminfo");
    std::string line;
    std::getline(in, line);
    std::istringstream fields(line);
    std::string name;
    double kb = 0;
    fields >> name >> kb;
    facts.emplace_back("memory", fixed(kb / 1024.0 / 1024.0, 1) + " GiB");
  }
  utsname u{};
  if (uname(&u) == 0)
    facts.emplace_back("kernel",
                       std::string(u.sysname) + " " + u.release + " " + u.machine);
#if defined(__clang__)
  facts.emplace_back("compiler", std::string("clang ") + __clang_version__);
#elif defined(__GNUC__)
  facts.emplace_back("compiler", std::string("GCC ") + __VERSION__);
#endif
#ifdef NDEBUG
  facts.emplace_back("build",
                     "optimized, NDEBUG (CMAKE_BUILD_TYPE of the build directory)");
#else
  facts.emplace_back(
      "build", "assertions on (not a Release build: timings are not representative)");
#endif
  facts.emplace_back("PCL", PCL_VERSION_PRETTY);
  facts.emplace_back("CGAL", CGAL_VERSION_STR);
  facts.emplace_back("oneTBB", std::to_string(TBB_VERSION_MAJOR) + "." +
                                   std::to_string(TBB_VERSION_MINOR));
  facts.emplace_back("Eigen", std::to_string(EIGEN_WORLD_VERSION) + "." +
                                  std::to_string(EIGEN_MAJOR_VERSION) + "." +
                                  std::to_string(EIGEN_MINOR_VERSION));
  return facts;
}

std::string
utcNow()
{
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[64];
  std::strftime(text, sizeof(text), "%Y-%m-%d %H:%M UTC", &tm);
  return text;
}

std::string
fixed(double value, int digits)
{
  if (std::isnan(value))
    return "-";
  if (std::isinf(value))
    return value > 0 ? "inf" : "-inf";
  std::ostringstream out;
  out << std::fixed << std::setprecision(digits) << value;
  return out.str();
}

std::string
sig(double value, int significant)
{
  if (std::isnan(value))
    return "-";
  if (std::isinf(value))
    return value > 0 ? "inf" : "-inf";
  if (value == 0)
    return "0";
  const int magnitude = static_cast<int>(std::floor(std::log10(std::abs(value))));
  const int digits = std::max(0, significant - 1 - magnitude);
  if (digits > 6) {
    std::ostringstream out;
    out << std::setprecision(significant) << value;
    return out.str();
  }
  return fixed(value, digits);
}

std::string
count(double value)
{
  if (std::isnan(value))
    return "-";
  const long long v = std::llround(value);
  std::string digits = std::to_string(std::llabs(v));
  std::string out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0)
      out += ' ';
    out += digits[i];
  }
  return v < 0 ? "-" + out : out;
}

std::string
seconds(double s)
{
  if (std::isnan(s) || s < 0)
    return "-";
  if (s < 1)
    return fixed(s, 3);
  if (s < 100)
    return fixed(s, 2);
  return fixed(s, 0);
}

std::string
percent(double fraction, int digits)
{
  if (std::isnan(fraction))
    return "-";
  return fixed(100.0 * fraction, digits) + "%";
}

Table::Table(std::vector<std::string> header) : header_(std::move(header)) {}

void
Table::add(std::vector<std::string> row)
{
  row.resize(header_.size());
  rows_.push_back(std::move(row));
}

std::string
Table::markdown() const
{
  std::vector<std::size_t> width(header_.size(), 3);
  // Width in characters, not bytes: count UTF-8 lead bytes only.
  const auto length = [](const std::string& s) {
    std::size_t n = 0;
    for (const unsigned char c : s)
      n += (c & 0xC0) != 0x80;
    return n;
  };
  for (std::size_t c = 0; c < header_.size(); ++c) {
    width[c] = std::max(width[c], length(header_[c]));
    for (const auto& row : rows_)
      width[c] = std::max(width[c], length(row[c]));
  }
  const auto line = [&](const std::vector<std::string>& cells) {
    std::string out = "|";
    for (std::size_t c = 0; c < cells.size(); ++c) {
      std::string cell = cells[c];
      for (char& ch : cell)
        if (ch == '|')
          ch = '/';
      out += " " + cell + std::string(width[c] - length(cell), ' ') + " |";
    }
    return out + "\n";
  };
  std::string out = line(header_);
  out += "|";
  for (std::size_t c = 0; c < header_.size(); ++c)
    out += std::string(width[c] + 2, '-') + "|";
  out += "\n";
  for (const auto& row : rows_)
    out += line(row);
  return out;
}

void
Report::add(const std::string& text)
{
  text_ += text;
  std::cout << text << std::flush;
}

void
Report::heading(int level, const std::string& title)
{
  add("\n" + std::string(static_cast<std::size_t>(level), '#') + " " + title + "\n\n");
}

void
Report::paragraph(const std::string& text)
{
  add(text + "\n\n");
}

void
Report::table(const Table& table)
{
  add(table.markdown() + "\n");
}

void
progress(const std::string& message)
{
  const double t =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - kProgramStart)
          .count();
  std::cerr << "[" << std::fixed << std::setprecision(0) << std::setw(5) << t << " s] "
            << message << std::endl;
}

} // namespace bench
} // namespace cocone
} // namespace pcl
