// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * Infrastructure of pcl_cocone_benchmark: isolated runs (one forked child process per
 * measurement, so that each method's peak memory is its own and a crash or a timeout
 * of a peer cannot take the benchmark down), wall-clock timing, machine facts and load,
 * and table formatting (Markdown tables that read as text on stdout too).
 */
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace pcl {
namespace cocone {
namespace bench {

/** "Not measured" in every table. */
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------------------------
// Measurements

/** \brief What one isolated run reports back to the parent process. */
struct Measurement
{
  bool ok = false;
  std::string error;   ///< why the run failed (exception, signal, timeout)
  double seconds = -1; ///< wall time of the algorithm alone
  double peak_mb = -1; ///< peak resident memory above the baseline at the start
  std::map<std::string, double> values;     ///< named numbers (counts, sub-timings)
  std::map<std::string, std::string> texts; ///< named strings

  /** \brief values[key], or NaN when absent. */
  double value(const std::string& key) const;
  /** \brief texts[key], or \a fallback when absent. */
  std::string text(const std::string& key, const std::string& fallback = "") const;
  bool
  has(const std::string& key) const
  {
    return values.count(key) != 0;
  }
};

/** \brief Inside a run: measures the algorithm's wall time and peak memory. Construct
 * it right before the algorithm (after the inputs are prepared), call stop() right
 * after; quality checks that follow do not count. */
class AlgorithmMeter
{
public:
  AlgorithmMeter();
  /** \brief Stops the clock and reads the peak; writes seconds and peak_mb. */
  void stop(Measurement& m);
  /** \brief Seconds since construction (the clock keeps running). */
  double elapsed() const;

private:
  std::chrono::steady_clock::time_point start_;
  double baseline_kb_ = 0;
};

/** \brief Runs \a body in a forked child process and returns what it recorded. The
 * child is killed after \a timeout_seconds. An exception in \a body, a crash or a
 * timeout gives ok = false and an error text. The parent process itself must not have
 * started worker threads (TBB, OpenMP) before forking: all parallel work runs in
 * children. */
Measurement
runIsolated(const std::function<void(Measurement&)>& body, double timeout_seconds);

/** \brief Keeps the best of repeated runs of one method: the first run's values (its
 * quality checks), the fastest successful time with its sub-timings (values named
 * "t_..."), the smallest peak. Used by bestOf and by interleaved repeats. */
class BestRun
{
public:
  void add(const Measurement& m);
  /** \brief The merged measurement ("repeats": successful runs, "worst_seconds"). */
  Measurement result() const;
  /** \brief Sum of the measured times so far. */
  double
  spent() const
  {
    return spent_;
  }
  /** \brief True when the first run failed (repeating would fail again). */
  bool
  failed() const
  {
    return runs_ > 0 && !best_.ok;
  }

private:
  Measurement best_;
  int runs_ = 0;
  double spent_ = 0;
  double smallest_peak_ = -1;
  std::vector<double> times_;
};

/** \brief The budget of a method that runs in every round. */
constexpr double kNoBudget = std::numeric_limits<double>::infinity();

/** \brief One method timed by takeTurns: its body, which receives the round (0 first:
 * do quality checks only there) and its measurement, and the budget after which it is
 * not run again. */
struct Contestant
{
  std::function<void(int, Measurement&)> body;
  double budget_seconds = 60;
};

/** \brief Runs the contestants in turn, each isolated, for up to \a repeats rounds, and
 * keeps each one's fastest successful run (BestRun). Taking turns means a burst of load
 * on the shared machine hits every method of a comparison alike, so the ratios between
 * them hold even when the absolute times do not. A contestant is not run again once it
 * failed or its measured times add up to its budget (slow peers run once or twice).
 * Results come in the contestants' order. */
std::vector<Measurement>
takeTurns(int repeats, const std::vector<Contestant>& contestants,
          double timeout_seconds);

/** \brief takeTurns with one contestant. */
Measurement bestOf(int repeats, const std::function<void(int, Measurement&)>& body,
                   double timeout_seconds, double budget_seconds = 60);

// ---------------------------------------------------------------------------------
// Machine facts and load

/** \brief A snapshot of the machine's counters: load averages and CPU time shares. */
struct LoadSample
{
  std::string loadavg;          ///< /proc/loadavg's first three fields
  unsigned long long total = 0; ///< all jiffies of the "cpu" line
  unsigned long long steal = 0; ///< steal jiffies
  unsigned long long idle = 0;  ///< idle + iowait jiffies
};
LoadSample sampleLoad();

/** \brief Share of steal time between two samples (NaN when no time passed). */
double stealShare(const LoadSample& from, const LoadSample& to);
/** \brief Share of busy (non-idle) time between two samples. */
double busyShare(const LoadSample& from, const LoadSample& to);

/** \brief CPU model, cores, memory, kernel, compiler, library versions. */
std::vector<std::pair<std::string, std::string>> machineFacts();

/** \brief Current time as "YYYY-MM-DD HH:MM UTC". */
std::string utcNow();

// ---------------------------------------------------------------------------------
// Formatting

/** \brief Fixed-point number with \a digits decimals; "-" for NaN. */
std::string fixed(double value, int digits);
/** \brief Number with about \a significant significant digits; "-" for NaN. */
std::string sig(double value, int significant = 3);
/** \brief Integer with thousands separators ("12 345"); "-" for NaN. */
std::string count(double value);
/** \brief Seconds as "0.123" / "12.3" / "123"; "-" for NaN or negative. */
std::string seconds(double s);
/** \brief A percentage "12.3%"; "-" for NaN. */
std::string percent(double fraction, int digits = 1);

/** \brief A Markdown table built row by row. */
class Table
{
public:
  explicit Table(std::vector<std::string> header);
  void add(std::vector<std::string> row);
  bool
  empty() const
  {
    return rows_.empty();
  }
  /** \brief The table as Markdown, columns padded so that it also reads as text. */
  std::string markdown() const;

private:
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

/** \brief The report: Markdown text collected section by section, echoed to stdout as
 * it grows. */
class Report
{
public:
  /** \brief Appends \a text (and prints it). */
  void add(const std::string& text);
  void heading(int level, const std::string& title);
  void paragraph(const std::string& text);
  void table(const Table& table);
  const std::string&
  text() const
  {
    return text_;
  }

private:
  std::string text_;
};

/** \brief Progress line on stderr, with the time since the program started. */
void progress(const std::string& message);

} // namespace bench
} // namespace cocone
} // namespace pcl
