#pragma once
// Private: GDAL set-up shared by the maps sources (drivers registered once, errors kept quiet
// and readable as one line).
#include <cpl_error.h>
#include <gdal.h>

#include <mutex>
#include <string>

namespace pcl_ls3d {
namespace maps {
namespace detail {

inline void
initGdal()
{
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

/// Silences GDAL's stderr output while alive; lastError() gives GDAL's last message.
class QuietGdal
{
public:
  QuietGdal()
  {
    initGdal();
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
  }
  ~QuietGdal()
  {
    CPLPopErrorHandler();
  }
  QuietGdal(const QuietGdal&) = delete;
  QuietGdal&
  operator=(const QuietGdal&) = delete;

  static std::string
  lastError()
  {
    const char* m = CPLGetLastErrorMsg();
    return m && *m ? std::string(m) : std::string("unknown GDAL error");
  }
};

}  // namespace detail
}  // namespace maps
}  // namespace pcl_ls3d
