// SPDX-License-Identifier: GPL-3.0-or-later
//
// JobFiles (job_files.h). A file is a header line (magic, job, jobs, fingerprint),
// the message's length, and the message.
#include "job_files.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <thread>

namespace pcl {
namespace cocone {
namespace tools {

namespace {

// The tiles travel in the library's in-memory layout: the version is part of the
// header, so that files of another release are refused rather than misread.
const char kMagic[] = "pcl_cocone " PCL_COCONE_VERSION " tiles";

std::string
headerOf(unsigned job, unsigned jobs, const std::string& fingerprint)
{
  return std::string(kMagic) + " job " + std::to_string(job) + " of " +
         std::to_string(jobs) + " " + fingerprint + "\n";
}

/** Opens the file of job \a job at \a path and checks its header; throws with the
 * reason it cannot be used. */
std::ifstream
openChecked(const std::string& path, unsigned job, unsigned jobs,
            const std::string& fingerprint)
{
  std::error_code error;
  if (!std::filesystem::exists(path, error))
    throw std::runtime_error(path + " is missing: run jobs 1 to " +
                             std::to_string(jobs - 1) + " first");
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw std::runtime_error("cannot read " + path);
  std::string header;
  std::getline(in, header);
  if (!in || header.compare(0, sizeof kMagic - 1, kMagic) != 0)
    throw std::runtime_error(path + " is no tile file of this version of pcl_cocone");
  if (header + "\n" != headerOf(job, jobs, fingerprint))
    throw std::runtime_error(path + " was made from another input or other options");
  return in;
}

} // namespace

std::uint64_t
fingerprintBytes(const void* bytes, std::size_t size, std::uint64_t hash)
{
  const auto* p = static_cast<const unsigned char*>(bytes);
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= p[i];
    hash *= 0x100000001b3ull;
  }
  return hash;
}

JobFiles::JobFiles(unsigned job, unsigned jobs, std::string output,
                   std::string fingerprint, double wait_seconds)
  : job_(job), jobs_(jobs), output_(std::move(output)),
    fingerprint_(std::move(fingerprint)), wait_seconds_(wait_seconds)
{}

std::string
JobFiles::fileOf(unsigned job) const
{
  return output_ + ".job-" + std::to_string(job) + "-of-" + std::to_string(jobs_) +
         ".tiles";
}

std::vector<std::vector<std::uint8_t>>
JobFiles::gatherToRoot(const std::vector<std::uint8_t>& message)
{
  if (job_ != 0) {
    const std::string path = fileOf(job_);
    // A name of its own, so that two copies of one job (a requeued array task) do not
    // write into one file; the rename is atomic, so job 0 sees a whole file or none.
    const std::string temporary =
        path + ".partial-" + std::to_string(static_cast<long>(::getpid()));
    const auto give_up = [&](const std::string& reason) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw std::runtime_error(reason);
    };
    {
      std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
      const std::string header = headerOf(job_, jobs_, fingerprint_);
      const std::uint64_t length = message.size();
      out.write(header.data(), std::streamsize(header.size()));
      out.write(reinterpret_cast<const char*>(&length), sizeof length);
      out.write(reinterpret_cast<const char*>(message.data()),
                std::streamsize(message.size()));
      out.close();
      if (!out)
        give_up("cannot write " + temporary);
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error)
      give_up("cannot rename " + temporary + " to " + path + ": " + error.message());
    return {};
  }
  if (!message.empty())
    return std::vector<std::vector<std::uint8_t>>(jobs_); // job 0 failed: no wait
  // The files still missing are polled, a little less often the longer the wait (a
  // shared file system is not to be hammered), until the deadline.
  using Clock = std::chrono::steady_clock;
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(
                         std::chrono::duration<double>(wait_seconds_));
  std::vector<std::vector<std::uint8_t>> messages(jobs_);
  for (unsigned r = 1; r < jobs_; ++r) {
    const std::string path = fileOf(r);
    std::chrono::milliseconds pause(100);
    std::error_code error;
    while (!std::filesystem::exists(path, error) && Clock::now() < deadline) {
      std::this_thread::sleep_for(
          std::min<Clock::duration>(pause, deadline - Clock::now()));
      pause = std::min(2 * pause, std::chrono::milliseconds(5000));
    }
    if (wait_seconds_ > 0 && !std::filesystem::exists(path, error))
      throw std::runtime_error(
          error ? "cannot look for " + path + ": " + error.message()
                : path + " did not appear within the " +
                      std::to_string(static_cast<long long>(wait_seconds_)) +
                      " s of -wait: did job " + std::to_string(r) + " run?");
    std::ifstream in = openChecked(path, r, jobs_, fingerprint_);
    std::uint64_t length = 0;
    in.read(reinterpret_cast<char*>(&length), sizeof length);
    const auto here = in.tellg();
    in.seekg(0, std::ios::end);
    const auto end = in.tellg();
    if (!in || here < 0 || std::uint64_t(end - here) != length)
      throw std::runtime_error(path + " is truncated");
    in.seekg(here);
    messages[r].resize(length);
    in.read(reinterpret_cast<char*>(messages[r].data()), std::streamsize(length));
    if (!in)
      throw std::runtime_error("cannot read " + path);
  }
  return messages;
}

void
JobFiles::checkOthersReady() const
{
  for (unsigned r = 1; r < jobs_; ++r) {
    std::error_code error;
    if (wait_seconds_ > 0 && !std::filesystem::exists(fileOf(r), error))
      continue; // still running: waited for once job 0's own tiles are built
    openChecked(fileOf(r), r, jobs_, fingerprint_);
  }
}

void
JobFiles::removeFiles() const
{
  for (unsigned r = 1; r < jobs_; ++r) {
    std::error_code ignored;
    std::filesystem::remove(fileOf(r), ignored);
  }
}

} // namespace tools
} // namespace cocone
} // namespace pcl
