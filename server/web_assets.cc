#include "server/web_assets.h"

#include <dirent.h>
#include <sys/stat.h>

#include <utility>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "core/io/file_bytes.h"
#include "server/client_text.h"

namespace membrane::server {
namespace {

std::string ContentTypeOf(const std::string& name) {
  if (absl::EndsWith(name, ".html")) return "text/html; charset=utf-8";
  if (absl::EndsWith(name, ".js")) return "text/javascript; charset=utf-8";
  if (absl::EndsWith(name, ".css")) return "text/css; charset=utf-8";
  if (absl::EndsWith(name, ".png")) return "image/png";
  if (absl::EndsWith(name, ".svg")) return "image/svg+xml";
  return "application/octet-stream";
}

bool IsRegularFile(const std::string& path) {
  struct stat s;
  return stat(path.c_str(), &s) == 0 && S_ISREG(s.st_mode);
}

}  // namespace

absl::StatusOr<WebAssets> WebAssets::Load(const std::string& web_dir,
                                          const std::string& three_dir) {
  WebAssets assets;
  const auto add = [&](const std::string& url, const std::string& path,
                       const std::string& provider) -> absl::Status {
    absl::StatusOr<std::string> bytes = ReadFileBytes(path);
    if (!bytes.ok()) {
      return absl::UnavailableError(absl::StrCat("the web console's file ", path,
                                                 " cannot be read (", provider, "): ",
                                                 bytes.status().message()));
    }
    assets.files_[url] = File{ContentTypeOf(path),
                              std::make_shared<const std::string>(*std::move(bytes))};
    return absl::OkStatus();
  };
  DIR* dir = opendir(web_dir.c_str());
  if (dir == nullptr) {
    return absl::UnavailableError(absl::StrCat(
        "the web console's directory ", web_dir, " cannot be read (--web-dir)"));
  }
  absl::Status status;
  while (dirent* entry = readdir(dir)) {
    const std::string name = entry->d_name;
    const std::string path = web_dir + "/" + name;
    if (name.empty() || name[0] == '.' || !IsRegularFile(path)) continue;
    status.Update(add("/" + name, path, "--web-dir"));
  }
  closedir(dir);
  if (!status.ok()) return status;
  if (assets.files_.count("/index.html") == 0) {
    return absl::UnavailableError(
        absl::StrCat("the web console's directory ", web_dir, " has no index.html (--web-dir)"));
  }
  assets.files_["/"] = assets.files_["/index.html"];
  for (const auto& [url, file] : {std::pair{"/three/three.min.js", kThreeJsFile},
                                  std::pair{"/three/OrbitControls.js", kOrbitControlsFile}}) {
    if (absl::Status s = add(url, three_dir + "/" + file,
                             "Debian's libjs-three, or --three-js-dir");
        !s.ok()) {
      return s;
    }
  }
  return assets;
}

HttpResponse WebAssets::Serve(const HttpRequest& request) const {
  const auto found = files_.find(request.path);
  if (found == files_.end()) {
    return ErrorResponse(
        absl::NotFoundError(absl::StrCat("no file '", ClientText(request.path), "' here")));
  }
  if (request.method != "GET" && request.method != "HEAD") {
    HttpResponse response = ErrorResponse(absl::UnimplementedError(
        absl::StrCat(ClientText(request.path), " takes GET, not ", ClientText(request.method))));
    response.headers.push_back({"Allow", "GET, HEAD"});
    return response;
  }
  HttpResponse response;
  response.content_type = found->second.content_type;
  response.ShareBody(found->second.bytes);
  // The page and three.js change only with membraned: a reload checks, a tab keeps its copy.
  response.headers.push_back({"Cache-Control", "no-cache"});
  // Every script, style and request is membraned's own; previews are blob URLs. A page that
  // somehow got markup injected could run nothing and send nothing elsewhere.
  response.headers.push_back(
      {"Content-Security-Policy",
       "default-src 'self'; img-src 'self' blob:; object-src 'none'; base-uri 'none'; "
       "frame-ancestors 'none'"});
  return response;
}

}  // namespace membrane::server
