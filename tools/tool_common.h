// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * Code shared by the command-line tools: option parsing and validation, loading,
 * timed stages, saving, and the one-line error exit. It follows the conventions of
 * PCL's own tools (pcl::console printing, "[done, X ms : N points]") but checks what
 * those leave unchecked: unknown options, bad or out-of-range values, failed writes
 * and failed computations all end the program with one line on stderr and exit code 1.
 * The reason of a failed computation or load is the library's own (the classes'
 * getErrorMessage(), the reader's error argument); PCL's console is quiet around those
 * calls unless -v is given (QuietPcl). The valid ranges of the classes' parameters are
 * the library's (pcl/cocone/parameters.h), so that tools and classes agree.
 */
#pragma once

#include <pcl/PCLPointCloud2.h>
#include <pcl/cocone/core/mesh_topology.h>
#include <pcl/cocone/parameters.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace pcl {
namespace cocone {
namespace tools {

// ---------------------------------------------------------------------------------
// Errors

/** \brief Prints "<program>: <message>" as one line on stderr and exits with code 1.
 * An open stage line on stdout is closed first ("[failed]"), so that the two streams
 * do not share a line on a terminal. Control characters in \a message are replaced so
 * that the promise of one line holds for any file name or argument, and bytes that are
 * not UTF-8 are escaped (pcl::cocone::utf8Escaped). The message shows
 * even when called within a QuietPcl scope. */
[[noreturn]] void fail(const std::string& message);

/** \brief Silences PCL's console while it lives, unless -v was given (to
 * CommandLine::parse): the level is set to L_ALWAYS, so that the PCL_ERROR and PCL_WARN
 * of the classes and of PCL's readers add no line to the tool's one-line error, and the
 * previous level is restored at the end of the scope. The reasons come from the
 * classes' getErrorMessage() and the reader's error argument instead. With -v nothing
 * changes: PCL's messages are shown, the PCL_DEBUG statistics and stage timings of the
 * classes and the core included (a failure then also shows the class's PCL_ERROR line
 * before the tool's). Keep the scope to the library call: the tool's own printing goes
 * through the same console. */
class QuietPcl
{
public:
  QuietPcl();
  ~QuietPcl();
  QuietPcl(const QuietPcl&) = delete;
  QuietPcl& operator=(const QuietPcl&) = delete;

private:
  pcl::console::VERBOSITY_LEVEL previous_;
};

// ---------------------------------------------------------------------------------
// Command line

enum class ValueKind
{
  flag,    ///< a switch without value
  real,    ///< a floating-point value
  integer, ///< a whole number
  choice,  ///< one word of Option::choices
};

/** \brief One command-line option. */
struct Option
{
  std::string name; ///< with its dash, e.g. "-rho"
  ValueKind kind = ValueKind::flag;
  std::string argument; ///< placeholder in the help, e.g. "R"
  std::string help;     ///< what it does
  double default_value = 0;
  std::string default_text; ///< the default as shown, e.g. "pi/8"; derived if empty
  /// the valid values, checked with ParameterRange::contains; for a parameter of the
  /// classes the library's constant, e.g. pcl::cocone::kRatioBoundRange
  ParameterRange range{};
  std::string range_text{}; ///< the range as shown, e.g. "(0, pi/2)"; derived if empty
  /// the words of a ValueKind::choice option; its value is the position of the word
  /// given, its default_value that of the default
  std::vector<std::string> choices{};
};

/** \brief A switch without value. */
Option flagOption(const std::string& name, const std::string& help);

/** \name Options that mean the same in every tool (same names, ranges and help); the
 * ranges are the library's kRatioBoundRange, kCoconeAngleRange, kNormalAngleRange. */
/** \{ */
Option ratioBoundOption(double default_value, const std::string& help);
Option coconeAngleOption();
Option normalAngleOption();
Option threadsOption();
/** \brief "-tiles N": the tile count of the Voronoi diagram (0: automatic). */
Option tilesOption();
Option denoiseOption();
Option verboseOption();
/** \} */

/** \brief What a tool is, for its help text and the checks of its arguments. */
struct ToolDescription
{
  std::string program; ///< executable name
  std::string purpose; ///< one sentence
  std::string output;  ///< placeholder of the output argument, e.g. "OUTPUT.pcd"
  std::vector<std::string> output_extensions; ///< lower case, with dot
  std::string output_help;                    ///< what the output file holds
};

/** \brief Parses and validates a tool's arguments: INPUT OUTPUT and the options in any
 * order. Every value is checked against its range here, before anything runs. */
class CommandLine
{
public:
  CommandLine(ToolDescription tool, std::vector<Option> options);

  /** \brief Parses \a argv. Prints the help and exits 0 on -h or --help; calls fail()
   * on a missing or extra argument, an unknown or repeated option, an option without
   * value, a value that is not a number (an integer where one is needed) or is out of
   * range, and an output path with an unsupported extension or in a missing folder.
   * With -v, raises PCL's console verbosity to L_DEBUG for the whole run (QuietPcl
   * then silences nothing). Ignores SIGXFSZ, so that a write past a file size limit
   * fails with its reason instead of ending the tool (see pcl::cocone::writeFile). */
  void parse(int argc, char** argv);

  const std::string&
  input() const
  {
    return input_;
  }
  const std::string&
  output() const
  {
    return output_;
  }
  /** \brief The output extension, lower case, e.g. ".ply". */
  std::string outputExtension() const;

  /** \brief The value of a real or integer option (its default when not given). */
  double value(const std::string& name) const;
  /** \brief The value of an integer option. */
  unsigned count(const std::string& name) const;
  /** \brief The word given to a ValueKind::choice option (its default when not given).
   */
  const std::string& choice(const std::string& name) const;
  /** \brief Whether a switch was given. */
  bool flag(const std::string& name) const;
  bool
  verbose() const
  {
    return flag("-v");
  }

  void printHelp() const;

private:
  const Option& option(const std::string& name) const;

  ToolDescription tool_;
  std::vector<Option> options_;
  std::vector<double> values_; // per option: parsed value or default
  std::vector<bool> given_;
  std::string input_;
  std::string output_;
};

/** \brief The mode given with denoiseOption() ("-denoise"). */
pcl::cocone::DenoiseMode denoiseMode(const CommandLine& cmd);

// ---------------------------------------------------------------------------------
// Stages

/** \brief A timed stage printed like PCL's tools: "Loading file " ... "[done, 12.3 ms :
 * 3000 points]". With -v the opening line ends at once, so that the classes' debug
 * lines do not land in the middle of it. */
class Stage
{
public:
  Stage(const std::string& action, const std::string& object);

  /** \brief Closes the line: "[done, X ms : <count> <unit>]". */
  void done(std::size_t count, const std::string& unit);

private:
  pcl::console::TicToc timer_;
};

/** \brief The work of a computeStage: returns the count for the closing "[done, X ms :
 * <count> <unit>]", or nothing when the algorithm failed (an empty result for a
 * non-empty input), then with the reason in its argument (the class's
 * getErrorMessage()). */
using StageWork = std::function<std::optional<std::size_t>(std::string& reason)>;

/** \brief Runs \a work as the timed stage "Computing <what>", PCL's console quiet
 * (QuietPcl). If it fails, the tool fails with "computing <what> failed: <reason>"
 * ("empty result" when \a work gave no reason). */
std::size_t
computeStage(const std::string& what, const std::string& unit, const StageWork& work);

/** \brief A progress callback for the classes (setProgressCallback) that shows the
 * share done as a percentage at the end of the open stage line, on a terminal only;
 * empty when stdout is not a terminal or with -v, so that logs and pipes see the same
 * lines as before. Never cancels. */
std::function<bool(double)> terminalProgress();

/** \brief Prints "<label>: <value>\n" in PCL's colours (label as info, value as value);
 * for the -v details. */
void printDetail(const std::string& label, const std::string& value);

/** \brief Prints "warning: <text>\n" (PCL's warning colour) when \a text is not empty:
 * for the classes' getWarningMessage(), which the tools' quiet PCL output would hide.
 */
void printWarning(const std::string& text);

/** \brief A number with up to \a digits significant digits, e.g. for parameters. */
std::string formatNumber(double value, int digits = 6);

/** \brief 100 * part / whole with one decimal, "0.0" for an empty whole. */
std::string formatPercent(std::size_t part, std::size_t whole);

// ---------------------------------------------------------------------------------
// Loading and saving

/** \brief Loads \a path with pcl::cocone::loadPointSamples as a timed stage, PCL's
 * console quiet (QuietPcl); fails with the reader's reason. With -v also prints the
 * fields. */
pcl::PCLPointCloud2 loadCloud(const std::string& path, bool verbose);

/** \brief The x, y, z of \a cloud (same width, height and order) for the classes. */
pcl::PointCloud<pcl::PointXYZ>::Ptr toXyz(const pcl::PCLPointCloud2& cloud);

/** \brief Number of points (width * height) of a cloud. */
std::size_t pointCount(const pcl::PCLPointCloud2& cloud);

/** \brief A copy of \a cloud without the fields named in \a names (nor padding), the
 * others packed in their order; \a cloud itself when it has none of them. */
pcl::PCLPointCloud2
withoutFields(const pcl::PCLPointCloud2& cloud, const std::vector<std::string>& names);

/** \brief Writes \a cloud as binary PCD to \a path as a timed stage (the header of
 * pcl::PCDWriter, the data as they are); fails with a one-line reason if the file
 * cannot be written completely (a partial file is removed). */
void saveCloud(const std::string& path, const pcl::PCLPointCloud2& cloud);

/** \brief Writes a triangle mesh to \a path as a timed stage, in the format of its
 * extension: .ply (binary little endian: float x y z, face list uchar int
 * vertex_indices), .vtk (legacy ASCII POLYDATA) or .obj. Coordinates are written with
 * enough digits to read back the same floats. Fails with a one-line reason if the file
 * cannot be written completely (a partial file is removed). */
void
saveMesh(const std::string& path, const std::vector<std::array<float, 3>>& vertices,
         const std::vector<TriangleIndices>& triangles);

} // namespace tools
} // namespace cocone
} // namespace pcl
