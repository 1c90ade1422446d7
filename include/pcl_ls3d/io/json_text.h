#pragma once
/// \file json_text.h
/// \brief The one way pcl_ls3d turns JSON into text: every tool's report, the generators' truth
///        files and the comparison results go through toJsonText().

#include <string>

namespace pcl_ls3d {
namespace io {

/// `json.dump(indent)`, except that bytes which are not valid UTF-8 (a LAS header's system
/// identifier or generating software, a file name in Latin-1) are written as U+FFFD instead of
/// throwing nlohmann::json::type_error 316. Templated on the JSON type so that this header does
/// not make nlohmann_json a dependency of every user of the library.
template <typename Json>
std::string
toJsonText(const Json& json, int indent = -1)
{
  return json.dump(indent, ' ', false, Json::error_handler_t::replace);
}

}  // namespace io
}  // namespace pcl_ls3d
