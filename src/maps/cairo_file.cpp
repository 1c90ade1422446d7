#include "cairo_file.h"

#include <cerrno>
#include <cstring>

namespace pcl_ls3d {
namespace maps {
namespace detail {

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
    std::remove(path_.c_str());
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
  const bool flushed = std::fflush(f) == 0;
  if (!flushed && errno_ == 0)
    errno_ = errno;
  const bool closed = std::fclose(f) == 0;
  if (!closed && errno_ == 0)
    errno_ = errno;
  if (status == CAIRO_STATUS_SUCCESS && flushed && closed) {
    committed_ = true;
    return true;
  }
  std::remove(path_.c_str());
  error = "cannot write " + path_ + ": " +
          (errno_ != 0 ? std::strerror(errno_) : cairo_status_to_string(status));
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
