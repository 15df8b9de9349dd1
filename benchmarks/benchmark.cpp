// SPDX-License-Identifier: GPL-3.0-or-later
//
// pcl_cocone_benchmark: the classes of pcl_cocone against the bare CGAL Delaunay
// triangulation (the floor every Delaunay-based method pays) and against the peers in
// PCL and CGAL, on the paper's data sets, real scans and generated shapes; with the
// numbers of Dey et al. 2001 (Tables 1 and 2) beside ours.
//
//   pcl_cocone_benchmark [--quick] [--data DIR] [--markdown OUT.md]
//                        [--only reconstruction|boundary|decimation] [--filter NAME]
//                        [--timeout SECONDS]
//
// Every measurement runs in a forked child process (its own peak memory, no crash or
// timeout of a peer takes the run down); times are wall-clock times of the algorithm
// alone (reading and quality checks excluded).
#include "sections.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#ifndef PCL_COCONE_BENCH_DATA_DIR
#define PCL_COCONE_BENCH_DATA_DIR "../shared/data"
#endif

namespace pcl {
namespace cocone {
namespace bench {

std::string
ratio(double value)
{
  if (std::isnan(value))
    return "-";
  return sig(value, value < 10 ? 2 : 3) + "x";
}

void
Context::setTarget(const std::string& name, const std::string& goal, int status,
                   const std::string& evidence)
{
  for (Target& t : targets)
    if (t.name == name) {
      t.goal = goal;
      t.status = status;
      t.evidence = evidence;
      return;
    }
  targets.push_back({name, goal, status, evidence});
}

const Input*
Context::fileInput(const std::string& name)
{
  const std::string key = "file:" + name;
  auto it = inputs_.find(key);
  if (it != inputs_.end())
    return it->second.get();
  for (const FileSpec& spec : dataFiles())
    if (spec.name == name) {
      auto input = std::make_unique<Input>();
      std::string why;
      progress("loading " + spec.file);
      if (!loadFileInput(options.data_directory, spec, *input, why)) {
        skipped.push_back(spec.file + ": " + why);
        inputs_[key] = nullptr;
        return nullptr;
      }
      finishInput(*input, 100000);
      return (inputs_[key] = std::move(input)).get();
    }
  return nullptr;
}

const Input&
Context::generated(const std::string& shape, std::size_t n)
{
  const std::string key = "gen:" + shape + ":" + std::to_string(n);
  auto it = inputs_.find(key);
  if (it != inputs_.end())
    return *it->second;
  progress("sampling " + shape + " with " + std::to_string(n) + " points (blue noise)");
  ShapeGenerator generate = nullptr;
  if (shape == "knot")
    generate = &test::sampleTrefoilKnot;
  for (const GeneratedShape& g : generatedShapes())
    if (g.name == shape)
      generate = g.generate;
  auto input = std::make_unique<Input>(generatedInput(shape, generate, n));
  if (shape == "knot" && n == 10000) {
    input->paper = PaperReconstructionRow{"KNOT", 10000, 20000, 96};
    input->note =
        "trefoil tube of radius 0.25: a KNOT-sized stand-in (the paper's model "
        "is not available)";
  }
  if (shape == "monkey-saddle" && n == 10000) {
    input->paper = PaperReconstructionRow{"MONKEYSADDLE", 10000, 19599, 367};
    input->note = "z = x^3 - 3xy^2 over the unit disc, as the paper's MONKEYSADDLE";
  }
  finishInput(*input, std::min<std::size_t>(n, 50000));
  return *(inputs_[key] = std::move(input));
}

const Input&
Context::largeTorus()
{
  const std::string key = "torus-large";
  auto it = inputs_.find(key);
  if (it != inputs_.end())
    return *it->second;
  progress("generating the jittered torus with about " + std::to_string(options.large) +
           " points");
  auto input = std::make_unique<Input>(jitteredTorusInput(options.large));
  finishInput(*input, 100000);
  return *(inputs_[key] = std::move(input));
}

const Input&
Context::randomSampled(test::Shape shape, std::size_t n)
{
  const std::string key = "random:" + randomName(shape, n);
  auto it = inputs_.find(key);
  if (it != inputs_.end())
    return *it->second;
  progress("sampling " + randomName(shape, n) + " (area-uniform random)");
  const std::size_t probes = std::min<std::size_t>(n, 100000);
  auto input = std::make_unique<Input>(randomInput(shape, n, probes));
  finishInput(*input, probes);
  return *(inputs_[key] = std::move(input));
}

const Input&
Context::noisy(const NoisySpec& spec)
{
  const std::string key = "noisy:" + noisyName(spec);
  auto it = inputs_.find(key);
  if (it != inputs_.end())
    return *it->second;
  progress("sampling " + noisyName(spec) + " (area-uniform random, Gaussian noise)");
  const std::size_t probes = std::min<std::size_t>(spec.n, 100000);
  auto input = std::make_unique<Input>(
      noisyInput(spec.shape, spec.n, spec.sigma_in_spacings, probes));
  finishInput(*input, probes);
  return *(inputs_[key] = std::move(input));
}

} // namespace bench
} // namespace cocone
} // namespace pcl

namespace {

/** \a text with every occurrence of the source folder written relative to it, so that
 * the committed report names no machine's paths. */
std::string
relativeToSource(std::string text)
{
  const std::string source = std::string(PCL_COCONE_BENCH_SOURCE_DIR) + "/";
  for (std::size_t at = text.find(source); at != std::string::npos;
       at = text.find(source, at))
    text.erase(at, source.size());
  return text;
}

using namespace pcl::cocone::bench;

void
usage(std::ostream& out)
{
  out << "usage: pcl_cocone_benchmark [--quick] [--data DIR] [--markdown OUT.md]\n"
         "                            [--only reconstruction|boundary|decimation]\n"
         "                            [--filter NAME] [--timeout SECONDS] [--large N]\n"
         "                            [--ours-only] [--random N,N|none]\n"
         "  --quick     no 1M-point inputs, no peers on inputs of 100k points and more\n"
         "  --data      folder with the data files (default "
      << PCL_COCONE_BENCH_DATA_DIR
      << ")\n"
         "  --markdown  also write the report as Markdown to OUT.md\n"
         "  --only      run one section\n"
         "  --filter    only inputs whose name contains NAME\n"
         "  --timeout   seconds allowed to one isolated run (default 900)\n"
         "  --large     points of the large jittered torus (default 1000000)\n"
         "  --ours-only run no peer (e.g. to profile ours)\n"
         "  --random    sizes of the area-uniform random samples of the shapes (default\n"
         "              100000,1000000,4000000; with --quick 100000); none for none\n";
}

std::string
joinArguments(int argc, char** argv)
{
  std::string out;
  for (int i = 0; i < argc; ++i) {
    if (i)
      out += ' ';
    out += argv[i];
  }
  return out;
}

std::string
inputsTable(const Context& context)
{
  Table table({"input", "kind", "points", "distinct", "spacing", "reference surface",
               "closed / genus / loops", "source and notes"});
  for (const Input* input : context.used) {
    std::string reference = "none (no distance)";
    if (input->shape)
      reference = "analytic";
    else if (!input->mesh_triangles.empty())
      reference = "file's mesh (" +
                  count(static_cast<double>(input->mesh_triangles.size())) +
                  " triangles)";
    std::string topology = "unknown";
    if (input->closed >= 0)
      topology =
          std::string(input->closed ? "closed" : "open") + " / " +
          (input->genus >= 0 ? std::to_string(input->genus) : "?") + " / " +
          (input->boundary_loops >= 0 ? std::to_string(input->boundary_loops) : "?");
    std::string note = input->source;
    if (!input->note.empty())
      note += ": " + input->note;
    table.add({input->name, input->kind, count(static_cast<double>(input->size())),
               count(static_cast<double>(input->unique)), sig(input->spacing, 3),
               reference, topology, note});
  }
  return table.markdown();
}

} // namespace

int
main(int argc, char** argv)
{
  Options options;
  options.data_directory = PCL_COCONE_BENCH_DATA_DIR;
  bool random_sizes_given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << "pcl_cocone_benchmark: " << arg << " needs a value\n";
        std::exit(1);
      }
      return argv[++i];
    };
    // A number in [low, high], or a one-line reason and exit status 1.
    const auto number = [&](double low, double high) -> double {
      const std::string text = value();
      char* end = nullptr;
      const double parsed = std::strtod(text.c_str(), &end);
      if (text.empty() || *end != '\0' || !(parsed >= low && parsed <= high)) {
        std::cerr << "pcl_cocone_benchmark: " << arg << " needs a number from " << low
                  << " to " << high << ", not '" << text << "'\n";
        std::exit(1);
      }
      return parsed;
    };
    if (arg == "--quick")
      options.quick = true;
    else if (arg == "--data")
      options.data_directory = value();
    else if (arg == "--markdown")
      options.markdown = value();
    else if (arg == "--only")
      options.only = value();
    else if (arg == "--filter")
      options.filter = value();
    else if (arg == "--timeout")
      options.timeout = number(1, 1e6);
    else if (arg == "--ours-only")
      options.no_peers = true;
    else if (arg == "--large")
      options.large = static_cast<std::size_t>(number(1000, 1e8));
    else if (arg == "--random") {
      random_sizes_given = true;
      options.random_sizes.clear(); // the last --random counts
      // A trailing comma gets a last empty item (getline would drop it).
      const std::string text = value();
      std::stringstream list(text + (text.empty() || text.back() != ',' ? "" : ","));
      std::string item;
      while (text != "none" && std::getline(list, item, ',')) {
        char* end = nullptr;
        const double parsed = std::strtod(item.c_str(), &end);
        if (item.empty() || *end != '\0' || !(parsed >= 1000 && parsed <= 1e8) ||
            parsed != std::floor(parsed)) {
          std::cerr << "pcl_cocone_benchmark: --random takes sizes from 1000 to 1e8 "
                       "separated by commas, or none, not '"
                    << text << "'\n";
          return 1;
        }
        options.random_sizes.push_back(static_cast<std::size_t>(parsed));
      }
      if (text.empty()) {
        std::cerr << "pcl_cocone_benchmark: --random needs sizes or none\n";
        return 1;
      }
    }
    else if (arg == "--help" || arg == "-h") {
      usage(std::cout);
      return 0;
    }
    else {
      std::cerr << "pcl_cocone_benchmark: unknown argument " << arg << "\n";
      usage(std::cerr);
      return 1;
    }
  }
  if (!random_sizes_given)
    options.random_sizes = randomSizes(options.quick);
  const std::vector<std::string> sections = {"reconstruction", "boundary",
                                             "decimation"};
  if (!options.only.empty() &&
      std::find(sections.begin(), sections.end(), options.only) == sections.end()) {
    std::cerr
        << "pcl_cocone_benchmark: --only takes reconstruction, boundary or decimation\n";
    return 1;
  }

  Context context(options);
  const LoadSample load_before = sampleLoad();
  const std::string started = utcNow();
  const auto wall_start = std::chrono::steady_clock::now();

  std::vector<std::pair<std::string, std::pair<LoadSample, LoadSample>>> section_load;
  const auto run = [&](const std::string& name, void (*section)(Context&)) {
    if (!options.only.empty() && options.only != name)
      return;
    const LoadSample before = sampleLoad();
    section(context);
    section_load.push_back({name, {before, sampleLoad()}});
  };
  try {
    run("reconstruction", &runReconstructionSection);
    run("boundary", &runBoundarySection);
    run("decimation", &runDecimationSection);
  }
  catch (const std::exception& e) {
    std::cerr << "pcl_cocone_benchmark: " << e.what() << "\n";
    return 1;
  }
  const LoadSample load_after = sampleLoad();
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start)
          .count();

  // ---- the document: header, machine, commands, targets, then the sections -------
  Report head;
  std::ostringstream text;
  text
      << "# pcl_cocone benchmarks\n\n"
      << "Generated by `pcl_cocone_benchmark` (benchmarks/) on " << started << " in "
      << fixed(wall / 60.0, 1) << " minutes"
      << (options.quick
              ? " (**--quick**: no 1M inputs, no peers at 100k points and more)"
              : "")
      << (options.only.empty() ? "" : " (only the " + options.only + " section)")
      << (options.filter.empty() ? ""
                                 : " (inputs filtered by `" + options.filter + "`)")
      << ". Regenerate with `benchmarks/run_benchmarks.sh BUILD_DIR [--quick]`.\n\n"
      << "Algorithms: Dey, Giesen, Goswami, Hudson, Wenger, Zhao, \"Undersampling and "
         "Oversampling in Sample Based Shape Modeling\", IEEE Visualization 2001. The "
         "paper's columns are its Tables 1 and 2 (933 MHz Pentium III); they are shown for "
         "scale, not as a race.\n\n";
  text << "## Machine and load\n\n";
  Table machine({"fact", "value"});
  for (const auto& fact : machineFacts())
    machine.add({fact.first, fact.second});
  machine.add({"load average before / after",
               load_before.loadavg + " / " + load_after.loadavg});
  machine.add(
      {"steal share during the run", percent(stealShare(load_before, load_after))});
  machine.add({"busy share of all cores during the run",
               percent(busyShare(load_before, load_after))});
  for (const auto& s : section_load)
    machine.add({"section " + s.first,
                 "load " + s.second.first.loadavg + " -> " + s.second.second.loadavg +
                     ", steal " + percent(stealShare(s.second.first, s.second.second)) +
                     ", busy " + percent(busyShare(s.second.first, s.second.second))});
  text << machine.markdown() << "\n";
  text
      << "The machine is a shared 2-core VM with CPU steal and other jobs compiling: "
         "absolute times are noisy. Every Delaunay-based time is therefore also given as "
         "a ratio to the bare CGAL Delaunay triangulation of the same points measured in "
         "the same process run, and each time is the best of several isolated runs (3 up "
         "to 250k points, 2 above). The methods compared on an input take turns, round "
         "after round (the bare Delaunay, our core, ours, then each peer), so that a "
         "burst of load hits all of them alike; a peer is not run again once its runs "
         "add up to 15 s. Peak memory is the growth of the resident set of a forked "
         "child over the algorithm alone (VmHWM after the run minus VmRSS before, the "
         "peak reset through /proc/self/clear_refs); it includes the code pages of the "
         "shared libraries a method touches for the first time (a few MB, which "
         "dominates on small inputs).\n\n";
  text << "## Commands\n\n```\n";
  if (const char* invocation = std::getenv("PCL_COCONE_BENCH_INVOCATION"))
    text << invocation << "\n";
  text << relativeToSource(joinArguments(argc, argv)) << "\n```\n\n";
  text << "Data folder: `" << relativeToSource(options.data_directory) << "`.\n\n";
  if (!context.skipped.empty()) {
    text << "Skipped (missing or unreadable):\n\n";
    for (const std::string& s : context.skipped)
      text << "- " << s << "\n";
    text << "\n";
  }
  text << "## Targets\n\n";
  Table targets({"target", "goal", "verdict", "numbers"});
  for (const Target& t : context.targets)
    targets.add(
        {t.name, t.goal,
         t.status == 1 ? "**met**" : (t.status == 0 ? "**missed**" : "not evaluated"),
         t.evidence});
  text << targets.markdown() << "\n";
  text
      << "## Inputs\n\n"
      << "Spacing: mean distance from a sample to its nearest other sample; every distance "
         "below is in these units. Reference topology as given by the generator, by "
         "analyzeTriangleMesh on the file's faces, or, where the note says so, by what the "
         "samples cover (the cactus and the foot are open where no sample lies).\n\n"
      << inputsTable(context) << "\n";

  std::cout << "\n" << text.str();
  if (!options.markdown.empty()) {
    std::ofstream out(options.markdown);
    out << text.str() << context.report.text();
    if (!out) {
      std::cerr << "pcl_cocone_benchmark: cannot write " << options.markdown << "\n";
      return 1;
    }
    progress("wrote " + options.markdown);
  }
  return 0;
}
