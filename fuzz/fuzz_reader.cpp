// SPDX-License-Identifier: GPL-3.0-or-later
//
// A libFuzzer target for one reader of pcl_cocone_io, chosen at compile time
// (PCL_COCONE_FUZZ_<format>). It feeds the bytes to the reader as the contents of a
// file, the way loadPointSamples and loadMeshFaces do after reading one. A refusal (the
// reader's FormatError, or the documented 4 GiB limit as std::length_error) is the
// expected end of a malformed input; anything else, a crash, a sanitizer report, an
// uncaught exception such as std::bad_alloc, a leak, a timeout or running out of
// memory, is a finding.
#include "readers.h"

#include <pcl/cocone/io/point_io.h>

#include <pcl/console/print.h>

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace io = pcl::cocone::io_internal;

extern "C" int
LLVMFuzzerInitialize(int*, char***)
{
  // PCL's reader reports every problem on stderr: noise at millions of inputs.
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  return 0;
}

namespace {

/** Runs \a read, accepting a refusal as its end. */
template <typename Read>
void
expectEnd(Read read)
{
  try {
    read();
  }
  catch (const io::FormatError&) {
  }
  catch (const std::length_error&) {
  }
}

} // namespace

extern "C" int
LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const std::string name = "input";
  const io::Source source(name);
  std::vector<float> xyz;
  std::vector<pcl::Vertices> faces;
  pcl::PCLPointCloud2 cloud;
#if defined(PCL_COCONE_FUZZ_pcd)
  expectEnd([&] { io::readPcd(source, text, cloud); });
#elif defined(PCL_COCONE_FUZZ_ply)
  expectEnd([&] { io::readPlyVertices(source, text, cloud); });
  expectEnd([&] { io::readPlyFaces(source, text, faces); });
#elif defined(PCL_COCONE_FUZZ_obj)
  expectEnd([&] { io::readObj(source, text, xyz, &faces); });
#elif defined(PCL_COCONE_FUZZ_off)
  expectEnd([&] { io::readOff(source, text, xyz, &faces); });
  xyz.clear();
  expectEnd([&] { io::readOff(source, text, xyz, nullptr); });
#elif defined(PCL_COCONE_FUZZ_columns)
  expectEnd([&] { io::readColumns(source, text, xyz); });
#elif defined(PCL_COCONE_FUZZ_las)
  expectEnd([&] { io::readLas(source, text, cloud); });
#else
#error "define PCL_COCONE_FUZZ_<format>"
#endif
  // The messages of a refusal are built from the file's bytes too.
  static_cast<void>(pcl::cocone::utf8Escaped(text));
  return 0;
}
