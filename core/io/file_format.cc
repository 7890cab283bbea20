#include "core/io/file_format.h"

#include <array>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"

namespace membrane {
namespace {

struct ExtensionEntry {
  absl::string_view extension;
  FileFormat format;
};

constexpr std::array<ExtensionEntry, 9> kExtensions = {{
    {".ply", FileFormat::kPly},
    {".obj", FileFormat::kObj},
    {".xyz", FileFormat::kXyz},
    {".txt", FileFormat::kXyz},
    {".pts", FileFormat::kXyz},
    {".pcd", FileFormat::kPcd},
    {".stl", FileFormat::kStl},
    {".drc", FileFormat::kDrc},
    {".off", FileFormat::kOff},
}};

constexpr FileFormat kReadPointCloud[] = {FileFormat::kPly, FileFormat::kObj, FileFormat::kXyz,
                                          FileFormat::kPcd, FileFormat::kDrc, FileFormat::kOff};
constexpr FileFormat kWritePointCloud[] = {FileFormat::kPly, FileFormat::kXyz, FileFormat::kObj,
                                           FileFormat::kDrc};
constexpr FileFormat kReadMesh[] = {FileFormat::kPly, FileFormat::kObj, FileFormat::kStl,
                                    FileFormat::kDrc, FileFormat::kOff};
constexpr FileFormat kWriteMesh[] = {FileFormat::kPly, FileFormat::kObj, FileFormat::kStl,
                                     FileFormat::kDrc};

absl::string_view UseDescription(FileUse use) {
  switch (use) {
    case FileUse::kReadPointCloud: return "point clouds can be read from";
    case FileUse::kWritePointCloud: return "point clouds can be written to";
    case FileUse::kReadMesh: return "meshes can be read from";
    case FileUse::kWriteMesh: return "meshes can be written to";
  }
  return "";
}

}  // namespace

absl::Span<const FileFormat> SupportedFormats(FileUse use) {
  switch (use) {
    case FileUse::kReadPointCloud: return kReadPointCloud;
    case FileUse::kWritePointCloud: return kWritePointCloud;
    case FileUse::kReadMesh: return kReadMesh;
    case FileUse::kWriteMesh: return kWriteMesh;
  }
  return {};
}

std::string FormatExtensions(FileFormat format) {
  std::vector<absl::string_view> extensions;
  for (const ExtensionEntry& entry : kExtensions) {
    if (entry.format == format) extensions.push_back(entry.extension);
  }
  return absl::StrJoin(extensions, ", ");
}

absl::string_view FormatName(FileFormat format) {
  switch (format) {
    case FileFormat::kPly: return "PLY";
    case FileFormat::kObj: return "OBJ";
    case FileFormat::kXyz: return "XYZ";
    case FileFormat::kPcd: return "PCD";
    case FileFormat::kStl: return "STL";
    case FileFormat::kDrc: return "Draco";
    case FileFormat::kOff: return "OFF";
  }
  return "unknown";
}

absl::StatusOr<FileFormat> FormatFromPath(absl::string_view path, FileUse use) {
  const size_t slash = path.find_last_of('/');
  const absl::string_view file_name =
      slash == absl::string_view::npos ? path : path.substr(slash + 1);
  const size_t dot = file_name.find_last_of('.');
  const std::string extension =
      dot == absl::string_view::npos ? "" : absl::AsciiStrToLower(file_name.substr(dot));
  const absl::Span<const FileFormat> supported = SupportedFormats(use);
  for (const ExtensionEntry& entry : kExtensions) {
    if (entry.extension != extension) continue;
    for (FileFormat format : supported) {
      if (format == entry.format) return format;
    }
  }
  std::vector<std::string> listed;
  for (FileFormat format : supported) listed.push_back(FormatExtensions(format));
  return absl::InvalidArgumentError(
      absl::StrCat("'", path, "': ",
                   extension.empty() ? "no file extension"
                                     : absl::StrCat("unsupported extension '", extension, "'"),
                   "; ", UseDescription(use), " ", absl::StrJoin(listed, ", ")));
}

}  // namespace membrane
