// SPDX-License-Identifier: GPL-3.0-or-later
#include "tool_common.h"

#include <pcl/cocone/core/denoise.h>
#include <pcl/cocone/io/point_io.h>
#include <pcl/cocone/io/writers.h>
#include <pcl/common/io.h>
#include <pcl/console/print.h>
#include <pcl/conversions.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>

#include <unistd.h>

namespace pcl {
namespace cocone {
namespace tools {

namespace {

namespace fs = std::filesystem;
using pcl::console::print_error;
using pcl::console::print_highlight;
using pcl::console::print_info;
using pcl::console::print_value;

// Process-wide console state: fail() must know whether a stage line is open on stdout,
// and the name to put in front of its message; Stage and QuietPcl whether -v was given.
std::string program_name = "error";
bool stage_open = false;
bool verbose_run = false;
// Characters of a percentage shown at the end of the open stage line
// (terminalProgress).
int progress_shown = 0;

/** Erases the percentage shown at the end of the stage line, if any. */
void
eraseProgress()
{
  if (progress_shown == 0)
    return;
  std::printf("%.*s%*s%.*s", progress_shown, "\b\b\b\b\b", progress_shown, "",
              progress_shown, "\b\b\b\b\b");
  std::fflush(stdout);
  progress_shown = 0;
}

constexpr std::size_t help_column = 24; // where option descriptions start
constexpr std::size_t help_width = 88;

/** \a text with control characters replaced, so that it fits on one line. */
std::string
oneLine(std::string text)
{
  for (char& c : text)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      c = (c == '\t') ? ' ' : '?';
  return text;
}

std::string
inQuotes(const std::string& text)
{
  return "'" + text + "'";
}

std::string
lowerCase(std::string text)
{
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// Spaces that printWrapped must not break at, e.g. inside "(0, 10]".
constexpr char kGlue = '\x1f';

std::string
unbreakable(std::string text)
{
  std::replace(text.begin(), text.end(), ' ', kGlue);
  return text;
}

/** Prints \a text from column \a indent on, wrapped at help_width; the first line
 * continues wherever the cursor is (\a column). */
void
printWrapped(const std::string& text, std::size_t column, std::size_t indent)
{
  std::string line;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos)
      end = text.size();
    const std::string word = text.substr(start, end - start);
    if (!line.empty() && column + line.size() + 1 + word.size() > help_width) {
      std::replace(line.begin(), line.end(), kGlue, ' ');
      print_info("%s\n%s", line.c_str(), std::string(indent, ' ').c_str());
      column = indent;
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
    start = end + 1;
  }
  std::replace(line.begin(), line.end(), kGlue, ' ');
  print_info("%s\n", line.c_str());
}

std::string
defaultText(const Option& option)
{
  if (!option.default_text.empty())
    return option.default_text;
  if (option.kind == ValueKind::flag)
    return "off";
  return formatNumber(option.default_value);
}

/** The valid range as shown in the help and the errors, e.g. "(0, 10]". */
std::string
rangeText(const Option& option)
{
  return option.range_text.empty() ? option.range.text() : option.range_text;
}

/** The value \a text of \a option, checked; fails with the option's name otherwise. */
double
parseValue(const Option& option, const std::string& text)
{
  double value = 0;
  if (option.kind == ValueKind::choice) {
    const auto word = std::find(option.choices.begin(), option.choices.end(), text);
    if (word == option.choices.end())
      fail(option.name + ": " + inQuotes(text) + " is not one of " + rangeText(option));
    return static_cast<double>(word - option.choices.begin());
  }
  if (option.kind == ValueKind::integer) {
    long long number = 0;
    const char* last = text.data() + text.size();
    const auto [end, ec] = std::from_chars(text.data(), last, number);
    if (text.empty() || ec != std::errc() || end != last)
      fail(option.name + ": " + inQuotes(text) +
           " is not an integer (expected an integer in " + rangeText(option) + ")");
    value = static_cast<double>(number);
  }
  else {
    // strtod rather than PCL's parse_argument, which takes "abc" for 0 and "1x" for 1.
    char* end = nullptr;
    errno = 0;
    value = std::strtod(text.c_str(), &end);
    const bool whole = !text.empty() &&
                       !std::isspace(static_cast<unsigned char>(text[0])) && end &&
                       *end == '\0';
    if (!whole || errno == ERANGE || !std::isfinite(value))
      fail(option.name + ": " + inQuotes(text) +
           " is not a number (expected a value in " + rangeText(option) + ")");
  }
  if (!option.range.contains(value))
    fail(option.name + ": " + text + " is outside the valid range " +
         rangeText(option));
  return value;
}

std::string
fieldList(const pcl::PCLPointCloud2& cloud)
{
  std::string list;
  for (const pcl::PCLPointField& field : cloud.fields)
    if (field.name != "_")
      list += (list.empty() ? "" : " ") + field.name;
  return list;
}

} // namespace

// ---------------------------------------------------------------------------------

void
fail(const std::string& message)
{
  // Even from within a QuietPcl scope, the message (and "[failed]") must show.
  if (pcl::console::getVerbosityLevel() < pcl::console::L_INFO)
    pcl::console::setVerbosityLevel(pcl::console::L_INFO);
  eraseProgress();
  if (stage_open) {
    print_info("[failed]\n");
    stage_open = false;
  }
  std::fflush(stdout);
  print_error("%s: %s\n", program_name.c_str(), utf8Escaped(oneLine(message)).c_str());
  std::exit(EXIT_FAILURE);
}

QuietPcl::QuietPcl() : previous_(pcl::console::getVerbosityLevel())
{
  if (!verbose_run)
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
}

QuietPcl::~QuietPcl()
{
  pcl::console::setVerbosityLevel(previous_);
}

// ---------------------------------------------------------------------------------

Option
ratioBoundOption(double default_value, const std::string& help)
{
  return {"-rho", ValueKind::real, "R", help, default_value, "", kRatioBoundRange};
}

Option
coconeAngleOption()
{
  return {"-theta",
          ValueKind::real,
          "T",
          "cocone angle in radians: the cocone of a sample is the part of its Voronoi "
          "cell within T of the plane orthogonal to its pole vector",
          M_PI / 8,
          "pi/8 = 0.3927",
          kCoconeAngleRange,
          "(0, pi/2)"};
}

Option
normalAngleOption()
{
  return {"-alpha",
          ValueKind::real,
          "A",
          "largest angle in radians between the pole lines of neighbouring flat "
          "samples; smaller values flag more samples near curved or sharp regions",
          M_PI / 6,
          "pi/6 = 0.5236",
          kNormalAngleRange,
          "(0, pi/2]"};
}

Option
threadsOption()
{
  return {"-threads",
          ValueKind::integer,
          "N",
          "number of threads",
          0,
          "0 = every core",
          ParameterRange{0, 4096, false, false}};
}

Option
tilesOption()
{
  return {"-tiles",
          ValueKind::integer,
          "N",
          "build the Voronoi diagram in N tiles run in parallel, each with a halo that "
          "makes its stars exact: the output is the same for any N (docs/scaling.md)",
          0,
          "0 = automatic",
          ParameterRange{0, 1u << 20, false, false}};
}

Option
denoiseOption()
{
  Option option;
  option.name = "-denoise";
  option.kind = ValueKind::choice;
  option.argument = "MODE";
  option.help = "scanner noise: build the Voronoi diagram on a smoothed copy of the "
                "samples (the output keeps the input points); auto smooths when the "
                "measured noise exceeds " +
                formatNumber(pcl::cocone::kNoiseThreshold) +
                " sample spacings (docs/noise.md)";
  option.choices = {"auto", "on", "off"};
  option.default_value = 0;
  option.default_text = "auto";
  option.range_text = "auto|on|off";
  return option;
}

Option
flagOption(const std::string& name, const std::string& help)
{
  Option option;
  option.name = name;
  option.help = help;
  return option;
}

Option
verboseOption()
{
  return flagOption("-v",
                    "verbose: parameters, the time of every stage and the algorithms' "
                    "statistics");
}

// ---------------------------------------------------------------------------------

CommandLine::CommandLine(ToolDescription tool, std::vector<Option> options)
  : tool_(std::move(tool)), options_(std::move(options))
{
  program_name = tool_.program;
  for (const Option& option : options_)
    values_.push_back(option.default_value);
  given_.assign(options_.size(), false);
}

void
CommandLine::parse(int argc, char** argv)
{
  // Past a file size limit (ulimit -f) a write raises SIGXFSZ, which would end the tool
  // with a core dump and leave the temporary file of the write behind; ignored, the
  // write fails with EFBIG and the tool says so in its one line, having removed it.
  std::signal(SIGXFSZ, SIG_IGN);

  // Help wins over everything else on the line, as in PCL's tools.
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "-h") == 0 || std::strcmp(argv[i], "--help") == 0) {
      printHelp();
      std::exit(EXIT_SUCCESS);
    }

  const auto find = [this](const std::string& name) {
    return std::find_if(options_.begin(), options_.end(),
                        [&](const Option& o) { return o.name == name; });
  };
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.size() < 2 || arg[0] != '-') {
      positional.push_back(arg);
      continue;
    }
    // Every dash word must be an option: pcl::console::parse_argument looks only for
    // the names it is asked about, so a typo like -theat is silently ignored there.
    const auto it = find(arg);
    if (it == options_.end())
      fail("unknown option " + inQuotes(arg) + " (see " + tool_.program + " -h)");
    const std::size_t k = static_cast<std::size_t>(it - options_.begin());
    if (given_[k])
      fail(arg + " is given more than once");
    given_[k] = true;
    if (it->kind == ValueKind::flag)
      continue;
    if (i + 1 >= argc || find(argv[i + 1]) != options_.end())
      fail(arg + " needs a value: " + it->argument + " in " + rangeText(*it));
    values_[k] = parseValue(*it, argv[++i]);
  }

  if (positional.size() < 2)
    fail("missing arguments: expected INPUT " + tool_.output + " (see " +
         tool_.program + " -h)");
  if (positional.size() > 2)
    fail("unexpected argument " + inQuotes(positional[2]) + ": expected only INPUT " +
         tool_.output);
  input_ = positional[0];
  output_ = positional[1];

  // The output is checked now rather than after minutes of computing.
  const std::string extension = outputExtension();
  if (std::find(tool_.output_extensions.begin(), tool_.output_extensions.end(),
                extension) == tool_.output_extensions.end()) {
    std::string known;
    for (const std::string& e : tool_.output_extensions)
      known += (known.empty() ? "" : ", ") + e;
    fail("unsupported output format " + inQuotes(output_) + " (expected " + known +
         ")");
  }
  std::error_code ec;
  const fs::path folder = fs::path(output_).parent_path();
  if (!folder.empty() && !fs::is_directory(folder, ec))
    fail("cannot write " + output_ + ": folder " + folder.string() + " does not exist");
  if (fs::is_directory(output_, ec))
    fail("cannot write " + output_ + ": it is a folder");

  if (verbose()) {
    verbose_run = true;
    // The classes and the core report their statistics and stage timings with
    // PCL_DEBUG.
    pcl::console::setVerbosityLevel(pcl::console::L_DEBUG);
  }
}

std::string
CommandLine::outputExtension() const
{
  const std::string extension = fs::path(output_).extension().string();
  return lowerCase(extension);
}

const Option&
CommandLine::option(const std::string& name) const
{
  for (const Option& o : options_)
    if (o.name == name)
      return o;
  // A tool asking for an option it did not declare is a programming error.
  fail("internal error: no option " + name);
}

double
CommandLine::value(const std::string& name) const
{
  const Option& o = option(name);
  return values_[static_cast<std::size_t>(&o - options_.data())];
}

unsigned
CommandLine::count(const std::string& name) const
{
  return static_cast<unsigned>(value(name));
}

const std::string&
CommandLine::choice(const std::string& name) const
{
  const Option& o = option(name);
  return o.choices[static_cast<std::size_t>(value(name))];
}

pcl::cocone::DenoiseMode
denoiseMode(const CommandLine& cmd)
{
  pcl::cocone::DenoiseMode mode = pcl::cocone::DenoiseMode::automatic;
  pcl::cocone::parseDenoiseMode(cmd.choice("-denoise"), mode);
  return mode;
}

bool
CommandLine::flag(const std::string& name) const
{
  const Option& o = option(name);
  return given_[static_cast<std::size_t>(&o - options_.data())];
}

void
CommandLine::printHelp() const
{
  print_info("%s: ", tool_.program.c_str());
  printWrapped(tool_.purpose, tool_.program.size() + 2, 2);
  print_info("\nSyntax is: %s INPUT %s <options>\n", tool_.program.c_str(),
             tool_.output.c_str());
  const auto item = [](const std::string& name, const std::string& text) {
    std::string head = "  " + name;
    if (head.size() + 1 < help_column)
      head.resize(help_column, ' ');
    else
      head += ' ';
    print_info("%s", head.c_str());
    printWrapped(text, head.size(), help_column);
  };
  item("INPUT",
       "the samples: .pcd .ply .obj .off .xyz .pts .txt .las (a mesh's vertices "
       "are the samples; NaN points are skipped)");
  item(tool_.output, tool_.output_help);
  print_info("\nwhere options are:\n");
  for (const Option& o : options_) {
    std::string text = o.help + " (default " + unbreakable(defaultText(o));
    if (o.kind != ValueKind::flag)
      text += "; valid " + unbreakable(rangeText(o));
    item(o.name + (o.argument.empty() ? "" : " " + o.argument), text + ")");
  }
  item("-h, --help", "print this help and exit");
  print_info("\nAngles are in radians, as everywhere in PCL (pi/8 = 0.3927, pi/6 = "
             "0.5236, pi/2 = 1.5708).\n");
}

// ---------------------------------------------------------------------------------

Stage::Stage(const std::string& action, const std::string& object)
{
  print_highlight("%s ", action.c_str());
  print_value("%s", object.c_str());
  print_info(verbose_run ? " ...\n" : " ");
  std::fflush(stdout);
  stage_open = !verbose_run;
  timer_.tic();
}

void
Stage::done(std::size_t count, const std::string& unit)
{
  eraseProgress();
  print_info("[done, ");
  print_value("%g", timer_.toc());
  print_info(" ms : ");
  print_value("%zu", count);
  print_info(" %s]\n", unit.c_str());
  stage_open = false;
}

std::function<bool(double)>
terminalProgress()
{
  // Only where a person watches: on a terminal, with the stage line open (not with -v,
  // whose stage lines end at once). Piped or redirected output stays as it was.
  if (verbose_run || !isatty(fileno(stdout)))
    return nullptr;
  return [last = -1](double share) mutable {
    const int percent = static_cast<int>(100 * share);
    if (percent == last || !stage_open)
      return true;
    last = percent;
    eraseProgress();
    progress_shown = std::printf("%d%%", percent);
    std::fflush(stdout);
    return true;
  };
}

std::size_t
computeStage(const std::string& what, const std::string& unit, const StageWork& work)
{
  Stage stage("Computing", what);
  std::string reason;
  const std::optional<std::size_t> count = [&] {
    const QuietPcl quiet;
    return work(reason);
  }();
  if (!count)
    fail("computing " + what +
         " failed: " + (reason.empty() ? "empty result" : reason));
  stage.done(*count, unit);
  return *count;
}

void
printDetail(const std::string& label, const std::string& value)
{
  print_info("  %s: ", label.c_str());
  print_value("%s\n", value.c_str());
}

void
printWarning(const std::string& text)
{
  if (!text.empty())
    pcl::console::print_warn("warning: %s\n", text.c_str());
}

std::string
formatNumber(double value, int digits)
{
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

std::string
formatPercent(std::size_t part, std::size_t whole)
{
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f",
                whole ? 100.0 * static_cast<double>(part) / static_cast<double>(whole)
                      : 0.0);
  return buffer;
}

// ---------------------------------------------------------------------------------

pcl::PCLPointCloud2
loadCloud(const std::string& path, bool verbose)
{
  Stage stage("Loading", path);
  pcl::PCLPointCloud2 cloud;
  std::string error;
  const bool loaded = [&] {
    const QuietPcl quiet;
    return loadPointSamples(path, cloud, &error);
  }();
  if (!loaded)
    fail(error.empty() ? "cannot read " + path : error);
  stage.done(pointCount(cloud), "points");
  if (verbose)
    printDetail("Available dimensions", fieldList(cloud));
  return cloud;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr
toXyz(const pcl::PCLPointCloud2& cloud)
{
  auto xyz = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  pcl::fromPCLPointCloud2(cloud, *xyz);
  return xyz;
}

std::size_t
pointCount(const pcl::PCLPointCloud2& cloud)
{
  return static_cast<std::size_t>(cloud.width) * cloud.height;
}

pcl::PCLPointCloud2
withoutFields(const pcl::PCLPointCloud2& cloud, const std::vector<std::string>& names)
{
  const auto dropped = [&](const pcl::PCLPointField& f) {
    return f.name == "_" ||
           std::find(names.begin(), names.end(), f.name) != names.end();
  };
  if (std::none_of(cloud.fields.begin(), cloud.fields.end(), dropped))
    return cloud;

  pcl::PCLPointCloud2 out;
  out.header = cloud.header;
  out.width = cloud.width;
  out.height = cloud.height;
  out.is_bigendian = cloud.is_bigendian;
  out.is_dense = cloud.is_dense;
  std::vector<const pcl::PCLPointField*> kept;
  for (const pcl::PCLPointField& f : cloud.fields)
    if (!dropped(f)) {
      kept.push_back(&f);
      pcl::PCLPointField packed = f;
      packed.offset = out.point_step;
      out.fields.push_back(packed);
      out.point_step += f.count * pcl::getFieldSize(f.datatype);
    }
  out.row_step = out.point_step * out.width;
  const std::size_t n = pointCount(cloud);
  out.data.resize(n * out.point_step);
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t k = 0; k < kept.size(); ++k) {
      const pcl::PCLPointField& from = *kept[k];
      std::memcpy(&out.data[p * out.point_step + out.fields[k].offset],
                  &cloud.data[p * cloud.point_step + from.offset],
                  from.count * pcl::getFieldSize(from.datatype));
    }
  return out;
}

void
saveCloud(const std::string& path, const pcl::PCLPointCloud2& cloud)
{
  Stage stage("Saving", path);
  std::string error;
  if (!pcl::cocone::saveCloud(path, cloud, &error))
    fail(error);
  stage.done(pointCount(cloud), "points");
}

void
saveMesh(const std::string& path, const std::vector<std::array<float, 3>>& vertices,
         const std::vector<TriangleIndices>& triangles)
{
  Stage stage("Saving", path);
  std::string error;
  if (!pcl::cocone::saveMesh(path, vertices, triangles, program_name, &error))
    fail(error);
  stage.done(triangles.size(), "triangles");
}

} // namespace tools
} // namespace cocone
} // namespace pcl
