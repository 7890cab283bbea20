// The web console's files, read once when membraned starts: the page's own (server/web,
// installed beside membraned) and three.js with its orbit controls from Debian's libjs-three.
// Nothing is fetched from elsewhere: the browser gets every file from membraned.
#ifndef MEMBRANE_SERVER_WEB_ASSETS_H_
#define MEMBRANE_SERVER_WEB_ASSETS_H_

#include <map>
#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "server/http_api.h"

namespace membrane::server {

// The files of three.js that the page loads, relative to libjs-three's directory.
inline constexpr const char* kThreeJsFile = "build/three.min.js";
inline constexpr const char* kOrbitControlsFile = "examples/js/controls/OrbitControls.js";

class WebAssets {
 public:
  // Every regular file of `web_dir` (index.html among them), served as /NAME (index.html also
  // as /), and three.js's kThreeJsFile and kOrbitControlsFile of `three_dir`, served as
  // /three/three.min.js and /three/OrbitControls.js. Unavailable naming the file (and the
  // package or flag that provides it) when one is missing or unreadable.
  static absl::StatusOr<WebAssets> Load(const std::string& web_dir, const std::string& three_dir);

  // The file at `path` (GET or HEAD); 404 for any other path, 405 for other methods.
  HttpResponse Serve(const HttpRequest& request) const;

  // How many files are served.
  size_t size() const { return files_.size(); }

 private:
  struct File {
    std::string content_type;
    std::shared_ptr<const std::string> bytes;
  };
  std::map<std::string, File> files_;  // by URL path
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_WEB_ASSETS_H_
