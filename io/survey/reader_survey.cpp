// SPDX-License-Identifier: GPL-3.0-or-later
//
// reader_survey FILE...        every reader that takes the file's extension, on each
// reader_survey --malformed    the same on malformed files it writes to a temporary
//                              folder (truncated, oversized counts, bad values, ...)
//
// Each reader runs in a child process with an 8 GB address-space limit and a 60 s
// alarm, so that a crash, an abort on std::bad_alloc or a hang is reported instead of
// ending the survey. One line per reader and file: ok or FAIL, points, faces, the
// fields or arrays kept, time, peak memory, and the bytes printed on stderr with the
// first of them.
#include <pcl/PCLPointCloud2.h>
#include <pcl/PolygonMesh.h>
#include <pcl/cocone/io/point_io.h>
#include <pcl/io/ascii_io.h>
#include <pcl/io/obj_io.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <CGAL/IO/OFF.h>
#include <CGAL/Simple_cartesian.h>

#include <vtkAbstractPolyDataReader.h>
#include <vtkOBJReader.h>
#include <vtkPLYReader.h>
#include <vtkPTSReader.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSimplePointsReader.h>
#include <vtkSmartPointer.h>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct Result
{
  bool ok = false;
  long points = -1;
  long faces = -1;
  std::string fields;
};

std::string
fieldsOf(const pcl::PCLPointCloud2& cloud)
{
  std::string text;
  for (const pcl::PCLPointField& field : cloud.fields)
    text += field.name + " ";
  return text + "(" + std::to_string(cloud.width) + "x" + std::to_string(cloud.height) +
         ")";
}

Result
fromPcl(bool ok, const pcl::PCLPointCloud2& cloud, long faces = -1)
{
  return {ok, static_cast<long>(cloud.width) * cloud.height, faces, fieldsOf(cloud)};
}

template <typename Reader>
Result
fromVtk(const std::string& path)
{
  auto reader = vtkSmartPointer<Reader>::New();
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* data = reader->GetOutput();
  Result result;
  if (!data)
    return result;
  result.ok = data->GetNumberOfPoints() > 0;
  result.points = data->GetNumberOfPoints();
  result.faces = data->GetNumberOfPolys();
  vtkPointData* arrays = data->GetPointData();
  for (int i = 0; i < arrays->GetNumberOfArrays(); ++i)
    result.fields +=
        std::string(arrays->GetArrayName(i) ? arrays->GetArrayName(i) : "?") + " ";
  return result;
}

struct Reader
{
  const char* name;
  std::vector<std::string> extensions;
  std::function<Result(const std::string&)> read;
};

const std::vector<Reader> readers = {
    {"ours",
     {".pcd", ".ply", ".obj", ".off", ".xyz", ".pts", ".txt"},
     [](const std::string& path) {
       pcl::PCLPointCloud2 cloud;
       std::vector<pcl::Vertices> faces;
       const bool ok = pcl::cocone::loadPointSamples(path, cloud);
       const bool faces_ok = pcl::cocone::loadMeshFaces(path, faces);
       return fromPcl(ok, cloud, faces_ok ? static_cast<long>(faces.size()) : -1);
     }},
    {"pcl::PCDReader",
     {".pcd"},
     [](const std::string& path) {
       pcl::PCLPointCloud2 cloud;
       return fromPcl(pcl::PCDReader().read(path, cloud) >= 0, cloud);
     }},
    {"pcl::PLYReader",
     {".ply"},
     [](const std::string& path) {
       pcl::PolygonMesh mesh;
       const bool ok = pcl::io::loadPLYFile(path, mesh) >= 0;
       return fromPcl(ok, mesh.cloud, static_cast<long>(mesh.polygons.size()));
     }},
    {"vtkPLYReader", {".ply"}, fromVtk<vtkPLYReader>},
    {"pcl::OBJReader",
     {".obj"},
     [](const std::string& path) {
       pcl::PolygonMesh mesh;
       const bool ok = pcl::OBJReader().read(path, mesh) >= 0;
       return fromPcl(ok, mesh.cloud, static_cast<long>(mesh.polygons.size()));
     }},
    {"vtkOBJReader", {".obj"}, fromVtk<vtkOBJReader>},
    {"CGAL::IO::read_OFF",
     {".off"},
     [](const std::string& path) {
       using Point = CGAL::Simple_cartesian<double>::Point_3;
       std::vector<Point> points;
       std::vector<std::vector<std::size_t>> faces;
       const bool ok = CGAL::IO::read_OFF(path, points, faces);
       return Result{ok, static_cast<long>(points.size()),
                     static_cast<long>(faces.size()), ""};
     }},
    {"vtkSimplePointsReader", {".xyz", ".pts", ".txt"}, fromVtk<vtkSimplePointsReader>},
    {"vtkPTSReader", {".xyz", ".pts", ".txt"}, fromVtk<vtkPTSReader>},
    {"pcl::ASCIIReader",
     {".xyz", ".pts", ".txt"},
     [](const std::string& path) {
       // It refuses any extension but .txt: the survey gives it a copy so named.
       const std::string copy = path + ".txt";
       fs::copy_file(path, copy, fs::copy_options::overwrite_existing);
       pcl::ASCIIReader reader;
       reader.setSepChars(" \t");
       pcl::PCLPointCloud2 cloud;
       Eigen::Vector4f origin;
       Eigen::Quaternionf orientation;
       int version = 0;
       const bool ok = reader.read(copy, cloud, origin, orientation, version) >= 0;
       fs::remove(copy);
       return fromPcl(ok, cloud);
     }},
};

void
survey(const Reader& reader, const std::string& path)
{
  int pipe_ends[2];
  if (::pipe(pipe_ends) != 0)
    return;
  char err_name[] = "/tmp/reader_survey_XXXXXX";
  const int err = ::mkstemp(err_name);
  const auto start = std::chrono::steady_clock::now();
  std::fflush(stdout);
  const pid_t child = ::fork();
  if (child == 0) {
    ::dup2(err, 1);
    ::dup2(err, 2);
    const rlimit limit{8ul << 30, 8ul << 30};
    ::setrlimit(RLIMIT_AS, &limit);
    ::alarm(60);
    const Result r = reader.read(path);
    ::dprintf(pipe_ends[1], "%s points %ld faces %ld fields %s", r.ok ? "ok  " : "FAIL",
              r.points, r.faces, r.fields.c_str());
    ::_exit(0);
  }
  ::close(pipe_ends[1]);
  char verdict[4096] = {0};
  ssize_t length = 0;
  ssize_t got = 0;
  while ((got = ::read(pipe_ends[0], verdict + length,
                       sizeof verdict - 1 - static_cast<std::size_t>(length))) > 0)
    length += got;
  ::close(pipe_ends[0]);
  int status = 0;
  rusage usage{};
  ::wait4(child, &status, 0, &usage);
  const double ms = std::chrono::duration<double, std::milli>(
                        std::chrono::steady_clock::now() - start)
                        .count();
  const off_t printed = ::lseek(err, 0, SEEK_END);
  char first[121] = {0};
  ::pread(err, first, sizeof first - 1, 0);
  for (char& c : first)
    if (c == '\n' || c == '\r' || c == '\x1b')
      c = '|';
  ::close(err);
  ::unlink(err_name);
  std::string outcome = verdict;
  if (WIFSIGNALED(status))
    outcome = std::string("CRASH ") + ::strsignal(WTERMSIG(status));
  std::printf("%-22s %-28s %s | %.0f ms, %ld MB, stderr %ld B %s\n", reader.name,
              fs::path(path).filename().c_str(), outcome.c_str(), ms,
              usage.ru_maxrss / 1024, static_cast<long>(printed), first);
}

/** Malformed files, each named after what is wrong with it. */
std::vector<std::string>
writeMalformed(const fs::path& dir)
{
  const std::string ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                          "property float y\nproperty float z\n";
  const std::string pcd = "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                          "COUNT 1 1 1\nWIDTH 3\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\n"
                          "POINTS 3\n";
  const std::string three = "0 0 0\n1 0 0\n0 1 0\n";
  const std::vector<std::pair<std::string, std::string>> files = {
      {"empty.ply", ""},
      {"few_values.ply", ply + "end_header\n1 2 3\n4 5\n7 8 9\n"},
      {"word.ply", ply + "end_header\n1 2 3\n4 x 6\n7 8 9\n"},
      {"more_lines.ply", ply + "end_header\n" + three + "9 9 9\n"},
      {"no_z.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                   "property float y\nend_header\n1 2\n"},
      {"negative_count.ply", "ply\nformat ascii 1.0\nelement vertex -1\n"
                             "property float x\nproperty float y\nproperty float z\n"
                             "end_header\n1 2 3\n"},
      {"huge_count.ply", "ply\nformat binary_little_endian 1.0\n"
                         "element vertex 2000000000\nproperty float x\n"
                         "property float y\nproperty float z\nend_header\n" +
                             std::string(120, '\0')},
      {"truncated.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1000\n"
                        "property float x\nproperty float y\nproperty float z\n"
                        "end_header\n" +
                            std::string(120, '\0')},
      {"huge_list.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
                        "property float x\nproperty float y\nproperty float z\n"
                        "element face 1\nproperty list uint int vertex_indices\n"
                        "end_header\n" +
                            std::string(36, '\0') + "\xf0\xff\xff\xff" +
                            std::string(12, '\0')},
      {"face_range.ply", ply +
                             "element face 1\nproperty list uchar int vertex_indices\n"
                             "end_header\n" +
                             three + "3 0 1 7\n"},
      {"short.obj", "v 1 2\n"},
      {"word.obj", "v 1 x 3\n"},
      {"face_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"},
      {"face_zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"},
      {"face_behind.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -5 1 2\n"},
      {"face_huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999\n"},
      {"huge_vertices.off", "OFF\n2000000000 1 0\n0 0 0\n"},
      {"huge_faces.off", "OFF\n3 2000000000 0\n" + three},
      {"huge_face.off", "OFF\n3 1 0\n" + three + "4000000000 0 1 2\n"},
      {"face_range.off", "OFF\n3 1 0\n" + three + "3 0 1 7\n"},
      {"empty.pcd", ""},
      {"garbage.pcd", "hello world\n"},
      {"word.pcd", pcd + "DATA ascii\n1 2 3\n4 x 6\n7 8 9\n"},
      {"few_values.pcd", pcd + "DATA ascii\n1 2 3\n4 5\n7 8 9\n"},
      {"count_overflow.pcd", "VERSION 0.7\nFIELDS x y z w\nSIZE 4 4 4 4\nTYPE F F F F\n"
                             "COUNT 1 1 1 4611686018427387901\nWIDTH 10\nHEIGHT 1\n"
                             "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 10\nDATA binary\n" +
                                 std::string(400, '\0')},
      {"huge_points.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                          "COUNT 1 1 1\nWIDTH 2000000000\nHEIGHT 1\n"
                          "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2000000000\nDATA binary\n" +
                              std::string(120, '\0')},
      {"comments.xyz", "# two comment\n# lines\n1 2 3\n"},
      {"word.xyz", "1 2 3\n4 five 6\n"},
      {"short.xyz", "1 2 3\n4 5\n"},
      {"comma.xyz", "1,5 2 3\n"},
      {"binary.xyz", std::string("\x01\x02\x00\xff\n", 5)},
      {"six_columns.xyz", "1 2 3 0 0 1\n4 5 6 0 1 0\n"},
      {"a3d.pts", "# a3d\nd 0 0 0\np 1 2 3\nn 0 0 1\np 4 5 6\n"},
  };
  std::vector<std::string> paths;
  for (const auto& [name, contents] : files) {
    std::ofstream(dir / name, std::ios::binary) << contents;
    paths.push_back((dir / name).string());
  }
  return paths;
}

} // namespace

int
main(int argc, char** argv)
{
  std::vector<std::string> paths(argv + 1, argv + argc);
  fs::path temporary;
  if (paths.size() == 1 && paths[0] == "--malformed") {
    temporary =
        fs::temp_directory_path() / ("reader_survey_" + std::to_string(::getpid()));
    fs::create_directories(temporary);
    paths = writeMalformed(temporary);
  }
  for (const std::string& path : paths) {
    const std::string extension = fs::path(path).extension().string();
    for (const Reader& reader : readers)
      for (const std::string& e : reader.extensions)
        if (e == extension)
          survey(reader, path);
  }
  if (!temporary.empty())
    fs::remove_all(temporary);
  return 0;
}
