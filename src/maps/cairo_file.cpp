#include "cairo_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace pcl_ls3d {
namespace maps {
namespace detail {

namespace {

// Removes what a failed write left; a device or pipe written to (/dev/full) is not ours to remove.
void
removePartial(const std::string& path)
{
  std::error_code ec;
  if (std::filesystem::is_regular_file(path, ec))
    std::filesystem::remove(path, ec);
}

}  // namespace

OutputFile::OutputFile(const std::string& path, bool overwrite) : path_(path)
{
  errno = 0;
  file_ = std::fopen(path.c_str(), overwrite ? "wb" : "wbx");
  if (!file_)
    errno_ = errno;
}

OutputFile::~OutputFile()
{
  if (committed_)
    return;
  if (file_) {
    std::fclose(file_);
    removePartial(path_);
  }
}

cairo_status_t
OutputFile::write(void* closure, const unsigned char* data, unsigned int length)
{
  auto* self = static_cast<OutputFile*>(closure);
  if (std::fwrite(data, 1, length, self->file_) == length)
    return CAIRO_STATUS_SUCCESS;
  if (self->errno_ == 0)
    self->errno_ = errno ? errno : EIO;
  return CAIRO_STATUS_WRITE_ERROR;
}

bool
OutputFile::commit(cairo_status_t status, std::string& error)
{
  std::FILE* f = file_;
  file_ = nullptr;
  const bool flushed = std::fflush(f) == 0 && !std::ferror(f);
  if (!flushed && errno_ == 0)
    errno_ = errno ? errno : EIO;
  const bool closed = std::fclose(f) == 0;
  if (!closed && errno_ == 0)
    errno_ = errno ? errno : EIO;
  // cairo 1.16 does not report every failed stream write in the PDF surface's status, so a
  // write error seen here (errno_) fails the file whatever cairo says.
  if (status == CAIRO_STATUS_SUCCESS && flushed && closed && errno_ == 0) {
    committed_ = true;
    return true;
  }
  removePartial(path_);
  error =
      "cannot write " + path_ + ": " + (errno_ != 0 ? std::strerror(errno_) : cairo_status_to_string(status));
  return false;
}

std::string
OutputFile::openError() const
{
  if (errno_ == EEXIST)
    return path_ + " exists (not overwritten)";
  return "cannot write " + path_ + ": " + std::strerror(errno_ ? errno_ : EIO);
}

}  // namespace detail
}  // namespace maps
}  // namespace pcl_ls3d
