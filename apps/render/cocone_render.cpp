// SPDX-License-Identifier: GPL-3.0-or-later
//
// pcl_cocone_render: draws a mesh (shaded, optionally with its edges) or a point cloud
// off screen with PCL's visualizer and writes the picture as PNG; the README's figures
// are made with it. Boundary samples (a boundary_point field, as written by
// pcl_boundary_sample_estimation) are drawn in red, as in the paper's figures 4 and 10.
//
// VTK as Debian builds it renders through GLX only (no EGL, no OSMesa): an X display is
// needed even off screen. The tool checks for one first, so that a headless run ends
// with one line naming the remedy (xvfb-run -a) instead of VTK's abort().
#include "tool_common.h"

#include <pcl/PolygonMesh.h>
#include <pcl/cocone/io/point_io.h>
#include <pcl/cocone/io/writers.h>
#include <pcl/console/print.h>
#include <pcl/conversions.h>
#include <pcl/io/vtk_lib_io.h>
#include <pcl/visualization/pcl_visualizer.h>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkImageData.h>
#include <vtkLightKit.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPNGWriter.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

// Last: Xlib defines macros (None, Status, Bool, Success) that the headers above use
// as names.
#include <X11/Xlib.h>

using namespace pcl::cocone::tools;
using pcl::cocone::ParameterRange;

namespace {

namespace fs = std::filesystem;

const std::string kProgram = "pcl_cocone_render";

// Colours (RGB in [0, 1]).
constexpr std::array<double, 3> kBackground{1.0, 1.0, 1.0};
constexpr std::array<double, 3> kSurface{0.70, 0.78, 0.92};  // light grey-blue
constexpr std::array<double, 3> kEdges{0.36, 0.41, 0.50};    // darker, not black
constexpr std::array<double, 3> kPoints{0.42, 0.50, 0.66};   // a cloud without flags
constexpr std::array<double, 3> kOrdinary{0.62, 0.62, 0.62}; // grey: not flagged
constexpr std::array<double, 3> kBoundary{0.90, 0.05, 0.05}; // red: boundary sample

constexpr double kViewAngle = 25;    // degrees, vertical
constexpr double kFill = 0.92;       // share of the image the fitted shape spans
constexpr double kMarkerScale = 1.6; // boundary markers vs. -point_size

// ---------------------------------------------------------------------------------
// Command line

/** Options that take a text value (a file, a list of numbers). CommandLine knows only
 * numbers and switches: these are declared to it as switches, so that -h lists them
 * and a repeated one is refused, and their values are taken out of argv before it
 * parses. */
const std::vector<std::string> kTextOptions{"-boundary", "-camera"};

/** Every option name of commandLine(), in its order (a value after a text option is
 * taken as its value unless it is one of these). */
const std::vector<std::string> kOptionNames{"-boundary",  "-wireframe",  "-width",
                                            "-height",    "-camera",     "-azimuth",
                                            "-elevation", "-point_size", "-v"};

CommandLine
commandLine()
{
  return CommandLine(
      {kProgram,
       "draws a mesh (shaded, optionally with its edges) or a point cloud off screen "
       "with PCL's visualizer and writes it as PNG; boundary samples (a boundary_point "
       "field, as pcl_boundary_sample_estimation writes it) are drawn in red, as in the "
       "figures of Dey et al., IEEE Visualization 2001.",
       "OUTPUT.png",
       {".png"},
       "the picture: 8-bit RGB PNG of W x H pixels, white background"},
      {{"-boundary",
        ValueKind::flag,
        "B.pcd",
        "draw the samples flagged in B's boundary_point field (one row per sample with "
        "its x y z, as pcl_boundary_sample_estimation writes it) as red markers over "
        "INPUT",
        0,
        "none",
        {}},
       flagOption("-wireframe", "draw the mesh's edges over its shaded surface"),
       {"-width", ValueKind::integer, "W", "image width in pixels", 640, "",
        ParameterRange{16, 8192, false, false}},
       {"-height", ValueKind::integer, "H", "image height in pixels", 480, "",
        ParameterRange{16, 8192, false, false}},
       {"-camera",
        ValueKind::flag,
        "px,py,pz,fx,fy,fz,ux,uy,uz",
        "camera position, focal point and view-up vector: nine comma-separated numbers "
        "(every run prints its camera, to be reused or adjusted); -azimuth and "
        "-elevation then turn it about the focal point. Without it the camera looks "
        "along -z with +y up, turned by -azimuth and -elevation, from where INPUT "
        "fills the picture",
        0,
        "fitted",
        {}},
       {"-azimuth", ValueKind::real, "DEG",
        "turn the camera by DEG degrees about the view-up axis through the focal point "
        "(positive: towards +x from the default view)",
        0, "", ParameterRange{-360, 360, false, false}},
       {"-elevation", ValueKind::real, "DEG",
        "then raise the camera by DEG degrees (positive: seen from above)", 0, "",
        ParameterRange{-90, 90, true, true}},
       {"-point_size", ValueKind::real, "S",
        "diameter in pixels of the points of a cloud, drawn as shaded spheres; boundary "
        "markers are 1.6 times larger",
        4, "", ParameterRange{0, 64, true, false}},
       verboseOption()});
}

void
printNotes()
{
  pcl::console::print_info(
      "\n-azimuth and -elevation are in degrees, as in VTK's camera and pcl_viewer.\n"
      "\nINPUT may be a mesh (.ply .obj .off with faces, or legacy .vtk POLYDATA), drawn\n"
      "as a shaded surface, or a point cloud (.pcd .xyz .pts .txt, a mesh file without\n"
      "faces), drawn as points. If INPUT has a boundary_point field, its flagged\n"
      "samples are red (the other points of a cloud grey). Points with a NaN\n"
      "coordinate and faces using them are skipped.\n"
      "\n"
      "VTK renders through an X display, off screen (no window opens). On a headless\n"
      "machine run the tool under Xvfb:\n"
      "  xvfb-run -a %s INPUT OUTPUT.png [options]\n",
      kProgram.c_str());
}

bool
isHelp(const std::string& arg)
{
  return arg == "-h" || arg == "--help";
}

/** argv with the values of the text options taken out (into \a values, in the order
 * of kTextOptions; nullopt when an option is absent, "" when its value is missing). */
std::vector<char*>
takeTextOptions(int argc, char** argv, const std::vector<std::string>& option_names,
                std::vector<std::optional<std::string>>& values)
{
  values.assign(kTextOptions.size(), std::nullopt);
  const auto isName = [&](const std::string& arg) {
    return isHelp(arg) || std::find(option_names.begin(), option_names.end(), arg) !=
                              option_names.end();
  };
  std::vector<char*> rest{argv[0]};
  for (int i = 1; i < argc; ++i) {
    rest.push_back(argv[i]);
    const auto it = std::find(kTextOptions.begin(), kTextOptions.end(), argv[i]);
    if (it == kTextOptions.end())
      continue;
    auto& value = values[static_cast<std::size_t>(it - kTextOptions.begin())];
    // A value may start with a dash (-camera -1,0,0,...), but not be an option.
    if (i + 1 < argc && !isName(argv[i + 1]))
      value = std::string(argv[++i]);
    else
      value = std::string();
  }
  return rest;
}

/** The nine numbers of -camera. */
std::array<double, 9>
parseCamera(const std::string& text)
{
  const std::string expected =
      " (expected px,py,pz,fx,fy,fz,ux,uy,uz: nine comma-separated numbers)";
  std::array<double, 9> values{};
  std::size_t count = 0, start = 0;
  while (true) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, end - start);
    char* stop = nullptr;
    errno = 0;
    const double value = std::strtod(item.c_str(), &stop);
    if (item.empty() || std::isspace(static_cast<unsigned char>(item[0])) ||
        *stop != '\0' || errno == ERANGE || !std::isfinite(value))
      fail("-camera: '" + item + "' is not a number" + expected);
    if (count == values.size())
      fail("-camera: more than nine numbers in '" + text + "'" + expected);
    values[count++] = value;
    if (end == text.size())
      break;
    start = end + 1;
  }
  if (count != values.size())
    fail("-camera: " + std::to_string(count) + " numbers in '" + text + "'" + expected);
  const Eigen::Vector3d position(values[0], values[1], values[2]);
  const Eigen::Vector3d focal(values[3], values[4], values[5]);
  const Eigen::Vector3d up(values[6], values[7], values[8]);
  const Eigen::Vector3d view = focal - position;
  if (view.norm() == 0)
    fail("-camera: the position and the focal point are the same");
  if (up.norm() == 0 || view.normalized().cross(up.normalized()).norm() < 1e-6)
    fail("-camera: the view-up vector is zero or parallel to the view direction");
  return values;
}

// ---------------------------------------------------------------------------------
// VTK's messages

/** Collects VTK's errors and warnings instead of letting them print (VTK writes each
 * as several lines with source locations); the tool reports them as one line. */
class MessageLog : public vtkOutputWindow
{
public:
  static MessageLog* New();
  vtkTypeMacro(MessageLog, vtkOutputWindow);

  void
  DisplayText(const char* text) override
  {
    warnings.emplace_back(text ? text : "");
  }
  void
  DisplayErrorText(const char* text) override
  {
    errors.emplace_back(text ? text : "");
  }
  void
  DisplayWarningText(const char* text) override
  {
    warnings.emplace_back(text ? text : "");
  }
  void
  DisplayGenericWarningText(const char* text) override
  {
    warnings.emplace_back(text ? text : "");
  }
  void
  DisplayDebugText(const char*) override
  {}

  std::vector<std::string> errors;
  std::vector<std::string> warnings;
};
vtkStandardNewMacro(MessageLog);

/** The gist of a VTK message: its last non-empty line without the "vtkClass (0x..): "
 * prefix. */
std::string
gist(const std::string& message)
{
  std::string line;
  std::size_t end = message.size();
  while (line.empty() && end > 0) {
    const std::size_t start = message.rfind('\n', end - 1);
    const std::size_t first = (start == std::string::npos) ? 0 : start + 1;
    line = message.substr(first, end - first);
    line.erase(0, line.find_first_not_of(" \t\r"));
    line.erase(line.find_last_not_of(" \t\r") + 1);
    end = (start == std::string::npos) ? 0 : start;
  }
  const std::size_t prefix = line.find("): ");
  if (line.rfind("vtk", 0) == 0 && prefix != std::string::npos)
    line.erase(0, prefix + 3);
  return line;
}

/** Fails with VTK's last error, if there is one, as "<what>: <reason>". */
void
failOnVtkError(const MessageLog& log, const std::string& what)
{
  if (!log.errors.empty())
    fail(what + ": " + gist(log.errors.back()));
}

// ---------------------------------------------------------------------------------
// The scene

using Point = Eigen::Vector3f;

struct Scene
{
  std::vector<Point> vertices; ///< of the mesh, all rows of INPUT (NaN included)
  std::vector<std::vector<std::uint32_t>> faces; ///< empty: INPUT is a cloud
  std::vector<Point> ordinary; ///< cloud points drawn in the ordinary colour
  std::vector<Point> boundary; ///< points drawn in red (cloud points or markers)
  bool flagged_cloud = false;  ///< INPUT is a cloud with a boundary_point field

  bool
  isMesh() const
  {
    return !faces.empty();
  }
};

bool
isFinite(const Point& p)
{
  return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
}

std::vector<Point>
pointsOf(const pcl::PCLPointCloud2& cloud)
{
  const pcl::PointCloud<pcl::PointXYZ>::Ptr xyz = toXyz(cloud);
  std::vector<Point> points;
  points.reserve(xyz->size());
  for (const pcl::PointXYZ& p : *xyz)
    points.emplace_back(p.x, p.y, p.z);
  return points;
}

/** The boundary_point field of \a cloud as one flag per row; nullopt without it. */
std::optional<std::vector<bool>>
boundaryFlags(const pcl::PCLPointCloud2& cloud)
{
  const auto field = std::find_if(
      cloud.fields.begin(), cloud.fields.end(),
      [](const pcl::PCLPointField& f) { return f.name == "boundary_point"; });
  if (field == cloud.fields.end())
    return std::nullopt;
  const std::size_t n = pointCount(cloud);
  std::vector<bool> flags(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* at = &cloud.data[i * cloud.point_step + field->offset];
    double value = 0;
    const auto read = [&](auto type) {
      decltype(type) v;
      std::memcpy(&v, at, sizeof v);
      value = static_cast<double>(v);
    };
    switch (field->datatype) {
    case pcl::PCLPointField::INT8:
      read(std::int8_t{});
      break;
    case pcl::PCLPointField::UINT8:
      read(std::uint8_t{});
      break;
    case pcl::PCLPointField::INT16:
      read(std::int16_t{});
      break;
    case pcl::PCLPointField::UINT16:
      read(std::uint16_t{});
      break;
    case pcl::PCLPointField::INT32:
      read(std::int32_t{});
      break;
    case pcl::PCLPointField::UINT32:
      read(std::uint32_t{});
      break;
    case pcl::PCLPointField::FLOAT32:
      read(float{});
      break;
    case pcl::PCLPointField::FLOAT64:
      read(double{});
      break;
    default:
      fail("the boundary_point field has an unsupported type");
    }
    flags[i] = value != 0 && !std::isnan(value);
  }
  return flags;
}

std::string
lowerExtension(const std::string& path)
{
  std::string extension = fs::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

/** Reads a legacy VTK file with PCL's reader: its points and polygons. */
void
loadVtk(const std::string& path, const MessageLog& log, Scene& scene,
        pcl::PCLPointCloud2& cloud)
{
  Stage stage("Loading", path);
  std::error_code ec;
  if (!fs::exists(path, ec))
    fail("cannot read " + path + ": no such file");
  if (!fs::is_regular_file(path, ec))
    fail("cannot read " + path + ": not a regular file");
  pcl::PolygonMesh mesh;
  {
    const QuietPcl quiet;
    pcl::io::loadPolygonFileVTK(path, mesh);
  }
  failOnVtkError(log, "cannot read " + path);
  cloud = mesh.cloud;
  if (pointCount(cloud) == 0)
    fail("cannot read " + path + ": no point");
  scene.vertices = pointsOf(cloud);
  for (const pcl::Vertices& polygon : mesh.polygons)
    scene.faces.emplace_back(polygon.vertices.begin(), polygon.vertices.end());
  stage.done(pointCount(cloud), "points");
}

Scene
loadScene(const CommandLine& cmd, const MessageLog& log)
{
  Scene scene;
  pcl::PCLPointCloud2 cloud;
  const std::string& path = cmd.input();
  const std::string extension = lowerExtension(path);
  if (extension == ".vtk")
    loadVtk(path, log, scene, cloud);
  else {
    cloud = loadCloud(path, cmd.verbose());
    scene.vertices = pointsOf(cloud);
    if (extension == ".ply" || extension == ".obj" || extension == ".off") {
      std::vector<pcl::Vertices> faces;
      std::string error;
      if (!pcl::cocone::loadMeshFaces(path, faces, &error))
        fail(error.empty() ? "cannot read the faces of " + path : error);
      for (const pcl::Vertices& face : faces)
        scene.faces.emplace_back(face.vertices.begin(), face.vertices.end());
    }
  }

  const std::size_t n = scene.vertices.size();
  const std::optional<std::vector<bool>> flags = boundaryFlags(cloud);
  if (!scene.faces.empty()) {
    // Faces that use a NaN vertex, or fewer than three, cannot be drawn.
    std::vector<std::vector<std::uint32_t>> kept;
    for (std::size_t f = 0; f < scene.faces.size(); ++f) {
      const auto& face = scene.faces[f];
      bool drawable = face.size() >= 3;
      for (const std::uint32_t v : face) {
        if (v >= n)
          fail(path + ": face " + std::to_string(f) + " uses vertex " +
               std::to_string(v) + " of " + std::to_string(n));
        drawable = drawable && isFinite(scene.vertices[v]);
      }
      if (drawable)
        kept.push_back(face);
    }
    if (kept.empty())
      fail(path + ": no face with three or more finite vertices to draw");
    scene.faces = std::move(kept);
    if (flags)
      for (std::size_t i = 0; i < n; ++i)
        if ((*flags)[i] && isFinite(scene.vertices[i]))
          scene.boundary.push_back(scene.vertices[i]);
  }
  else {
    scene.flagged_cloud = flags.has_value();
    for (std::size_t i = 0; i < n; ++i)
      if (isFinite(scene.vertices[i]))
        (flags && (*flags)[i] ? scene.boundary : scene.ordinary)
            .push_back(scene.vertices[i]);
    if (scene.ordinary.empty() && scene.boundary.empty())
      fail(path + ": no finite point to draw");
  }
  return scene;
}

/** Adds the flagged samples of \a path (-boundary) to the scene's red points. */
std::size_t
loadMarkers(const std::string& path, bool verbose, Scene& scene)
{
  const pcl::PCLPointCloud2 cloud = loadCloud(path, verbose);
  const std::optional<std::vector<bool>> flags = boundaryFlags(cloud);
  if (!flags)
    fail(path + " has no boundary_point field (write it with "
                "pcl_boundary_sample_estimation)");
  const std::vector<Point> points = pointsOf(cloud);
  std::size_t count = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    if ((*flags)[i] && isFinite(points[i])) {
      scene.boundary.push_back(points[i]);
      ++count;
    }
  return count;
}

// ---------------------------------------------------------------------------------
// Drawing

/** Every point that will be drawn (the camera is fitted to them). */
std::vector<Point>
drawnPoints(const Scene& scene)
{
  std::vector<Point> points;
  if (scene.isMesh()) {
    std::vector<bool> used(scene.vertices.size(), false);
    for (const auto& face : scene.faces)
      for (const std::uint32_t v : face)
        used[v] = true;
    for (std::size_t i = 0; i < used.size(); ++i)
      if (used[i])
        points.push_back(scene.vertices[i]);
  }
  else
    points = scene.ordinary;
  points.insert(points.end(), scene.boundary.begin(), scene.boundary.end());
  return points;
}

vtkSmartPointer<vtkActor>
meshActor(const Scene& scene, bool wireframe)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(static_cast<vtkIdType>(scene.vertices.size()));
  for (std::size_t i = 0; i < scene.vertices.size(); ++i) {
    // NaN vertices are used by no face; VTK must still not see them (bounds).
    const Point p = isFinite(scene.vertices[i]) ? scene.vertices[i] : Point::Zero();
    points->SetPoint(static_cast<vtkIdType>(i), p.x(), p.y(), p.z());
  }
  vtkNew<vtkCellArray> polygons;
  std::vector<vtkIdType> ids;
  for (const auto& face : scene.faces) {
    ids.assign(face.begin(), face.end());
    polygons->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  }
  vtkNew<vtkPolyData> mesh;
  mesh->SetPoints(points);
  mesh->SetPolys(polygons);

  // Smooth shading: one normal per vertex, averaged over its faces.
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(mesh);
  normals->ComputePointNormalsOn();
  normals->ComputeCellNormalsOff();
  normals->SplittingOff();
  normals->ConsistencyOn();
  normals->Update();

  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(normals->GetOutputPort());
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  vtkProperty* property = actor->GetProperty();
  property->SetColor(kSurface[0], kSurface[1], kSurface[2]);
  property->SetInterpolationToGouraud();
  property->SetAmbient(0.12);
  property->SetDiffuse(0.85);
  property->SetSpecular(0.18);
  property->SetSpecularPower(25);
  if (wireframe) {
    property->EdgeVisibilityOn();
    property->SetEdgeColor(kEdges[0], kEdges[1], kEdges[2]);
    property->SetLineWidth(1);
  }
  return actor;
}

/** Adds \a points to the visualizer as shaded spheres of \a size pixels. */
void
addPoints(pcl::visualization::PCLVisualizer& viewer, const std::vector<Point>& points,
          const std::array<double, 3>& colour, double size, const std::string& id)
{
  if (points.empty())
    return;
  auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  cloud->reserve(points.size());
  for (const Point& p : points)
    cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  const pcl::visualization::PointCloudColorHandlerCustom<pcl::PointXYZ> handler(
      cloud, 255 * colour[0], 255 * colour[1], 255 * colour[2]);
  if (!viewer.addPointCloud<pcl::PointXYZ>(cloud, handler, id))
    fail("internal error: cannot add the points '" + id + "'");
  viewer.setPointCloudRenderingProperties(pcl::visualization::PCL_VISUALIZER_POINT_SIZE,
                                          size, id);
  vtkProperty* property = (*viewer.getCloudActorMap())[id].actor->GetProperty();
  property->RenderPointsAsSpheresOn();
  property->LightingOn();
  property->SetAmbient(0.25);
  property->SetDiffuse(0.75);
  property->SetSpecular(0.2);
  property->SetSpecularPower(20);
}

/** Turns the camera as -azimuth and -elevation ask. */
void
turn(vtkCamera& camera, double azimuth, double elevation)
{
  camera.Azimuth(azimuth);
  camera.OrthogonalizeViewUp();
  camera.Elevation(elevation);
  camera.OrthogonalizeViewUp();
}

/** Places the camera, looking along its current direction with its view-up, so that
 * every point is in the picture and the picture is filled (perspective projection with
 * a vertical view angle of kViewAngle). */
void
fit(vtkCamera& camera, const std::vector<Point>& points, double aspect)
{
  Eigen::Vector3d position, focal, up;
  camera.GetPosition(position.data());
  camera.GetFocalPoint(focal.data());
  camera.GetViewUp(up.data());
  const Eigen::Vector3d view = (focal - position).normalized();
  const Eigen::Vector3d right = view.cross(up).normalized();
  up = right.cross(view).normalized();

  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector3d high = -low;
  for (const Point& p : points) {
    const Eigen::Vector3d q(p.dot(right.cast<float>()), p.dot(up.cast<float>()),
                            p.dot(view.cast<float>()));
    low = low.cwiseMin(q);
    high = high.cwiseMax(q);
  }
  const Eigen::Vector3d middle = (low + high) / 2;
  const double half_depth = std::max((high.z() - low.z()) / 2, 1e-9);
  const double tan_v = std::tan(kViewAngle * M_PI / 360) * kFill;
  const double tan_h = tan_v * aspect;
  // Distance from the camera to the middle plane so that every point is inside the
  // view: |x| <= (distance + z) tan_h and |y| <= (distance + z) tan_v.
  double distance = 2 * half_depth;
  for (const Point& p : points) {
    const double x = p.dot(right.cast<float>()) - middle.x();
    const double y = p.dot(up.cast<float>()) - middle.y();
    const double z = p.dot(view.cast<float>()) - middle.z();
    distance = std::max({distance, std::abs(x) / tan_h - z, std::abs(y) / tan_v - z});
  }
  const Eigen::Vector3d centre =
      middle.x() * right + middle.y() * up + middle.z() * view;
  camera.SetFocalPoint(centre.data());
  const Eigen::Vector3d eye = centre - distance * view;
  camera.SetPosition(eye.data());
  camera.SetViewUp(up.data());
}

std::string
cameraText(vtkCamera& camera)
{
  double v[9];
  camera.GetPosition(v);
  camera.GetFocalPoint(v + 3);
  camera.GetViewUp(v + 6);
  std::string text;
  for (int i = 0; i < 9; ++i)
    text += (i ? "," : "") + formatNumber(v[i], 6);
  return text;
}

/** The X display, opened here rather than by VTK, which would abort() without one: no
 * display ends the tool with one line. The connection is handed to the render window
 * and stays open until the process ends: closing it would let the X server reset (it
 * does when its last client leaves), and a connection VTK opened during that reset
 * would be refused. */
Display*
openDisplay()
{
  Display* display = XOpenDisplay(nullptr);
  if (!display) {
    const char* name = std::getenv("DISPLAY");
    fail(std::string("cannot open the X display") +
         (name && *name ? std::string(" '") + name + "'" : " (DISPLAY is not set)") +
         ": VTK renders through X even off screen; on a headless machine run "
         "xvfb-run -a " +
         kProgram + " ...");
  }
  return display;
}

} // namespace

int
main(int argc, char** argv)
{
  CommandLine cmd = commandLine();
  // Help wins over everything else on the line, as in the other tools; this one adds
  // notes on its inputs and on headless machines.
  for (int i = 1; i < argc; ++i)
    if (isHelp(argv[i])) {
      cmd.printHelp();
      printNotes();
      return 0;
    }
  std::vector<std::optional<std::string>> text_values;
  std::vector<char*> rest = takeTextOptions(argc, argv, kOptionNames, text_values);
  cmd.parse(static_cast<int>(rest.size()), rest.data());
  const std::optional<std::string>& boundary_path = text_values[0];
  const std::optional<std::string>& camera_text = text_values[1];
  if (boundary_path && boundary_path->empty())
    fail("-boundary needs a value: B.pcd, a cloud with a boundary_point field");
  if (camera_text && camera_text->empty())
    fail("-camera needs a value: px,py,pz,fx,fy,fz,ux,uy,uz");
  std::array<double, 9> camera_values{};
  if (camera_text)
    camera_values = parseCamera(*camera_text);
  const int width = static_cast<int>(cmd.count("-width"));
  const int height = static_cast<int>(cmd.count("-height"));
  const double point_size = cmd.value("-point_size");

  // Before loading anything: without a display there is nothing to do.
  Display* display = openDisplay();

  // VTK's messages are collected and reported as one line (see MessageLog); VTK 9
  // also logs its errors to stderr through vtkLogger, which would add a second line.
  vtkNew<MessageLog> log;
  vtkOutputWindow::SetInstance(log);
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);

  Scene scene = loadScene(cmd, *log);
  if (boundary_path) {
    const std::size_t count = loadMarkers(*boundary_path, cmd.verbose(), scene);
    if (cmd.verbose())
      printDetail("Boundary markers", std::to_string(count));
  }
  if (cmd.verbose()) {
    if (scene.isMesh())
      printDetail("Mesh", std::to_string(scene.vertices.size()) + " vertices, " +
                              std::to_string(scene.faces.size()) + " faces");
    else
      printDetail("Cloud",
                  std::to_string(scene.ordinary.size() + scene.boundary.size()) +
                      " finite points");
    printDetail("Red points", std::to_string(scene.boundary.size()));
  }

  Stage stage("Rendering", std::to_string(width) + " x " + std::to_string(height));
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetDisplayId(display);
  // Off screen: an X connection is still needed (GLX), but no window is mapped, and
  // the framebuffer has the requested size whatever the screen's.
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(8);
  pcl::visualization::PCLVisualizer viewer(renderer, window, kProgram, false);
  viewer.setShowFPS(false);
  viewer.setBackgroundColor(kBackground[0], kBackground[1], kBackground[2]);
  window->SetSize(width, height);

  if (scene.isMesh()) {
    renderer->AddActor(meshActor(scene, cmd.flag("-wireframe")));
    addPoints(viewer, scene.boundary, kBoundary, kMarkerScale * point_size, "boundary");
  }
  else {
    addPoints(viewer, scene.ordinary, scene.flagged_cloud ? kOrdinary : kPoints,
              point_size, "cloud");
    addPoints(viewer, scene.boundary, kBoundary, kMarkerScale * point_size, "boundary");
  }
  vtkNew<vtkLightKit> lights;
  lights->SetKeyLightIntensity(0.95);
  lights->AddLightsToRenderer(renderer);

  vtkCamera& camera = *renderer->GetActiveCamera();
  camera.SetViewAngle(kViewAngle);
  if (camera_text) {
    const std::array<double, 9>& v = camera_values;
    camera.SetPosition(v[0], v[1], v[2]);
    camera.SetFocalPoint(v[3], v[4], v[5]);
    camera.SetViewUp(v[6], v[7], v[8]);
    turn(camera, cmd.value("-azimuth"), cmd.value("-elevation"));
  }
  else {
    camera.SetPosition(0, 0, 1);
    camera.SetFocalPoint(0, 0, 0);
    camera.SetViewUp(0, 1, 0);
    turn(camera, cmd.value("-azimuth"), cmd.value("-elevation"));
    fit(camera, drawnPoints(scene), static_cast<double>(width) / height);
  }
  renderer->ResetCameraClippingRange();

  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  failOnVtkError(*log, "rendering failed");
  int dimensions[3] = {0, 0, 0};
  grab->GetOutput()->GetDimensions(dimensions);
  if (dimensions[0] != width || dimensions[1] != height)
    fail("rendering failed: the picture is " + std::to_string(dimensions[0]) + " x " +
         std::to_string(dimensions[1]) + " pixels instead of " + std::to_string(width) +
         " x " + std::to_string(height));
  stage.done(static_cast<std::size_t>(width) * height, "pixels");
  if (cmd.verbose())
    for (const std::string& warning : log->warnings)
      printDetail("VTK", gist(warning));

  Stage saving("Saving", cmd.output());
  vtkNew<vtkPNGWriter> png;
  png->SetCompressionLevel(9);
  png->WriteToMemoryOn();
  png->SetInputConnection(grab->GetOutputPort());
  png->Write();
  vtkUnsignedCharArray* bytes = png->GetResult();
  failOnVtkError(*log, "cannot encode the PNG");
  if (!bytes || bytes->GetNumberOfValues() == 0)
    fail("cannot encode the PNG");
  const std::size_t size = static_cast<std::size_t>(bytes->GetNumberOfValues());
  std::string error;
  if (!pcl::cocone::writeFile(cmd.output(), bytes->GetPointer(0), size, &error))
    fail(error);
  saving.done(size, "bytes");

  pcl::console::print_info("Camera: -camera %s\n", cameraText(camera).c_str());
  return 0;
}
