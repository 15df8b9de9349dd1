// SPDX-License-Identifier: GPL-3.0-or-later
//
// The Python module pcl_cocone: numpy arrays in, numpy arrays and meshes out. Every
// function is a thin layer over the library's classes (CoconeReconstruction,
// BoundarySampleEstimation, VoronoiDecimation) and readers (loadPointSamples): the
// points are converted once into a pcl::PointCloud<pcl::PointXYZ>, the class runs with
// the GIL released, and its results come back as numpy arrays. Parameters are checked
// by the classes' own setters (a refused value raises ValueError with the setter's
// message); a failed run raises ValueError with the class's getErrorMessage().
#include <pcl/cocone/boundary_sample_estimation.h>
#include <pcl/cocone/cocone_reconstruction.h>
#include <pcl/cocone/core/mesh_topology.h>
#include <pcl/cocone/io/point_io.h>
#include <pcl/cocone/io/writers.h>
#include <pcl/cocone/parameters.h>
#include <pcl/cocone/voronoi_decimation.h>
#include <pcl/common/point_tests.h>
#include <pcl/console/print.h>
#include <pcl/conversions.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace py = pybind11;
using namespace pybind11::literals;

namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;
using pcl::cocone::ParameterRange;
using pcl::cocone::TriangleIndices;

// Index arrays are handed out as int32, PCL's index type, so that they can be used to
// index numpy arrays and go to Open3D (Vector3iVector) as they are.
static_assert(std::is_same<pcl::index_t, std::int32_t>::value,
              "the module hands out PCL indices as int32");

// ---------------------------------------------------------------------------------
// Input

/** The raw view of an (N, 3) float32 or float64 array, read without the GIL. */
struct PointView
{
  const char* data = nullptr;
  py::ssize_t rows = 0;
  py::ssize_t row_stride = 0;    // bytes
  py::ssize_t column_stride = 0; // bytes
  bool is_double = false;
};

/** Whether \a object is an Open3D geometry (checked by its type's module, so that the
 * module never imports Open3D to find out). */
bool
isOpen3dObject(py::handle object)
{
  const py::object module = py::type::handle_of(object).attr("__module__");
  return py::isinstance<py::str>(module) &&
         module.cast<std::string>().rfind("open3d", 0) == 0;
}

/** \a points as an (N, 3) array of float32 or float64, as numpy.asarray sees them; an
 * open3d.geometry.PointCloud gives its points. Arrays of those two types are used as
 * they are, in any memory order; other real types (integers, float16) are converted to
 * float64. Raises TypeError for what is not an array of real numbers, ValueError for
 * another shape. */
py::array
pointArray(py::handle points)
{
  const py::module_ numpy = py::module_::import("numpy");
  py::object source = py::reinterpret_borrow<py::object>(points);
  // Open3D's arrays are views of its std::vectors, which it may reallocate later: its
  // points are copied, so that Mesh.vertices never points into freed memory.
  const bool from_open3d = isOpen3dObject(points);
  if (from_open3d && py::hasattr(points, "points"))
    source = points.attr("points");
  py::array array = from_open3d ? numpy.attr("array")(source, "dtype"_a = "float64")
                                : numpy.attr("asarray")(source);
  const py::dtype type = array.dtype();
  const bool native_float =
      type.equal(py::dtype::of<float>()) || type.equal(py::dtype::of<double>());
  if (!native_float) {
    const char kind = type.kind();
    if (kind != 'f' && kind != 'i' && kind != 'u')
      throw py::type_error(
          "points must be an (N, 3) array of real numbers, got dtype " +
          py::str(py::handle(type)).cast<std::string>());
    array = array.attr("astype")(py::dtype::of<double>());
  }
  if (array.ndim() != 2 || array.shape(1) != 3)
    throw py::value_error("points must have shape (N, 3), got " +
                          py::str(array.attr("shape")).cast<std::string>());
  return array;
}

PointView
pointView(const py::array& array)
{
  PointView view;
  view.data = static_cast<const char*>(array.data());
  view.rows = array.shape(0);
  view.row_stride = array.strides(0);
  view.column_stride = array.strides(1);
  view.is_double = array.dtype().itemsize() == sizeof(double);
  return view;
}

template <typename Scalar>
void
fillCloud(const PointView& view, Cloud& cloud)
{
  bool dense = true;
  for (py::ssize_t i = 0; i < view.rows; ++i) {
    const char* row = view.data + i * view.row_stride;
    Scalar xyz[3];
    // memcpy: numpy arrays need not be aligned (e.g. a field of a packed record).
    for (int k = 0; k < 3; ++k)
      std::memcpy(&xyz[k], row + k * view.column_stride, sizeof(Scalar));
    pcl::PointXYZ& point = cloud[static_cast<std::size_t>(i)];
    point.x = static_cast<float>(xyz[0]);
    point.y = static_cast<float>(xyz[1]);
    point.z = static_cast<float>(xyz[2]);
    dense = dense && pcl::isXYZFinite(point);
  }
  cloud.is_dense = dense;
}

/** The one conversion of the input: the points into the cloud the classes take. Runs
 * without the GIL. */
Cloud::Ptr
toCloud(const PointView& view)
{
  auto cloud = pcl::make_shared<Cloud>();
  cloud->resize(static_cast<std::size_t>(view.rows));
  if (view.is_double)
    fillCloud<double>(view, *cloud);
  else
    fillCloud<float>(view, *cloud);
  return cloud;
}

// ---------------------------------------------------------------------------------
// Parameters: set through the classes' setters, which refuse a value outside its range
// by printing PCL_ERROR and keeping the old one; the refusal is seen by reading the
// value back, and raised with the setter's message.

std::string
refusal(const char* class_name, const char* setter, const char* name, double value,
        const ParameterRange& range)
{
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, "[pcl::%s::%s] %s = %g is outside %s",
                class_name, setter, name, value, range.text().c_str());
  return buffer;
}

template <typename Object>
void
setReal(Object& object, void (Object::*setter)(double),
        double (Object::*getter)() const, double value, const char* class_name,
        const char* setter_name, const char* name, const ParameterRange& range)
{
  (object.*setter)(value);
  if (!((object.*getter)() == value))
    throw py::value_error(refusal(class_name, setter_name, name, value, range));
}

/** For the unsigned parameters: Python's int may be negative or beyond unsigned, which
 * the setter would see wrapped around; those are refused here with the same message. */
template <typename Object>
void
setCount(Object& object, void (Object::*setter)(unsigned),
         unsigned (Object::*getter)() const, long long value, const char* class_name,
         const char* setter_name, const char* name, const ParameterRange& range)
{
  if (value < 0 || value > std::numeric_limits<unsigned>::max())
    throw py::value_error(
        refusal(class_name, setter_name, name, static_cast<double>(value), range));
  (object.*setter)(static_cast<unsigned>(value));
  if ((object.*getter)() != static_cast<unsigned>(value))
    throw py::value_error(
        refusal(class_name, setter_name, name, static_cast<double>(value), range));
}

/** Any thread count is valid for the classes (0: every core); only a negative one or
 * one beyond unsigned cannot be passed. */
unsigned
threadCount(long long threads)
{
  if (threads < 0 || threads > std::numeric_limits<unsigned>::max())
    throw py::value_error("threads = " + std::to_string(threads) + " is outside [0, " +
                          std::to_string(std::numeric_limits<unsigned>::max()) +
                          "] (0: every core)");
  return static_cast<unsigned>(threads);
}

/** The denoising mode named \a name ("auto", "on" or "off"), as the tools take it. */
pcl::cocone::DenoiseMode
denoiseMode(const std::string& name)
{
  pcl::cocone::DenoiseMode mode = pcl::cocone::DenoiseMode::automatic;
  if (!pcl::cocone::parseDenoiseMode(name, mode))
    throw py::value_error("denoise = '" + name + "' is not one of 'auto', 'on', 'off'");
  return mode;
}

// ---------------------------------------------------------------------------------
// Progress and Ctrl-C

/** Raised (as pcl_cocone.CancelledError) when a progress callback returns False. */
class Cancelled : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/** The progress of one call, between the class and Python. The classes call their
 * progress hook from the thread that called them, here the one that released the GIL.
 * The hook takes the GIL back, lets Python run its signal handlers
 * (PyErr_CheckSignals: Ctrl-C raises KeyboardInterrupt there, in the main thread),
 * calls the user's callable with the share done, and lets the GIL go again. Whatever
 * stops the run (an exception of a handler or of the callable, or False returned) makes
 * the hook return false, which cancels the class's run; once the GIL is held again,
 * raiseIfStopped raises that exception, or Cancelled. The hook is installed even
 * without a callable, so that Ctrl-C always stops a running call (a few times per
 * stage, at the latest after 65536 points of the triangulation). */
class ProgressBridge
{
public:
  /** \a callback: a callable taking the share done, or None. */
  explicit ProgressBridge(py::object callback) : callback_(std::move(callback))
  {
    if (!callback_.is_none() && !PyCallable_Check(callback_.ptr()))
      throw py::type_error("progress must be a callable taking the share done (a "
                           "float from 0 to 1) or None, got " +
                           py::repr(callback_).cast<std::string>());
  }

  /** The hook for the class's setProgressCallback; valid while this bridge lives. */
  std::function<bool(double)>
  hook()
  {
    return [this](double share) { return report(share); };
  }

  /** Raises what stopped the run, if anything did. Call with the GIL held. */
  void
  raiseIfStopped(const std::string& call) const
  {
    if (error_)
      std::rethrow_exception(error_);
    if (cancelled_)
      throw Cancelled(call + " cancelled: the progress callback returned False");
  }

private:
  bool
  report(double share)
  {
    py::gil_scoped_acquire gil;
    try {
      if (PyErr_CheckSignals() != 0)
        throw py::error_already_set();
      if (callback_.is_none())
        return true;
      const py::object result = callback_(share);
      // None (a function without return) and True go on; False cancels.
      if (result.is_none())
        return true;
      const int truth = PyObject_IsTrue(result.ptr());
      if (truth < 0)
        throw py::error_already_set();
      cancelled_ = truth == 0;
      return !cancelled_;
    }
    catch (...) {
      // Kept, with the GIL held, to be raised after the run (error_already_set holds
      // the Python exception with its traceback).
      error_ = std::current_exception();
      return false;
    }
  }

  py::object callback_;
  std::exception_ptr error_;
  bool cancelled_ = false;
};

// ---------------------------------------------------------------------------------
// Output

/** A numpy array over \a values, which it takes over (no copy). */
template <typename T>
py::array_t<T>
arrayOf(std::vector<T>&& values)
{
  auto owner = std::make_unique<std::vector<T>>(std::move(values));
  const py::ssize_t size = static_cast<py::ssize_t>(owner->size());
  T* data = owner->data();
  py::capsule free(owner.get(),
                   [](void* p) { delete static_cast<std::vector<T>*>(p); });
  owner.release();
  return py::array_t<T>({size}, {static_cast<py::ssize_t>(sizeof(T))}, data, free);
}

py::array_t<std::int32_t>
indexArray(const pcl::Indices& indices)
{
  return arrayOf(std::vector<std::int32_t>(indices.begin(), indices.end()));
}

py::array_t<bool>
flagArray(const std::vector<std::uint8_t>& flags)
{
  py::array_t<bool> array(static_cast<py::ssize_t>(flags.size()));
  bool* out = array.mutable_data();
  for (std::size_t i = 0; i < flags.size(); ++i)
    out[i] = flags[i] != 0;
  return array;
}

void
makeReadOnly(py::array& array)
{
  array.attr("flags").attr("writeable") = false;
}

/** The class's warning as a Python RuntimeWarning (the tools print it as
 * "warning: ..."); nothing when it is empty. */
void
warn(const std::string& message)
{
  if (!message.empty() && PyErr_WarnEx(PyExc_RuntimeWarning, message.c_str(), 2) != 0)
    throw py::error_already_set(); // warnings turned into errors
}

// ---------------------------------------------------------------------------------
// Reconstruction

/** What reconstruct() returns: the mesh on the input points and what the run found. */
class Mesh
{
public:
  py::object vertices;
  py::array_t<std::int32_t> triangles;
  py::list boundary_loops;
  py::array_t<std::int32_t> unused;
  py::array_t<bool> boundary_samples;
  py::array_t<std::int32_t> far_indices;
  std::string warning;
  pcl::cocone::ReconstructionStatistics statistics;
  double reconstruct_seconds = 0; ///< CoconeReconstruction::reconstruct as a whole
  /** The triangles' own storage (the numpy array views it), for the topology. */
  std::shared_ptr<const std::vector<TriangleIndices>> triangle_storage;
  /** The cloud the class reconstructed from (the one conversion of the input) and the
   * points it left out as far: what save() writes, as the tool does. */
  Cloud::ConstPtr cloud;
  pcl::Indices far_points;

  /** The statistics as a dict, built on first use: its topology part walks every
   * triangle, which reconstruct() need not pay for. */
  py::dict
  report()
  {
    if (report_)
      return *report_;
    pcl::cocone::MeshTopology topology;
    {
      py::gil_scoped_release release;
      topology = pcl::cocone::analyzeTriangleMesh(*triangle_storage);
    }
    py::dict report;
    const py::ssize_t flags =
        py::int_(boundary_samples.attr("sum")()).cast<py::ssize_t>();
    // What pcl_cocone_reconstruction prints (its -v lines, then its summary).
    report["boundary_samples"] = flags;
    report["candidate_triangles"] = statistics.candidate_triangles;
    report["lid_triangles"] = statistics.lid_triangles;
    report["pruned_triangles"] = statistics.pruned_triangles;
    report["walked_triangles"] = statistics.walked_triangles;
    report["pinch_removed_triangles"] = statistics.pinch_removed_triangles;
    report["stitched_holes"] = statistics.stitched_holes;
    report["stitched_triangles"] = statistics.stitched_triangles;
    report["inserted_samples"] = statistics.inserted_samples;
    report["crossing_triangles"] = statistics.crossing_triangles;
    report["open_boundary_loops"] = py::len(boundary_loops);
    report["unused_points"] = py::len(unused);
    report["vertices_used"] = topology.vertices;
    report["triangles"] = topology.triangles;
    report["boundary_loops"] = topology.boundary_loops.size();
    report["euler_characteristic"] = topology.eulerCharacteristic();
    report["closed"] = topology.isClosed();
    report["manifold"] = topology.isManifold();
    report["components"] = topology.components;
    report["genus"] = topology.genus();
    report["distinct_samples"] = statistics.distinct_samples;
    report["distinct_boundary_samples"] = statistics.distinct_boundary_samples;
    report["too_sparse_for_boundary_detection"] =
        statistics.tooSparseForBoundaryDetection();
    const auto& t = statistics.timings;
    report["timings"] =
        py::dict("boundary"_a = t.boundary, "candidates"_a = t.candidates,
                 "pruning"_a = t.pruning, "walk"_a = t.walk,
                 "stitching"_a = t.stitching, "finishing"_a = t.finishing,
                 "restore"_a = t.restore, "reconstruct"_a = reconstruct_seconds);
    report["far_indices"] = far_indices;
    report["warning"] = warning;
    report_ = report;
    return report;
  }

  py::object
  toOpen3d() const
  {
    py::module_ o3d;
    try {
      o3d = py::module_::import("open3d");
    }
    catch (py::error_already_set& error) {
      if (!error.matches(PyExc_ImportError))
        throw;
      throw py::import_error("Mesh.to_open3d() needs Open3D (Debian: apt-get install "
                             "python3-open3d; elsewhere: pip install open3d)");
    }
    const py::module_ numpy = py::module_::import("numpy");
    const py::object utility = o3d.attr("utility");
    // Vector3dVector wants float64 rows, Vector3iVector int32 ones, both writeable
    // (Open3D copies them into its own vectors in any case).
    const py::object points = numpy.attr("array")(vertices, "dtype"_a = "float64");
    return o3d.attr("geometry")
        .attr("TriangleMesh")(
            utility.attr("Vector3dVector")(points),
            utility.attr("Vector3iVector")(numpy.attr("array")(triangles)));
  }

  /** Writes the mesh with the tool's writer: the io library's meshForWriting (the
   * finite points that are not far, the triangles renumbered) and saveMesh (binary PLY,
   * legacy VTK or OBJ by the extension, written atomically). */
  void
  save(const py::object& path_like) const
  {
    const std::string path =
        py::module_::import("os").attr("fspath")(path_like).cast<std::string>();
    std::string error;
    bool built = false;
    bool saved = false;
    {
      py::gil_scoped_release release;
      pcl::cocone::MeshForWriting mesh;
      built = pcl::cocone::meshForWriting(*cloud, *triangle_storage, far_points, mesh,
                                          &error);
      saved = built && pcl::cocone::saveMesh(path, mesh.vertices, mesh.triangles,
                                             "pcl_cocone.Mesh.save", &error);
    }
    if (!built)
      throw std::runtime_error("internal error: " + error);
    if (!saved) {
      // The writer's one-line reason either way: the format is the caller's choice, a
      // failed write the system's ("cannot write PATH: No such file or directory").
      if (!pcl::cocone::isMeshFormat(path))
        throw py::value_error(error);
      PyErr_SetString(PyExc_OSError, error.c_str());
      throw py::error_already_set();
    }
  }

private:
  std::optional<py::dict> report_;
};

/** When most samples are boundary samples, says so with the way out, as the tool does:
 * with theta, rho or alpha away from their defaults those values, not the cloud, may
 * be the reason (alpha 0.001 flags every sample of any cloud), so they are named.
 * Empty otherwise. */
std::string
sparseNote(const pcl::CoconeReconstruction<pcl::PointXYZ>& cocone)
{
  const pcl::cocone::ReconstructionStatistics& report = cocone.getReport();
  if (!report.tooSparseForBoundaryDetection())
    return "";
  const auto format = [](double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", value);
    return std::string(buffer);
  };
  const pcl::CoconeReconstruction<pcl::PointXYZ> defaults;
  std::string changed;
  const auto compare = [&](const char* name, double value, double default_value) {
    if (value != default_value)
      changed += std::string(changed.empty() ? "" : ", ") + name + "=" + format(value) +
                 " (default " + format(default_value) + ")";
  };
  compare("theta", cocone.getCoconeAngle(), defaults.getCoconeAngle());
  compare("rho", cocone.getRatioBound(), defaults.getRatioBound());
  compare("alpha", cocone.getNormalAngle(), defaults.getNormalAngle());
  std::string note = std::to_string(report.distinct_boundary_samples) + " of " +
                     std::to_string(report.distinct_samples) +
                     " points are boundary samples";
  if (changed.empty())
    return note + ": the cloud is too sparse for boundary detection at rho " +
           format(cocone.getRatioBound()) +
           ", so it was reconstructed without it (every hole closed where it can "
           "be); a larger rho keeps true boundaries open";
  return note + " with " + changed +
         ": these values flag most samples, so the cloud was reconstructed without "
         "boundary detection; try the defaults or a larger rho";
}

Mesh
reconstruct(const py::object& points, double theta, double rho, double alpha,
            double boundary_ratio, bool boundary_detection, bool stitching,
            long long threads, const std::string& denoise, const py::object& progress)
{
  using Class = pcl::CoconeReconstruction<pcl::PointXYZ>;
  const char* name = "CoconeReconstruction";
  Class cocone;
  setReal(cocone, &Class::setCoconeAngle, &Class::getCoconeAngle, theta, name,
          "setCoconeAngle", "theta", pcl::cocone::kCoconeAngleRange);
  setReal(cocone, &Class::setRatioBound, &Class::getRatioBound, rho, name,
          "setRatioBound", "rho", pcl::cocone::kRatioBoundRange);
  setReal(cocone, &Class::setNormalAngle, &Class::getNormalAngle, alpha, name,
          "setNormalAngle", "alpha", pcl::cocone::kNormalAngleRange);
  setReal(cocone, &Class::setTrueBoundaryRatio, &Class::getTrueBoundaryRatio,
          boundary_ratio, name, "setTrueBoundaryRatio", "ratio",
          pcl::cocone::kTrueBoundaryRatioRange);
  cocone.setBoundaryDetection(boundary_detection);
  cocone.setHoleStitching(stitching);
  cocone.setNumberOfThreads(threadCount(threads));
  cocone.setDenoise(denoiseMode(denoise));
  ProgressBridge bridge(progress);
  cocone.setProgressCallback(bridge.hook());

  const py::array array = pointArray(points);
  const PointView view = pointView(array);
  auto triangles = std::make_shared<std::vector<TriangleIndices>>();
  Cloud::Ptr cloud;
  double seconds = 0;
  {
    py::gil_scoped_release release;
    cloud = toCloud(view);
    cocone.setInputCloud(cloud);
    std::vector<pcl::Vertices> polygons;
    // Timed as the tool times its computing stage, so that the binding's own share of
    // a call (conversion in, arrays out) can be measured against it.
    const auto start = std::chrono::steady_clock::now();
    cocone.reconstruct(polygons);
    seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    triangles->reserve(polygons.size());
    for (const pcl::Vertices& polygon : polygons)
      triangles->push_back({static_cast<std::uint32_t>(polygon.vertices[0]),
                            static_cast<std::uint32_t>(polygon.vertices[1]),
                            static_cast<std::uint32_t>(polygon.vertices[2])});
  }
  bridge.raiseIfStopped("reconstruct");
  if (!cocone.getErrorMessage().empty())
    throw py::value_error(cocone.getErrorMessage());

  Mesh mesh;
  mesh.cloud = cloud;
  mesh.far_points = cocone.getFarIndices();
  mesh.vertices = array;
  // The int32 rows view the triangles' own storage, which the array keeps alive.
  auto* owner = new std::shared_ptr<const std::vector<TriangleIndices>>(triangles);
  py::capsule free(owner, [](void* p) {
    delete static_cast<std::shared_ptr<const std::vector<TriangleIndices>>*>(p);
  });
  mesh.triangles = py::array_t<std::int32_t>(
      {static_cast<py::ssize_t>(triangles->size()), py::ssize_t{3}},
      {static_cast<py::ssize_t>(sizeof(TriangleIndices)),
       static_cast<py::ssize_t>(sizeof(std::uint32_t))},
      reinterpret_cast<const std::int32_t*>(triangles->data()), free);
  mesh.triangle_storage = triangles;
  for (const pcl::Vertices& loop : cocone.getBoundaryLoops())
    mesh.boundary_loops.append(indexArray(loop.vertices));
  mesh.unused = indexArray(cocone.getUnusedIndices());
  mesh.boundary_samples = flagArray(cocone.getBoundarySamples());
  mesh.far_indices = indexArray(cocone.getFarIndices());
  mesh.statistics = cocone.getReport();
  mesh.reconstruct_seconds = seconds;
  mesh.warning = cocone.getWarningMessage();
  const std::string sparse = sparseNote(cocone);
  if (!sparse.empty())
    mesh.warning += (mesh.warning.empty() ? "" : "; ") + sparse;
  // Read-only: the report describes these arrays as they are.
  for (py::array* array : std::initializer_list<py::array*>{
           &mesh.triangles, &mesh.unused, &mesh.boundary_samples, &mesh.far_indices})
    makeReadOnly(*array);
  for (py::handle loop : mesh.boundary_loops) {
    py::array a = py::reinterpret_borrow<py::array>(loop);
    makeReadOnly(a);
  }
  warn(mesh.warning);
  return mesh;
}

// ---------------------------------------------------------------------------------
// BOUNDARY and the Voronoi geometry

using BoundaryClass = pcl::BoundarySampleEstimation<pcl::PointXYZ, pcl::Boundary>;

/** Runs BoundarySampleEstimation on \a points; raises ValueError when it fails. */
void
estimateBoundary(BoundaryClass& estimation, const py::array& array,
                 pcl::PointCloud<pcl::Boundary>& output, const py::object& progress,
                 const std::string& call)
{
  const PointView view = pointView(array);
  ProgressBridge bridge(progress);
  estimation.setProgressCallback(bridge.hook());
  {
    py::gil_scoped_release release;
    estimation.setInputCloud(toCloud(view));
    estimation.compute(output);
  }
  estimation.setProgressCallback(nullptr); // the bridge ends here
  bridge.raiseIfStopped(call);
  if (!estimation.getErrorMessage().empty())
    throw py::value_error(estimation.getErrorMessage());
  warn(estimation.getWarningMessage());
}

void
setBoundaryDiagram(BoundaryClass& estimation, double theta, long long threads,
                   const std::string& denoise)
{
  setReal(estimation, &BoundaryClass::setCoconeAngle, &BoundaryClass::getCoconeAngle,
          theta, "BoundarySampleEstimation", "setCoconeAngle", "theta",
          pcl::cocone::kCoconeAngleRange);
  estimation.setNumberOfThreads(threadCount(threads));
  estimation.setDenoise(denoiseMode(denoise));
}

py::array_t<bool>
boundarySamples(const py::object& points, double rho, double alpha, double theta,
                long long band_rings, bool rim_row_completion, long long threads,
                const std::string& denoise, const py::object& progress)
{
  const char* name = "BoundarySampleEstimation";
  BoundaryClass estimation;
  setReal(estimation, &BoundaryClass::setRatioBound, &BoundaryClass::getRatioBound, rho,
          name, "setRatioBound", "rho", pcl::cocone::kRatioBoundRange);
  setReal(estimation, &BoundaryClass::setNormalAngle, &BoundaryClass::getNormalAngle,
          alpha, name, "setNormalAngle", "alpha", pcl::cocone::kNormalAngleRange);
  setCount(estimation, &BoundaryClass::setBoundaryBandRings,
           &BoundaryClass::getBoundaryBandRings, band_rings, name,
           "setBoundaryBandRings", "rings", pcl::cocone::kBandRingsRange);
  estimation.setRimRowCompletion(rim_row_completion);
  setBoundaryDiagram(estimation, theta, threads, denoise);

  const py::array array = pointArray(points);
  pcl::PointCloud<pcl::Boundary> output;
  estimateBoundary(estimation, array, output, progress, "boundary_samples");
  py::array_t<bool> flags(static_cast<py::ssize_t>(output.size()));
  bool* out = flags.mutable_data();
  for (std::size_t i = 0; i < output.size(); ++i)
    out[i] = output[i].boundary_point != 0;
  return flags;
}

/** A copy of a per-point float vector as a float32 array. */
py::array_t<float>
floatArray(const std::vector<float>& values)
{
  return arrayOf(std::vector<float>(values));
}

py::dict
voronoiGeometry(const py::object& points, double theta, long long threads,
                const std::string& denoise, const py::object& progress)
{
  BoundaryClass estimation;
  setBoundaryDiagram(estimation, theta, threads, denoise);
  const py::array array = pointArray(points);
  pcl::PointCloud<pcl::Boundary> output;
  estimateBoundary(estimation, array, output, progress, "voronoi_geometry");

  const std::vector<Eigen::Vector3f>& poles = estimation.getPoleVectors();
  py::array_t<float> pole_vectors(
      {static_cast<py::ssize_t>(poles.size()), py::ssize_t{3}});
  auto out = pole_vectors.mutable_unchecked<2>();
  for (std::size_t i = 0; i < poles.size(); ++i)
    for (int k = 0; k < 3; ++k)
      out(static_cast<py::ssize_t>(i), k) = poles[i][k];
  return py::dict("pole_vectors"_a = pole_vectors,
                  "heights"_a = floatArray(estimation.getHeights()),
                  "cocone_radii"_a = floatArray(estimation.getCoconeRadii()),
                  "ratios"_a = floatArray(estimation.getRatios()),
                  "valid"_a = flagArray(estimation.getValidity()),
                  "far_indices"_a = indexArray(estimation.getFarIndices()),
                  "warning"_a = estimation.getWarningMessage());
}

// ---------------------------------------------------------------------------------
// DECIMATE

using DecimationClass = pcl::VoronoiDecimation<pcl::PointXYZ>;

void
setDecimation(DecimationClass& decimation, double theta, bool thin_rims,
              long long threads, const std::string& denoise)
{
  setReal(decimation, &DecimationClass::setCoconeAngle,
          &DecimationClass::getCoconeAngle, theta, "VoronoiDecimation",
          "setCoconeAngle", "theta", pcl::cocone::kCoconeAngleRange);
  decimation.setThinRims(thin_rims);
  decimation.setNumberOfThreads(threadCount(threads));
  decimation.setDenoise(denoiseMode(denoise));
}

py::array_t<std::int32_t>
decimate(const py::object& points, double rho, double theta, bool thin_rims,
         long long relaxation_iterations, long long threads, const std::string& denoise,
         const py::object& progress)
{
  const char* name = "VoronoiDecimation";
  DecimationClass decimation;
  setReal(decimation, &DecimationClass::setRatioBound, &DecimationClass::getRatioBound,
          rho, name, "setRatioBound", "rho", pcl::cocone::kRatioBoundRange);
  setCount(decimation, &DecimationClass::setRelaxationIterations,
           &DecimationClass::getRelaxationIterations, relaxation_iterations, name,
           "setRelaxationIterations", "iterations",
           pcl::cocone::kRelaxationIterationsRange);
  setDecimation(decimation, theta, thin_rims, threads, denoise);
  ProgressBridge bridge(progress);
  decimation.setProgressCallback(bridge.hook());

  const py::array array = pointArray(points);
  const PointView view = pointView(array);
  pcl::Indices kept;
  {
    py::gil_scoped_release release;
    decimation.setInputCloud(toCloud(view));
    decimation.filter(kept);
  }
  bridge.raiseIfStopped("decimate");
  if (!decimation.getErrorMessage().empty())
    throw py::value_error(decimation.getErrorMessage());
  warn(decimation.getWarningMessage());
  return arrayOf(std::move(kept));
}

py::list
levelsOfDetail(const py::object& points, const std::vector<double>& rhos, double theta,
               bool thin_rims, long long threads, const std::string& denoise,
               const py::object& progress)
{
  DecimationClass decimation;
  setDecimation(decimation, theta, thin_rims, threads, denoise);
  ProgressBridge bridge(progress);
  decimation.setProgressCallback(bridge.hook());
  const py::array array = pointArray(points);
  const PointView view = pointView(array);
  std::vector<pcl::Indices> kept;
  bool ok = false;
  {
    py::gil_scoped_release release;
    decimation.setInputCloud(toCloud(view));
    ok = decimation.computeLevelsOfDetail(rhos, kept);
  }
  bridge.raiseIfStopped("levels_of_detail");
  if (!ok) {
    // A refused rho (PCL_ERROR only) leaves the error message empty.
    for (const double rho : rhos)
      if (!pcl::cocone::kRatioBoundRange.contains(rho))
        throw py::value_error(refusal("VoronoiDecimation", "computeLevelsOfDetail",
                                      "rho", rho, pcl::cocone::kRatioBoundRange));
    const std::string& message = decimation.getErrorMessage();
    throw py::value_error(message.empty() ? "the levels of detail could not be computed"
                                          : message);
  }
  warn(decimation.getWarningMessage());
  py::list levels;
  for (pcl::Indices& level : kept)
    levels.append(arrayOf(std::move(level)));
  return levels;
}

// ---------------------------------------------------------------------------------
// Files

py::array_t<float>
loadPoints(const py::object& path_like)
{
  const std::string path =
      py::module_::import("os").attr("fspath")(path_like).cast<std::string>();
  // The reader says why it failed in one line; OSError for a file that cannot be
  // opened at all (as open() would raise), ValueError for contents it cannot use.
  std::error_code ignored;
  const bool directory = std::filesystem::is_directory(path, ignored);
  if (directory || !std::ifstream(path).good()) {
    // errno says why the open failed (ENOENT, EACCES); a folder opens, but is none.
    if (directory)
      errno = EISDIR;
    PyErr_SetFromErrnoWithFilename(PyExc_OSError, path.c_str());
    throw py::error_already_set();
  }
  pcl::PCLPointCloud2 blob;
  std::string error;
  bool ok = false;
  Cloud cloud;
  {
    py::gil_scoped_release release;
    ok = pcl::cocone::loadPointSamples(path, blob, &error);
    if (ok)
      pcl::fromPCLPointCloud2(blob, cloud);
  }
  if (!ok)
    throw py::value_error(error.empty() ? "cannot read " + path : error);
  py::array_t<float> points({static_cast<py::ssize_t>(cloud.size()), py::ssize_t{3}});
  auto out = points.mutable_unchecked<2>();
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    out(static_cast<py::ssize_t>(i), 0) = cloud[i].x;
    out(static_cast<py::ssize_t>(i), 1) = cloud[i].y;
    out(static_cast<py::ssize_t>(i), 2) = cloud[i].z;
  }
  return points;
}

// ---------------------------------------------------------------------------------
// PCL's console

pcl::console::VERBOSITY_LEVEL
verbosityLevel(const std::string& name)
{
  if (name == "always")
    return pcl::console::L_ALWAYS;
  if (name == "error")
    return pcl::console::L_ERROR;
  if (name == "warn")
    return pcl::console::L_WARN;
  if (name == "info")
    return pcl::console::L_INFO;
  if (name == "debug")
    return pcl::console::L_DEBUG;
  if (name == "verbose")
    return pcl::console::L_VERBOSE;
  throw py::value_error("verbosity must be one of always, error, warn, info, debug, "
                        "verbose; got " +
                        name);
}

std::string
verbosityName(pcl::console::VERBOSITY_LEVEL level)
{
  switch (level) {
  case pcl::console::L_ALWAYS:
    return "always";
  case pcl::console::L_ERROR:
    return "error";
  case pcl::console::L_WARN:
    return "warn";
  case pcl::console::L_INFO:
    return "info";
  case pcl::console::L_DEBUG:
    return "debug";
  case pcl::console::L_VERBOSE:
    return "verbose";
  default:
    return "info";
  }
}

// ---------------------------------------------------------------------------------
// Docstrings: units, defaults and ranges as the classes' headers give them; the ranges
// are printed from the library's constants so that they cannot drift.

std::string
range(const ParameterRange& r)
{
  return r.text();
}

std::string
number(double value)
{
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

} // namespace

PYBIND11_MODULE(pcl_cocone, m)
{
  namespace c = pcl::cocone;

  // The classes report every refused parameter and failed run with PCL_ERROR; here
  // they become exceptions with the same text, so PCL's console is quiet by default
  // (set_verbosity brings its messages and the stages' debug timings back).
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);

  // The defaults are read from default-constructed classes: the same as in C++.
  const pcl::CoconeReconstruction<pcl::PointXYZ> cocone;
  const BoundaryClass boundary;
  const DecimationClass decimation;

  // Docstrings in numpydoc's layout. Units and meanings are the headers'; every range
  // is printed from the library's constant.
  const std::string points_doc =
      "points : array_like (N, 3) or open3d.geometry.PointCloud\n"
      "    x, y, z per row: float32 or float64 in any memory order, or anything\n"
      "    numpy.asarray turns into one (a list of triples; other real types are\n"
      "    converted to float64). Converted once to pcl::PointCloud<pcl::PointXYZ>\n"
      "    (float32).\n";
  const std::string theta_doc =
      "theta : float, radians, default pi/8 (the paper's value), range (0, pi/2) = " +
      range(c::kCoconeAngleRange) +
      "\n"
      "    The cocone angle: the cocone of p is the part of its Voronoi cell within\n"
      "    theta of the plane orthogonal to the pole vector.\n";
  const std::string threads_doc =
      "threads : int, default 0\n"
      "    Worker threads for the per-sample work; 0 uses every core. Results do not\n"
      "    depend on it.\n"
      "denoise : str, default 'auto'\n"
      "    'auto' measures the cloud's noise and, when it is noisy (a scan), builds\n"
      "    the Voronoi diagram on a smoothed copy; the results still index the\n"
      "    input points. 'on' always smooths, 'off' never (docs/noise.md).\n";
  const std::string progress_doc =
      "progress : callable or None, default None\n"
      "    Called as progress(share) with the share of the run done, from 0 to 1,\n"
      "    a few times per stage, from the calling thread (with the GIL); 1.0 is\n"
      "    the last call of a run that completes. Return None or True to go on,\n"
      "    False to cancel (CancelledError); an exception it raises stops the run\n"
      "    and propagates. Ctrl-C stops a running call with or without it.\n";
  const std::string raises_doc =
      "\nRaises\n------\n"
      "TypeError\n"
      "    points are not an array of real numbers.\n"
      "ValueError\n"
      "    points are not (N, 3); a parameter is outside its range (the setter's\n"
      "    message); the cloud has no 3D Voronoi diagram: empty, all NaN, fewer than\n"
      "    4 distinct points, coplanar or collinear (the class's error message).\n"
      "CancelledError\n"
      "    The progress callback returned False.\n"
      "KeyboardInterrupt\n"
      "    Ctrl-C (SIGINT) during the run, which stops at its next progress report.\n"
      "\nWarns\n-----\n"
      "RuntimeWarning\n"
      "    The class's warning: far points left out, coarse float rounding.\n";

  m.doc() =
      "Voronoi-based boundary detection, COCONE surface reconstruction with\n"
      "boundaries and DECIMATE (Dey, Giesen, Goswami, Hudson, Wenger, Zhao,\n"
      "\"Undersampling and Oversampling in Sample Based Shape Modeling\", IEEE\n"
      "Visualization 2001), from the pcl_cocone library.\n\n"
      "    mesh = pcl_cocone.reconstruct(points)   # points: (N, 3)\n"
      "    mesh.triangles, mesh.boundary_loops, mesh.report\n"
      "    mesh.to_open3d()                        # needs Open3D\n\n"
      "Every function takes an (N, 3) array or an open3d PointCloud, and releases\n"
      "the GIL while it computes, so that Python threads can run it at once.\n"
      "Indices are int32 rows of the input.";
  m.attr("__version__") = PCL_COCONE_VERSION;
  py::register_exception<Cancelled>(m, "CancelledError", PyExc_RuntimeError)
      .attr("__doc__") = "A call stopped because its progress callback returned False.";

  py::class_<Mesh>(m, "Mesh",
                   "A reconstructed surface whose vertices are the input points.\n\n"
                   "Its arrays are read-only (copy them to edit): the report\n"
                   "describes them as they are.")
      .def_readonly("vertices", &Mesh::vertices,
                    "(N, 3) array: the input points as given, not copied (integers\n"
                    "as their float64 conversion; an Open3D cloud's points as a\n"
                    "float64 copy). Row i is vertex i, also for points in no triangle\n"
                    "(see unused).")
      .def_readonly("triangles", &Mesh::triangles,
                    "(M, 3) int32: oriented triangles as rows of vertices (closed\n"
                    "components face outward).")
      .def_readonly("boundary_loops", &Mesh::boundary_loops,
                    "list of int32 arrays: the boundary loops left open (true\n"
                    "boundaries, holes that could not be closed), each a cycle of\n"
                    "vertex rows oriented with the surface.")
      .def_readonly("unused", &Mesh::unused,
                    "int32, ascending: the input points in no triangle (non-finite,\n"
                    "far, duplicates, outliers, samples the extraction left out).")
      .def_readonly("boundary_samples", &Mesh::boundary_samples,
                    "bool (N,): BOUNDARY's flags as published, the samples that cast\n"
                    "no vote (all False with boundary_detection=False).")
      .def_property_readonly(
          "report", &Mesh::report,
          "dict: what pcl_cocone_reconstruction prints. The stages' counts\n"
          "(candidate_triangles, lid_triangles, pruned_triangles, walked_triangles,\n"
          "stitched_holes, stitched_triangles, ...), the mesh's topology\n"
          "(vertices_used, triangles, boundary_loops, euler_characteristic, closed,\n"
          "manifold, components, genus), timings (seconds per stage, and\n"
          "'reconstruct': the class's whole run, Voronoi diagram included, as the\n"
          "tool times it), far_indices\n"
          "(the far points left out) and warning ('' if none). Built on first use.")
      .def("to_open3d", &Mesh::toOpen3d,
           "The mesh as an open3d.geometry.TriangleMesh. Its vertices are every input\n"
           "row (float64), so indices stay those of the input; its\n"
           "remove_unreferenced_vertices() drops the unused ones. Only this imports\n"
           "Open3D.")
      .def(
          "save", &Mesh::save, "path"_a,
          "Writes the mesh as pcl_cocone_reconstruction does, with the same writer.\n\n"
          "The format is the extension's (case-insensitive): .ply (binary little\n"
          "endian, float x y z, triangles as uchar int lists), .vtk (legacy ASCII\n"
          "POLYDATA) or .obj. The vertices are the input rows with finite\n"
          "coordinates that are not far, in input order: with no such row left out,\n"
          "vertex i is row i; otherwise the later rows move up and the triangles are\n"
          "renumbered to match. Coordinates are the float32 values the\n"
          "reconstruction used. The file is written beside its target and renamed\n"
          "over it, so a failed write leaves no partial file.\n"
          "\nParameters\n----------\n"
          "path : str or os.PathLike\n"
          "\nRaises\n------\n"
          "ValueError\n"
          "    The extension is none of .ply, .vtk, .obj.\n"
          "OSError\n"
          "    The file cannot be written (the system's reason: a missing folder,\n"
          "    no permission, a full disk).\n")
      .def("__repr__", [](const Mesh& mesh) {
        return "<pcl_cocone.Mesh: " + std::to_string(py::len(mesh.vertices)) +
               " vertices, " + std::to_string(mesh.triangles.shape(0)) +
               " triangles, " + std::to_string(py::len(mesh.boundary_loops)) +
               " boundary loops>";
      });

  const std::string reconstruct_doc =
      "COCONE surface reconstruction with boundaries (pcl::CoconeReconstruction).\n\n"
      "An oriented 2-manifold, with boundary where there is one, whose vertices are\n"
      "the input points. Holes smaller than boundary_ratio are stitched.\n"
      "\nParameters\n----------\n" +
      points_doc + theta_doc + "rho : float, dimensionless, default " +
      number(cocone.getRatioBound()) + ", range " + range(c::kRatioBoundRange) +
      "\n"
      "    BOUNDARY's ratio bound: r_p / h_p <= rho for flat samples. Smaller\n"
      "    values flag more boundary samples.\n"
      "alpha : float, radians, default pi/6, range (0, pi/2] = " +
      range(c::kNormalAngleRange) +
      "\n"
      "    BOUNDARY's normal agreement angle: the largest acute angle between the\n"
      "    pole lines of neighbouring flat samples.\n"
      "boundary_ratio : float, local sample spacings, default " +
      number(cocone.getTrueBoundaryRatio()) + ", range " +
      range(c::kTrueBoundaryRatioRange) +
      "\n"
      "    A hole whose size (twice its area over its perimeter: the radius of a\n"
      "    round hole) exceeds this many local spacings is a true boundary and\n"
      "    stays open; smaller holes are stitched. Raise it to close larger holes\n"
      "    (a scan's cut), lower it to keep smaller ones open.\n"
      "boundary_detection : bool, default True\n"
      "    Detect boundary samples and let them cast no vote. False gives the\n"
      "    original COCONE, for densely sampled closed smooth surfaces only.\n"
      "stitching : bool, default True\n"
      "    Close the holes that are not true boundaries.\n" +
      threads_doc + progress_doc +
      "\nReturns\n-------\n"
      "Mesh\n"
      "    A cloud too sparse for boundary detection (most samples flagged) is\n"
      "    reconstructed without it, with a RuntimeWarning that says so.\n" +
      raises_doc;
  m.def("reconstruct", &reconstruct, "points"_a, py::kw_only(),
        "theta"_a = cocone.getCoconeAngle(), "rho"_a = cocone.getRatioBound(),
        "alpha"_a = cocone.getNormalAngle(),
        "boundary_ratio"_a = cocone.getTrueBoundaryRatio(),
        "boundary_detection"_a = cocone.getBoundaryDetection(),
        "stitching"_a = cocone.getHoleStitching(),
        "threads"_a = static_cast<long long>(cocone.getNumberOfThreads()),
        "denoise"_a = pcl::cocone::toString(cocone.getDenoise()),
        "progress"_a = py::none(), reconstruct_doc.c_str());

  const std::string boundary_doc =
      "Algorithm BOUNDARY (pcl::BoundarySampleEstimation).\n\n"
      "Flags the samples near undersampling (boundaries, sharp features, thin or\n"
      "sparsely sampled parts) from the shape of their Voronoi cells; no normals,\n"
      "no k, no radius.\n"
      "\nParameters\n----------\n" +
      points_doc + "rho : float, dimensionless, default " +
      number(boundary.getRatioBound()) + ", range " + range(c::kRatioBoundRange) +
      "\n"
      "    The ratio bound of the flatness test r_p / h_p <= rho. Smaller values\n"
      "    flag more samples.\n"
      "alpha : float, radians, default pi/6, range (0, pi/2] = " +
      range(c::kNormalAngleRange) +
      "\n"
      "    The largest acute angle between the pole lines of neighbouring flat\n"
      "    samples. Smaller values flag more samples near curved or sharp regions.\n" +
      theta_doc + "band_rings : int, rings, default 0, range " +
      range(c::kBandRingsRange) +
      "\n"
      "    Beyond the paper: also flag this many rings of cocone neighbours around\n"
      "    the boundary samples (a band, like pcl::BoundaryEstimation's); 0 is\n"
      "    BOUNDARY as published.\n"
      "rim_row_completion : bool, default True\n"
      "    Beyond the paper: complete the outermost row of samples along each rim\n"
      "    (BOUNDARY alone flags 27-54% of it). False gives BOUNDARY as published.\n" +
      threads_doc + progress_doc +
      "\nReturns\n-------\n"
      "numpy.ndarray of bool, (N,)\n"
      "    True for a boundary sample; False also for points that took no part\n"
      "    (non-finite, far).\n" +
      raises_doc;
  m.def("boundary_samples", &boundarySamples, "points"_a, py::kw_only(),
        "rho"_a = boundary.getRatioBound(), "alpha"_a = boundary.getNormalAngle(),
        "theta"_a = boundary.getCoconeAngle(),
        "band_rings"_a = static_cast<long long>(boundary.getBoundaryBandRings()),
        "rim_row_completion"_a = boundary.getRimRowCompletion(),
        "threads"_a = static_cast<long long>(boundary.getNumberOfThreads()),
        "denoise"_a = pcl::cocone::toString(boundary.getDenoise()),
        "progress"_a = py::none(), boundary_doc.c_str());

  const std::string geometry_doc =
      "The per-point Voronoi values that BOUNDARY measures.\n\n"
      "pcl::BoundarySampleEstimation's getPoleVectors, getHeights, getCoconeRadii\n"
      "and getRatios. rho and alpha do not change them, so they are not taken.\n"
      "\nParameters\n----------\n" +
      points_doc + theta_doc + threads_doc + progress_doc +
      "\nReturns\n-------\n"
      "dict, one row per input point\n"
      "    pole_vectors: float32 (N, 3), unit pole vectors v_p, a normal estimate\n"
      "        oriented towards the positive pole (where the cell extends farther);\n"
      "    heights: float32 (N,), h_p = |p- - p| in input units, an estimate of the\n"
      "        local feature size (NaN where the cell has no negative pole);\n"
      "    cocone_radii: float32 (N,), r_p in input units (+inf: unbounded cocone);\n"
      "    ratios: float32 (N,), r_p / h_p, dimensionless (+inf where h_p is\n"
      "        undefined or r_p infinite);\n"
      "    valid: bool (N,), False for points that took no part (values NaN);\n"
      "    far_indices: int32, the points left out as far beyond the cloud's scale;\n"
      "    warning: str, the class's warning ('' if none).\n" +
      raises_doc;
  m.def("voronoi_geometry", &voronoiGeometry, "points"_a, py::kw_only(),
        "theta"_a = boundary.getCoconeAngle(),
        "threads"_a = static_cast<long long>(boundary.getNumberOfThreads()),
        "denoise"_a = pcl::cocone::toString(boundary.getDenoise()),
        "progress"_a = py::none(), geometry_doc.c_str());

  const std::string rims_doc =
      "thin_rims : bool, default True\n"
      "    Beyond the paper: measure rim samples of an open surface on the side\n"
      "    where the surface is, so that rims are thinned like the rest. False gives\n"
      "    DECIMATE as published.\n";
  const std::string decimate_doc =
      "Algorithm DECIMATE (pcl::VoronoiDecimation).\n\n"
      "Removes oversampling and keeps features: flat regions are thinned much more\n"
      "than curved ones. Kept points are input points, never moved; the result is\n"
      "the same on every run.\n"
      "\nParameters\n----------\n" +
      points_doc + "rho : float, dimensionless, default " +
      number(decimation.getRatioBound()) + ", range " + range(c::kRatioBoundRange) +
      "\n"
      "    Samples with r_p / h_p below it are removed, smallest first. Useful\n"
      "    range 0.25 to 0.4.\n" +
      theta_doc + rims_doc + "relaxation_iterations : int, default " +
      std::to_string(decimation.getRelaxationIterations()) + ", range " +
      range(c::kRelaxationIterationsRange) +
      "\n"
      "    Beyond the paper: rounds of relaxation that even out the kept sample at\n"
      "    the same size; 0 gives DECIMATE's own sample.\n" +
      threads_doc + progress_doc +
      "\nReturns\n-------\n"
      "numpy.ndarray of int32\n"
      "    The rows of the kept points, ascending: never a non-finite or far one;\n"
      "    of exact duplicates only the first.\n" +
      raises_doc;
  m.def("decimate", &decimate, "points"_a, "rho"_a = decimation.getRatioBound(),
        py::kw_only(), "theta"_a = decimation.getCoconeAngle(),
        "thin_rims"_a = decimation.getThinRims(),
        "relaxation_iterations"_a =
            static_cast<long long>(decimation.getRelaxationIterations()),
        "threads"_a = static_cast<long long>(decimation.getNumberOfThreads()),
        "denoise"_a = pcl::cocone::toString(decimation.getDenoise()),
        "progress"_a = py::none(), decimate_doc.c_str());

  const std::string levels_doc =
      "Nested subsets for several ratio bounds from one DECIMATE run.\n\n"
      "pcl::VoronoiDecimation::computeLevelsOfDetail: DECIMATE's own sets, without\n"
      "relaxation.\n"
      "\nParameters\n----------\n" +
      points_doc + "rhos : sequence of float, dimensionless, each in " +
      range(c::kRatioBoundRange) +
      "\n"
      "    The ratio bounds, in any order.\n" +
      theta_doc + rims_doc + threads_doc + progress_doc +
      "\nReturns\n-------\n"
      "list of numpy.ndarray of int32\n"
      "    The kept rows per rho, in the order of rhos; a larger rho keeps a subset\n"
      "    of what a smaller one keeps.\n" +
      raises_doc;
  m.def("levels_of_detail", &levelsOfDetail, "points"_a, "rhos"_a, py::kw_only(),
        "theta"_a = decimation.getCoconeAngle(),
        "thin_rims"_a = decimation.getThinRims(),
        "threads"_a = static_cast<long long>(decimation.getNumberOfThreads()),
        "denoise"_a = pcl::cocone::toString(decimation.getDenoise()),
        "progress"_a = py::none(), levels_doc.c_str());

  m.def("load_points", &loadPoints, "path"_a,
        "The points of a file, as the tools read them (loadPointSamples).\n\n"
        "Formats by extension, case-insensitive: .pcd, .ply, .obj, .off, .xyz,\n"
        ".pts, .txt, .las (LAS 1.0 to 1.4; LAZ is refused with the commands that\n"
        "decompress it). Meshes give their vertices; NaN points are kept, in file\n"
        "order.\n"
        "\nParameters\n----------\n"
        "path : str or os.PathLike\n"
        "\nReturns\n-------\n"
        "numpy.ndarray of float32, (N, 3)\n"
        "\nRaises\n------\n"
        "OSError\n"
        "    The file cannot be opened.\n"
        "ValueError\n"
        "    The reader cannot use it (with its reason).\n");

  m.def(
      "set_verbosity",
      [](const std::string& level) {
        const std::string previous = verbosityName(pcl::console::getVerbosityLevel());
        pcl::console::setVerbosityLevel(verbosityLevel(level));
        return previous;
      },
      "level"_a,
      "Sets PCL's console level, process-wide, and returns the previous one.\n\n"
      "'always' is the module's default: the classes' errors and warnings come as\n"
      "exceptions and RuntimeWarnings instead. Then 'error', 'warn', 'info',\n"
      "'debug' (the stages' statistics and timings), 'verbose'.");
}
