// SPDX-License-Identifier: GPL-3.0-or-later
//
// The writers build the whole file in memory and write it at once: a mesh of a million
// triangles is a few tens of megabytes, and one write makes a failure simple to report.
// Every file is written beside its target and renamed into place (writeFile), so that
// a failed write never leaves a partial file, nor destroys the one that was there.
#include <pcl/cocone/io/writers.h>

#include <pcl/cocone/io/point_io.h>

#include <pcl/io/pcd_io.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>

namespace pcl {
namespace cocone {

namespace {

namespace fs = std::filesystem;
using Triangle = std::array<std::uint32_t, 3>;

/** Stores the 4 bytes of \a bits at \a p least significant first, whatever the host
 * order; returns the byte after them. */
char*
storeLittleEndian(char* p, std::uint32_t bits)
{
  for (int shift = 0; shift < 32; shift += 8)
    *p++ = static_cast<char>((bits >> shift) & 0xffu);
  return p;
}

/** Appends the shortest text that reads back as the same float. */
void
appendText(std::string& out, float value)
{
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

void
appendText(std::string& out, std::uint64_t value)
{
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

std::string
meshAsPly(const std::vector<std::array<float, 3>>& vertices,
          const std::vector<Triangle>& triangles, const std::string& creator)
{
  std::string out = "ply\nformat binary_little_endian 1.0\n"
                    "comment written by " +
                    creator + "\n" + "element vertex " +
                    std::to_string(vertices.size()) + "\n" +
                    "property float x\nproperty float y\nproperty float z\n" +
                    "element face " + std::to_string(triangles.size()) + "\n" +
                    "property list uchar int vertex_indices\nend_header\n";
  // The body is sized once and filled through a pointer: appended byte by byte, 10M
  // vertices and 20M triangles took 0.9 to 1.3 s to encode, now 0.57 s
  // (docs/performance.md). storeLittleEndian's four byte stores compile to one on a
  // little-endian host.
  const std::size_t header_size = out.size();
  out.resize(header_size + 12 * vertices.size() + 13 * triangles.size());
  char* p = &out[header_size];
  for (const auto& v : vertices)
    for (const float c : v) {
      std::uint32_t bits;
      std::memcpy(&bits, &c, sizeof bits);
      p = storeLittleEndian(p, bits);
    }
  for (const Triangle& t : triangles) {
    *p++ = static_cast<char>(3);
    for (const std::uint32_t i : t)
      p = storeLittleEndian(p, i);
  }
  return out;
}

std::string
meshAsVtk(const std::vector<std::array<float, 3>>& vertices,
          const std::vector<Triangle>& triangles, const std::string& creator)
{
  std::string out = "# vtk DataFile Version 3.0\nwritten by " + creator +
                    "\nASCII\nDATASET POLYDATA\nPOINTS " +
                    std::to_string(vertices.size()) + " float\n";
  for (const auto& v : vertices) {
    appendText(out, v[0]);
    out += ' ';
    appendText(out, v[1]);
    out += ' ';
    appendText(out, v[2]);
    out += '\n';
  }
  out += "POLYGONS " + std::to_string(triangles.size()) + " " +
         std::to_string(4 * triangles.size()) + "\n";
  for (const Triangle& t : triangles) {
    out += '3';
    for (const std::uint32_t i : t) {
      out += ' ';
      appendText(out, std::uint64_t{i});
    }
    out += '\n';
  }
  return out;
}

std::string
meshAsObj(const std::vector<std::array<float, 3>>& vertices,
          const std::vector<Triangle>& triangles, const std::string& creator)
{
  std::string out = "# written by " + creator + ": " + std::to_string(vertices.size()) +
                    " vertices, " + std::to_string(triangles.size()) + " triangles\n";
  for (const auto& v : vertices) {
    out += 'v';
    for (const float c : v) {
      out += ' ';
      appendText(out, c);
    }
    out += '\n';
  }
  for (const Triangle& t : triangles) {
    out += 'f';
    for (const std::uint32_t i : t) {
      out += ' ';
      appendText(out, std::uint64_t{i} + 1); // OBJ counts from 1
    }
    out += '\n';
  }
  return out;
}

bool
failed(std::string* error, const std::string& message)
{
  if (error)
    *error = utf8Escaped(message);
  return false;
}

std::string
lowerCase(std::string text)
{
  std::transform(text.begin(), text.end(), text.begin(), [](char c) {
    return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
  });
  return text;
}

/** The lower-case extension of \a path when saveMesh writes it, "" otherwise. */
std::string
meshExtension(const std::string& path)
{
  const std::string extension = lowerCase(fs::path(path).extension().string());
  return extension == ".ply" || extension == ".vtk" || extension == ".obj" ? extension
                                                                           : "";
}

/** Writes all \a size bytes to \a fd, going on after partial writes and interrupts;
 * false with errno set on an error (EFBIG past a file size limit when SIGXFSZ is
 * ignored, ENOSPC, EDQUOT, EIO). */
bool
writeAll(int fd, const void* data, std::size_t size)
{
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t written = ::write(fd, p, size);
    if (written < 0) {
      if (errno == EINTR)
        continue;
      return false;
    }
    p += written;
    size -= static_cast<std::size_t>(written);
  }
  return true;
}

} // namespace

bool
writeFile(const std::string& path, const void* data, std::size_t size,
          std::string* error)
{
  const auto failWith = [&](int code) {
    return failed(error, "cannot write " + path + ": " +
                             (code ? std::strerror(code) : "write error"));
  };
  // A symbolic link stays a link: the file it names (through any chain of links, up to
  // the kernel's own limit of 40) is the one replaced.
  fs::path target = path;
  std::error_code ec;
  for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(target, ec));
       ++hops) {
    const fs::path link = fs::read_symlink(target, ec);
    if (ec)
      break;
    target = link.is_absolute() ? link : target.parent_path() / link;
  }
  struct stat existing;
  const bool exists = ::stat(target.c_str(), &existing) == 0;
  // The checks opening the file for writing would have made: a file we may not write
  // is not replaced behind its owner's back.
  if (exists && ::access(target.c_str(), W_OK) != 0)
    return failWith(errno);
  // A device or a FIFO cannot be replaced by a rename; it is written as it is.
  if (exists && !S_ISREG(existing.st_mode)) {
    const int fd = ::open(target.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0)
      return failWith(errno);
    const int code = writeAll(fd, data, size) ? 0 : errno;
    if (::close(fd) != 0 || code != 0)
      return failWith(code ? code : errno);
    if (error)
      error->clear();
    return true;
  }

  // The bytes go to a new file beside the target, which a rename then puts in its
  // place: until then the target is untouched, whatever fails (a full disk, a quota,
  // a file size limit), and afterwards it is complete. So OUTPUT may be INPUT.
  static std::atomic<unsigned> counter{0};
  const fs::path folder = target.parent_path();
  const std::string stem =
      "." + target.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-";
  std::string temporary;
  int fd = -1;
  while (fd < 0) {
    temporary = (folder / (stem + std::to_string(counter++))).string();
    // 0666 as fopen uses, so that the user's umask applies as it always did.
    fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST)
      return failWith(errno);
  }
  int code = writeAll(fd, data, size) ? 0 : errno;
  // A file replaced keeps its permissions.
  if (code == 0 && exists && ::fchmod(fd, existing.st_mode & 07777) != 0)
    code = errno;
  // The data must be on the disk before the name points at them; a full disk may
  // also show up only here.
  if (code == 0 && ::fsync(fd) != 0)
    code = errno;
  if (::close(fd) != 0 && code == 0)
    code = errno ? errno : EIO;
  if (code == 0 && ::rename(temporary.c_str(), target.c_str()) != 0)
    code = errno;
  if (code != 0) {
    ::unlink(temporary.c_str());
    return failWith(code);
  }
  if (error)
    error->clear();
  return true;
}

bool
saveCloud(const std::string& path, const pcl::PCLPointCloud2& cloud, std::string* error)
{
  // PCL's PCDWriter::writeBinary creates files with mode 0600, writes through mmap (a
  // full disk gives "Error during write ()!" without the reason, or SIGBUS), throws
  // when it cannot open the file and logs its locking at debug level. Its header with
  // the data written here is the same file, made with the user's umask and failing
  // with the system's reason.
  if (cloud.data.size() !=
      static_cast<std::size_t>(cloud.width) * cloud.height * cloud.point_step)
    return failed(error, "internal error: the cloud for " + path +
                             " has an inconsistent data size");
  std::string contents = pcl::PCDWriter().generateHeaderBinary(
      cloud, Eigen::Vector4f::Zero(), Eigen::Quaternionf::Identity());
  contents += "DATA binary\n";
  contents.append(reinterpret_cast<const char*>(cloud.data.data()), cloud.data.size());
  return writeFile(path, contents.data(), contents.size(), error);
}

bool
saveMesh(const std::string& path, const std::vector<std::array<float, 3>>& vertices,
         const std::vector<Triangle>& triangles, const std::string& creator,
         std::string* error)
{
  const std::string extension = meshExtension(path);
  std::string contents;
  if (extension == ".ply")
    contents = meshAsPly(vertices, triangles, creator);
  else if (extension == ".vtk")
    contents = meshAsVtk(vertices, triangles, creator);
  else if (extension == ".obj")
    contents = meshAsObj(vertices, triangles, creator);
  else
    return failed(error,
                  "unsupported mesh format '" + path + "' (expected .ply, .vtk, .obj)");
  return writeFile(path, contents.data(), contents.size(), error);
}

bool
isMeshFormat(const std::string& path)
{
  return !meshExtension(path).empty();
}

bool
meshForWriting(const pcl::PointCloud<pcl::PointXYZ>& points,
               const std::vector<Triangle>& triangles, const pcl::Indices& far_points,
               MeshForWriting& mesh, std::string* error)
{
  mesh = MeshForWriting();
  const auto fail = [&](const std::string& message) {
    mesh = MeshForWriting();
    return failed(error, message);
  };
  std::vector<std::uint8_t> far(points.size(), 0);
  for (const pcl::index_t i : far_points) {
    if (i < 0 || static_cast<std::size_t>(i) >= points.size())
      return fail("far point " + std::to_string(i) + " is not a point of the cloud (" +
                  std::to_string(points.size()) + " points)");
    far[static_cast<std::size_t>(i)] = 1;
  }
  constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> id(points.size(), none);
  mesh.vertices.reserve(points.size() - std::min(points.size(), far_points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const pcl::PointXYZ& p = points[i];
    if (far[i])
      ++mesh.far_dropped;
    else if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      ++mesh.non_finite_dropped;
    else {
      id[i] = static_cast<std::uint32_t>(mesh.vertices.size());
      mesh.vertices.push_back({p.x, p.y, p.z});
    }
  }
  mesh.triangles.resize(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = triangles[t][k];
      if (v >= id.size() || id[v] == none)
        return fail(
            "triangle " + std::to_string(t) + " uses point " + std::to_string(v) +
            (v >= id.size() ? ", beyond the cloud" : ", which is not finite or far"));
      mesh.triangles[t][k] = id[v];
    }
  if (error)
    error->clear();
  return true;
}

} // namespace cocone
} // namespace pcl
