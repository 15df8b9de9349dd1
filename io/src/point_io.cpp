// SPDX-License-Identifier: GPL-3.0-or-later
//
// The public readers: the file is read whole, the reader is chosen by the extension,
// and whatever a reader throws becomes the one-line reason. Each format's reader is in
// a file of its own (readers.h), whose header says why it is ours or a library's.
#include <pcl/cocone/io/point_io.h>

#include "cloud_layout.h"
#include "readers.h"
#include "text_scan.h"

#include <algorithm>
#include <exception>
#include <filesystem>
#include <new>

namespace pcl {
namespace cocone {

namespace {

using namespace io_internal;

enum class Format
{
  pcd,
  ply,
  obj,
  off,
  columns,
  las,
  unknown
};

Format
formatOf(const std::string& path, std::string& extension)
{
  extension = std::filesystem::path(path).extension().string();
  std::string lower = extension;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](char c) {
    return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
  });
  if (lower == ".pcd")
    return Format::pcd;
  if (lower == ".ply")
    return Format::ply;
  if (lower == ".obj")
    return Format::obj;
  if (lower == ".off")
    return Format::off;
  if (lower == ".xyz" || lower == ".pts" || lower == ".txt")
    return Format::columns;
  // A .laz file goes to the LAS reader too: it refuses compressed data with the way to
  // convert it, and reads a file that is LAS under that name.
  if (lower == ".las" || lower == ".laz")
    return Format::las;
  return Format::unknown;
}

/** Runs \a body and turns whatever it throws into the one-line reason. */
template <typename Body>
bool
guarded(const std::string& path, std::string* error, Body body)
{
  std::string reason;
  try {
    body();
    if (error)
      error->clear();
    return true;
  }
  catch (const FormatError& e) {
    reason = e.message;
  }
  catch (const std::bad_alloc&) {
    reason = path + ": out of memory";
  }
  catch (const std::exception& e) {
    reason = path + ": " + e.what();
  }
  catch (...) {
    reason = path + ": unexpected error";
  }
  if (error)
    *error = utf8Escaped(oneLine(std::move(reason)));
  return false;
}

} // namespace

bool
loadPointSamples(const std::string& path, pcl::PCLPointCloud2& cloud,
                 std::string* error)
{
  const bool ok = guarded(path, error, [&] {
    cloud = pcl::PCLPointCloud2();
    const Source source(path);
    std::string extension;
    const Format format = formatOf(path, extension);
    if (format == Format::unknown)
      source.fail("unknown extension " + excerpt(extension) +
                  " (readable: .pcd .ply .obj .off .xyz .pts .txt .las)");
    std::string text;
    readFile(source, path, text);
    std::vector<float> xyz;
    switch (format) {
    case Format::pcd:
      readPcd(source, text, cloud);
      break;
    case Format::ply:
      readPlyVertices(source, text, cloud);
      break;
    case Format::las:
      readLas(source, text, cloud);
      break;
    case Format::obj:
      readObj(source, text, xyz, nullptr);
      break;
    case Format::off:
      readOff(source, text, xyz, nullptr);
      break;
    case Format::columns:
      readColumns(source, text, xyz);
      break;
    case Format::unknown:
      break;
    }
    if (format == Format::obj || format == Format::off || format == Format::columns) {
      if (xyz.empty())
        source.fail(format == Format::obj ? "no points (no 'v x y z' line)"
                    : format == Format::off
                        ? "no points (the vertex count is 0)"
                        : "no points (only blank or comment lines)");
      makeXyzCloud(xyz, cloud);
    }
  });
  if (!ok)
    cloud = pcl::PCLPointCloud2();
  return ok;
}

bool
loadMeshFaces(const std::string& path, std::vector<pcl::Vertices>& faces,
              std::string* error)
{
  const bool ok = guarded(path, error, [&] {
    faces.clear();
    const Source source(path);
    std::string extension;
    const Format format = formatOf(path, extension);
    if (format != Format::ply && format != Format::obj && format != Format::off)
      source.fail("not a mesh format (faces are read from .ply, .obj and .off)");
    std::string text;
    readFile(source, path, text);
    std::vector<float> xyz;
    if (format == Format::ply)
      readPlyFaces(source, text, faces);
    else if (format == Format::obj)
      readObj(source, text, xyz, &faces);
    else
      readOff(source, text, xyz, &faces);
  });
  if (!ok)
    faces.clear();
  return ok;
}

} // namespace cocone
} // namespace pcl