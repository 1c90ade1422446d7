#pragma once
// Private: cairo's output streams into a file we open ourselves, so that a refusal names the
// path and the system's reason, an existing file is never replaced by accident (exclusive
// creation) and a failed write leaves no partial file.
#include <cairo.h>

#include <cstdio>
#include <string>

namespace pcl_ls3d {
namespace maps {
namespace detail {

/// \brief A file being written through a cairo stream.
class OutputFile
{
public:
  /// Opens \a path for writing; with \a overwrite false, fails when it exists.
  OutputFile(const std::string& path, bool overwrite);
  /// Removes the file unless commit() succeeded.
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile&
  operator=(const OutputFile&) = delete;

  bool
  isOpen() const
  {
    return file_ != nullptr;
  }
  /// cairo_write_func_t; the closure is the OutputFile.
  static cairo_status_t
  write(void* closure, const unsigned char* data, unsigned int length);
  /// Closes the file after checking \a status (cairo's, of the finished surface) and every
  /// write; false with "cannot write PATH: reason" in \a error, the file then removed.
  bool
  commit(cairo_status_t status, std::string& error);
  /// "cannot write PATH: reason" for a file that did not open.
  std::string
  openError() const;

private:
  std::string path_;
  std::FILE* file_ = nullptr;
  int errno_ = 0;  // the first system error seen
  bool committed_ = false;
};

}  // namespace detail
}  // namespace maps
}  // namespace pcl_ls3d
