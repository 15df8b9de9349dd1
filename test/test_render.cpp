// SPDX-License-Identifier: GPL-3.0-or-later
// pcl_cocone_render run as a user runs it: as a process under xvfb-run, on a mesh and
// clouds written here. The PNGs it writes are checked without an image library: the
// size from the IHDR chunk, the pixels by inflating IDAT with zlib and undoing the
// per-row filters, so that a blank (all background) picture is caught.
#include "support/process.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

namespace fs = std::filesystem;
using Args = std::vector<std::string>;
using pcl::cocone::test::expectOneLineFailure;
using pcl::cocone::test::expectSuccess;
using pcl::cocone::test::readText;
using pcl::cocone::test::runTool;
using pcl::cocone::test::shellQuote;
using pcl::cocone::test::ToolRun;

// The build passes the folder of the tool and, when found, the path of xvfb-run.
#ifdef PCL_COCONE_TOOL_DIR
const char* const kToolDir = PCL_COCONE_TOOL_DIR;
#else
const char* const kToolDir = nullptr;
#endif
#ifdef PCL_COCONE_XVFB_RUN
const char* const kXvfbRun = PCL_COCONE_XVFB_RUN;
#else
const char* const kXvfbRun = nullptr;
#endif

const std::string kTool = "pcl_cocone_render";

// --- a small mesh and clouds ---------------------------------------------------------

using Vec = std::array<double, 3>;
using Tri = std::array<int, 3>;

Vec
unit(const Vec& v)
{
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return {v[0] / n, v[1] / n, v[2] / n};
}

/** The unit icosphere: the icosahedron with every triangle split into four,
 * \a levels times, the new vertices pushed onto the sphere. */
void
icosphere(int levels, std::vector<Vec>& vertices, std::vector<Tri>& triangles)
{
  const double t = (1 + std::sqrt(5.0)) / 2;
  vertices = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
              {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
              {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (Vec& v : vertices)
    v = unit(v);
  triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
               {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
               {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
               {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> middle;
    const auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto found = middle.find(key);
      if (found != middle.end())
        return found->second;
      const Vec& p = vertices[a];
      const Vec& q = vertices[b];
      vertices.push_back(unit({p[0] + q[0], p[1] + q[1], p[2] + q[2]}));
      const int id = static_cast<int>(vertices.size()) - 1;
      middle[key] = id;
      return id;
    };
    std::vector<Tri> finer;
    for (const Tri& f : triangles) {
      const int ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]),
                ca = midpoint(f[2], f[0]);
      finer.push_back({f[0], ab, ca});
      finer.push_back({f[1], bc, ab});
      finer.push_back({f[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    triangles = std::move(finer);
  }
}

/** The body that OFF and ASCII PLY share: a line "x y z" per vertex, then a line
 * "3 a b c" per triangle. */
void
writeMeshBody(std::ostream& out, const std::vector<Vec>& vertices,
              const std::vector<Tri>& triangles)
{
  for (const Vec& v : vertices)
    out << v[0] << " " << v[1] << " " << v[2] << "\n";
  for (const Tri& t : triangles)
    out << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
}

// --- reading PNG ---------------------------------------------------------------------

std::uint32_t
bigEndian(const std::string& bytes, std::size_t at)
{
  return (std::uint32_t(std::uint8_t(bytes[at])) << 24) |
         (std::uint32_t(std::uint8_t(bytes[at + 1])) << 16) |
         (std::uint32_t(std::uint8_t(bytes[at + 2])) << 8) |
         std::uint32_t(std::uint8_t(bytes[at + 3]));
}

/** An 8-bit RGB(A) PNG, decoded: one RGB triple per pixel, rows top to bottom. */
struct Image
{
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  int colour_type = -1;
  std::vector<std::array<std::uint8_t, 3>> pixels;
  std::string error; ///< why it could not be decoded; empty on success
};

int
paeth(int a, int b, int c)
{
  const int p = a + b - c;
  const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  if (pa <= pb && pa <= pc)
    return a;
  return pb <= pc ? b : c;
}

Image
readPng(const fs::path& path)
{
  Image image;
  const std::string bytes = readText(path);
  static const std::string signature("\x89PNG\r\n\x1a\n", 8);
  if (bytes.compare(0, 8, signature) != 0) {
    image.error = "not a PNG signature";
    return image;
  }
  std::string idat;
  int bit_depth = 0, interlace = 0;
  bool header = false;
  for (std::size_t at = 8; at + 12 <= bytes.size();) {
    const std::uint32_t length = bigEndian(bytes, at);
    const std::string type = bytes.substr(at + 4, 4);
    if (at + 12 + length > bytes.size()) {
      image.error = "truncated chunk " + type;
      return image;
    }
    const std::size_t data = at + 8;
    if (type == "IHDR" && length >= 13) {
      header = true;
      image.width = bigEndian(bytes, data);
      image.height = bigEndian(bytes, data + 4);
      bit_depth = std::uint8_t(bytes[data + 8]);
      image.colour_type = std::uint8_t(bytes[data + 9]);
      interlace = std::uint8_t(bytes[data + 12]);
    }
    else if (type == "IDAT")
      idat.append(bytes, data, length);
    else if (type == "IEND")
      break;
    at += 12 + length;
  }
  if (!header) {
    image.error = "no IHDR chunk";
    return image;
  }
  if (bit_depth != 8 || (image.colour_type != 2 && image.colour_type != 6) ||
      interlace != 0) {
    image.error = "not 8-bit non-interlaced RGB or RGBA (depth " +
                  std::to_string(bit_depth) + ", colour type " +
                  std::to_string(image.colour_type) + ")";
    return image;
  }

  const std::size_t channels = image.colour_type == 6 ? 4 : 3;
  const std::size_t stride = image.width * channels;
  std::vector<std::uint8_t> raw((stride + 1) * image.height);
  uLongf raw_size = static_cast<uLongf>(raw.size());
  if (uncompress(raw.data(), &raw_size, reinterpret_cast<const Bytef*>(idat.data()),
                 static_cast<uLong>(idat.size())) != Z_OK ||
      raw_size != raw.size()) {
    image.error = "cannot inflate IDAT";
    return image;
  }

  // Undo the filters row by row (PNG spec, section 9): each byte is predicted from the
  // byte one pixel to the left (a), above (b) and above-left (c).
  std::vector<std::uint8_t> previous(stride, 0), row(stride);
  image.pixels.reserve(std::size_t(image.width) * image.height);
  for (std::uint32_t y = 0; y < image.height; ++y) {
    const std::uint8_t* line = &raw[y * (stride + 1)];
    const int filter = line[0];
    for (std::size_t i = 0; i < stride; ++i) {
      const int x = line[1 + i];
      const int a = i >= channels ? row[i - channels] : 0;
      const int b = previous[i];
      const int c = i >= channels ? previous[i - channels] : 0;
      int value = 0;
      switch (filter) {
      case 0:
        value = x;
        break;
      case 1:
        value = x + a;
        break;
      case 2:
        value = x + b;
        break;
      case 3:
        value = x + (a + b) / 2;
        break;
      case 4:
        value = x + paeth(a, b, c);
        break;
      default:
        image.error = "unknown filter type " + std::to_string(filter);
        image.pixels.clear();
        return image;
      }
      row[i] = static_cast<std::uint8_t>(value & 0xff);
    }
    for (std::uint32_t x = 0; x < image.width; ++x)
      image.pixels.push_back(
          {row[x * channels], row[x * channels + 1], row[x * channels + 2]});
    std::swap(previous, row);
  }
  return image;
}

/** Shares of the pixels that are not background (white), and that are red. */
struct Coverage
{
  double drawn = 0;
  double red = 0;
  double grey = 0; ///< neutral, clearly darker than the background
};

Coverage
coverage(const Image& image)
{
  Coverage c;
  if (image.pixels.empty())
    return c;
  std::size_t drawn = 0, red = 0, grey = 0;
  for (const auto& p : image.pixels) {
    const int r = p[0], g = p[1], b = p[2];
    if (r < 250 || g < 250 || b < 250)
      ++drawn;
    if (r > 150 && g < 90 && b < 90)
      ++red;
    if (std::max({r, g, b}) - std::min({r, g, b}) < 12 && r < 220)
      ++grey;
  }
  const double n = static_cast<double>(image.pixels.size());
  c.drawn = static_cast<double>(drawn) / n;
  c.red = static_cast<double>(red) / n;
  c.grey = static_cast<double>(grey) / n;
  return c;
}

// --- the fixture ---------------------------------------------------------------------

class Render : public ::testing::Test
{
protected:
  static void
  SetUpTestSuite()
  {
    dir_ = fs::path(::testing::TempDir()) /
           ("pcl_cocone_render_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);

    std::vector<Vec> vertices;
    std::vector<Tri> triangles;
    icosphere(3, vertices, triangles); // 642 vertices, 1280 triangles

    std::ostringstream off;
    off << "OFF\n" << vertices.size() << " " << triangles.size() << " 0\n";
    writeMeshBody(off, vertices, triangles);
    writeText("icosphere.off", off.str());

    std::ostringstream ply;
    ply << "ply\nformat ascii 1.0\nelement vertex " << vertices.size()
        << "\nproperty float x\nproperty float y\nproperty float z\nelement face "
        << triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
    writeMeshBody(ply, vertices, triangles);
    writeText("icosphere.ply", ply.str());

    // The vertices as a cloud whose band around the equator is flagged, in the layout
    // pcl_boundary_sample_estimation writes (x y z boundary_point, one row per point).
    std::ostringstream pcd;
    pcd << "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n"
           "FIELDS x y z boundary_point\nSIZE 4 4 4 1\nTYPE F F F U\nCOUNT 1 1 1 1\n"
           "WIDTH "
        << vertices.size() << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS "
        << vertices.size() << "\nDATA ascii\n";
    for (const Vec& v : vertices)
      pcd << v[0] << " " << v[1] << " " << v[2] << " "
          << (std::abs(v[1]) < 0.15 ? 1 : 0) << "\n";
    writeText("flagged.pcd", pcd.str());

    std::ostringstream xyz;
    for (const Vec& v : vertices)
      xyz << v[0] << " " << v[1] << " " << v[2] << "\n";
    writeText("cloud.xyz", xyz.str());
  }

  void
  SetUp() override
  {
    if (!kToolDir)
      GTEST_SKIP() << "pcl_cocone_render is not built";
  }

  static void
  TearDownTestSuite()
  {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  static fs::path
  path(const std::string& name)
  {
    return dir_ / name;
  }

  static void
  writeText(const std::string& name, const std::string& text)
  {
    std::ofstream(path(name), std::ios::binary) << text;
  }

  /** Runs the tool with \a args; under xvfb-run -a with \a display, and without any X
   * display (DISPLAY unset) otherwise. */
  static ToolRun
  run(const Args& args, bool display)
  {
    static int counter = 0;
    const std::string id = std::to_string(counter++);
    const fs::path out = path("stdout_" + id), err = path("stderr_" + id);
    const std::string launcher =
        display ? shellQuote(kXvfbRun) + " -a " : "env -u DISPLAY ";
    ToolRun result;
    // xvfb-run -a can lose the race for a display number to another test starting
    // Xvfb at the same moment, or fail to clean up its temporary folder on a busy
    // machine; both are xvfb-run's own errors, not the tool's: try again.
    for (int attempt = 0; attempt < 3; ++attempt) {
      result = runTool(launcher, fs::path(kToolDir) / kTool, args, out, err);
      if (!display || (result.err.find("Xvfb failed to start") == std::string::npos &&
                       result.err.find("xvfb-run: error") == std::string::npos))
        break;
    }
    return result;
  }

  /** Renders under Xvfb (skipping when xvfb-run is not installed). */
  static ToolRun
  render(const Args& args)
  {
    return run(args, true);
  }

  static fs::path dir_;
};

fs::path Render::dir_;

#define REQUIRE_XVFB()                                                                 \
  if (!kXvfbRun)                                                                       \
  GTEST_SKIP() << "xvfb-run was not found when the tests were configured (apt-get "    \
                  "install xvfb): rendering needs an X display"

/** Checks the size of the PNG at \a file and that it is not blank; returns it. */
Image
expectPicture(const fs::path& file, std::uint32_t width, std::uint32_t height)
{
  EXPECT_TRUE(fs::is_regular_file(file)) << file;
  const Image image = readPng(file);
  EXPECT_EQ(image.error, "");
  EXPECT_EQ(image.width, width);
  EXPECT_EQ(image.height, height);
  EXPECT_EQ(image.pixels.size(), std::size_t(width) * height);
  const Coverage c = coverage(image);
  EXPECT_GT(c.drawn, 0.05) << "the picture is (nearly) blank";
  EXPECT_LT(c.drawn, 0.80) << "the picture is (nearly) all foreground";
  return image;
}

// --- arguments -----------------------------------------------------------------------

TEST_F(Render, HelpListsEveryOptionAndHowToRunHeadless)
{
  for (const std::string help : {"-h", "--help"}) {
    // Help needs no display, and wins over everything else on the line.
    const ToolRun r = run({"missing.ply", "-foo", help}, false);
    expectSuccess(r);
    EXPECT_NE(r.out.find("Syntax is: " + kTool), std::string::npos) << r.out;
    for (const std::string name :
         {"-boundary B.pcd", "-wireframe", "-width W", "-height H", "-camera",
          "-azimuth DEG", "-elevation DEG", "-point_size S", "-v"})
      EXPECT_NE(r.out.find("  " + name + " "), std::string::npos) << name;
    EXPECT_NE(r.out.find("default 640"), std::string::npos);
    EXPECT_NE(r.out.find("default 480"), std::string::npos);
    EXPECT_NE(r.out.find("xvfb-run -a " + kTool), std::string::npos);
  }
}

TEST_F(Render, MissingOrBadInputFailsWithOneLine)
{
  REQUIRE_XVFB();
  writeText("garbage.vtk", "garbage\n");
  writeText("bad_face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  for (const std::string name :
       {"missing.ply", "missing.vtk", "missing.pcd", "garbage.vtk", "bad_face.off"}) {
    SCOPED_TRACE(name);
    const ToolRun r = render({path(name).string(), path("missing.png").string()});
    expectOneLineFailure(r, name);
    EXPECT_FALSE(fs::exists(path("missing.png")));
  }
}

TEST_F(Render, BadOptionsFailWithOneLineBeforeLoading)
{
  const std::string in = path("icosphere.off").string();
  const std::string out = path("bad.png").string();
  const std::vector<std::pair<Args, std::string>> cases{
      {{in, out, "-width", "abc"}, "-width"},
      {{in, out, "-width", "0"}, "-width"},
      {{in, out, "-height", "1.5"}, "-height"},
      {{in, out, "-azimuth", "north"}, "-azimuth"},
      {{in, out, "-elevation", "90"}, "-elevation"},
      {{in, out, "-point_size", "-2"}, "-point_size"},
      {{in, out, "-camera", "1,2,3"}, "-camera"},
      {{in, out, "-camera", "0,0,1,0,0,0,0,1,x"}, "-camera"},
      {{in, out, "-camera", "0,0,1,0,0,0,0,0,1"}, "-camera"}, // up along the view
      {{in, out, "-camera"}, "-camera"},
      {{in, out, "-boundary"}, "-boundary"},
      {{in, out, "-boundary", "a.pcd", "-boundary", "b.pcd"}, "-boundary"},
      {{in, out, "-wireframe", "-wireframe"}, "-wireframe"},
      {{in, out, "-foo"}, "-foo"},
      {{in}, "missing arguments"},
      {{in, path("picture.jpg").string()}, "picture.jpg"},
      {{in, path("no_folder/picture.png").string()}, "no_folder"},
  };
  for (const auto& [args, expected] : cases) {
    std::string line;
    for (const std::string& a : args)
      line += " " + a;
    SCOPED_TRACE(line);
    const ToolRun r = run(args, false);
    expectOneLineFailure(r, expected);
    EXPECT_EQ(r.out.find("Loading"), std::string::npos) << r.out;
  }
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Render, BadBoundaryFileFailsWithOneLine)
{
  REQUIRE_XVFB();
  // A cloud without boundary_point field.
  const ToolRun r = render({path("icosphere.off").string(), path("b.png").string(),
                            "-boundary", path("cloud.xyz").string()});
  expectOneLineFailure(r, "boundary_point");
  EXPECT_FALSE(fs::exists(path("b.png")));
}

TEST_F(Render, WithoutDisplayFailsWithOneLineNamingXvfbRun)
{
  const ToolRun r =
      run({path("icosphere.off").string(), path("headless.png").string()}, false);
  expectOneLineFailure(r, "xvfb-run -a");
  EXPECT_EQ(r.out.find("Loading"), std::string::npos) << "checked before loading";
  EXPECT_FALSE(fs::exists(path("headless.png")));
}

// --- pictures ------------------------------------------------------------------------

TEST_F(Render, RendersAShadedMesh)
{
  REQUIRE_XVFB();
  const fs::path out = path("mesh.png");
  const ToolRun r = render({path("icosphere.off").string(), out.string(), "-width",
                            "320", "-height", "240"});
  expectSuccess(r);
  EXPECT_NE(r.out.find("Camera: -camera "), std::string::npos) << r.out;
  const Image image = expectPicture(out, 320, 240);
  const Coverage c = coverage(image);
  EXPECT_EQ(c.red, 0) << "no boundary was asked for";
  // A sphere fitted into the picture covers about pi/4 * (240/320) * 0.92^2 of it.
  EXPECT_GT(c.drawn, 0.3);
  EXPECT_LT(c.drawn, 0.6);
}

TEST_F(Render, RendersAMeshWithEdgesAndBoundaryMarkers)
{
  REQUIRE_XVFB();
  const fs::path out = path("mesh_boundary.png");
  const ToolRun r = render({path("icosphere.ply").string(), out.string(), "-wireframe",
                            "-boundary", path("flagged.pcd").string(), "-width", "300",
                            "-height", "300", "-azimuth", "30", "-elevation", "20"});
  expectSuccess(r);
  const Image image = expectPicture(out, 300, 300);
  EXPECT_GT(coverage(image).red, 0.005) << "the boundary markers are not drawn in red";
}

TEST_F(Render, RendersACloudWithItsBoundaryPointsInRed)
{
  REQUIRE_XVFB();
  const fs::path out = path("cloud_flags.png");
  const ToolRun r = render({path("flagged.pcd").string(), out.string(), "-point_size",
                            "8", "-width", "256", "-height", "200"});
  expectSuccess(r);
  const Image image = expectPicture(out, 256, 200);
  const Coverage c = coverage(image);
  EXPECT_GT(c.red, 0.005) << "the flagged points are not red";
  EXPECT_GT(c.grey, 0.01) << "the other points are not grey";
}

TEST_F(Render, RendersAPlainCloudFromAGivenCamera)
{
  REQUIRE_XVFB();
  const fs::path out = path("cloud.png");
  const ToolRun r = render({path("cloud.xyz").string(), out.string(), "-camera",
                            "0,0,-5,0,0,0,0,1,0", "-point_size", "6"});
  expectSuccess(r);
  const Image image = expectPicture(out, 640, 480);
  EXPECT_EQ(coverage(image).red, 0);
}

} // namespace
