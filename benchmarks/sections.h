// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * The benchmark's sections (reconstruction, boundary detection, decimation) and what
 * they share: options, the inputs (loaded or generated once per process), the report
 * and the list of targets with their verdicts.
 */
#pragma once

#include "bench_common.h"
#include "bench_inputs.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace pcl {
namespace cocone {
namespace bench {

struct Options
{
  bool quick = false;          ///< no 1M inputs, no peers at 100k points and above
  std::string data_directory;  ///< where the data files are
  std::string markdown;        ///< output file, empty for none
  std::string only;            ///< one section, empty for all
  std::string filter;          ///< only inputs whose name contains this
  double timeout = 900;        ///< seconds per isolated run
  std::size_t large = 1000000; ///< size of the large torus
  bool no_peers = false;       ///< ours only (for profiling)
  /** Sizes of the random-sampled shapes (randomSizes() unless --random is given). */
  std::vector<std::size_t> random_sizes;
};

/** \brief A target of the brief with its verdict. */
struct Target
{
  std::string name;
  std::string goal;
  int status = -1; ///< 1 met, 0 missed, -1 not evaluated in this run
  std::string evidence;
};

class Context
{
public:
  explicit Context(Options options) : options(std::move(options)) {}

  Options options;
  Report report;
  std::vector<Target> targets;
  std::vector<std::string> skipped; ///< inputs that were not available, with the reason
  std::vector<const Input*> used;   ///< inputs that some section ran on, in order

  /** \brief Adds \a input to the inputs table (once). */
  void
  noteInput(const Input& input)
  {
    for (const Input* i : used)
      if (i == &input)
        return;
    used.push_back(&input);
  }

  /** \brief Sets (or replaces) the verdict of a target. */
  void setTarget(const std::string& name, const std::string& goal, int status,
                 const std::string& evidence);

  /** \brief A data file's input, or null when it is missing (noted in skipped). */
  const Input* fileInput(const std::string& name);
  /** \brief A generated blue-noise shape ("sphere", ..., "knot") with n samples. */
  const Input& generated(const std::string& shape, std::size_t n);
  /** \brief The large jittered torus. */
  const Input& largeTorus();
  /** \brief A random sample with scanner noise (noisyInputs()). */
  const Input& noisy(const NoisySpec& spec);
  /** \brief A shape sampled as a scanner does (area-uniform random) with n samples. */
  const Input& randomSampled(test::Shape shape, std::size_t n);

  /** \brief True when the input's name passes --filter. */
  bool
  selected(const std::string& name) const
  {
    return options.filter.empty() || name.find(options.filter) != std::string::npos;
  }

  /** \brief Rounds for the runs on \a n points: best of 3 up to 250k points (the
   * inputs whose ratios to the peers are targets, the 1M torus excepted), 2 above. */
  static int
  repeatsFor(std::size_t n)
  {
    return n <= 250000 ? 3 : 2;
  }
  /** \brief Time budget of the repeats of a peer (see bestOf): slow peers run once or
   * twice. */
  static constexpr double kPeerBudget = 15;

private:
  std::map<std::string, std::unique_ptr<Input>> inputs_;
};

void runReconstructionSection(Context& context);
void runBoundarySection(Context& context);
void runDecimationSection(Context& context);

/** \brief "1.23x" with two significant decimals; "-" for NaN. */
std::string ratio(double value);

} // namespace bench
} // namespace cocone
} // namespace pcl
