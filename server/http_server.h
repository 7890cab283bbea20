// The HTTP listener of membraned --http-listen: civetweb (Debian's libcivetweb, which
// prometheus-cpp's /metrics endpoint already runs on) carrying requests to a handler. Each of
// its threads serves one connection at a time; a connection is closed after its response.
#ifndef MEMBRANE_SERVER_HTTP_SERVER_H_
#define MEMBRANE_SERVER_HTTP_SERVER_H_

#include <functional>
#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "server/http_api.h"

struct mg_connection;
struct mg_context;

namespace membrane::server {

class HttpServer {
 public:
  using Handler = std::function<HttpResponse(const HttpRequest&)>;

  // Serves `handler` on `address` (HOST:PORT; port 0 picks a free one) with `threads` threads
  // (requests served at once; more wait for a thread). A request that is not read whole
  // within `request_timeout_ms`, or a response not taken within it, ends its connection.
  // Unavailable naming the address and civetweb's reason when it cannot listen.
  static absl::StatusOr<std::unique_ptr<HttpServer>> Start(const std::string& address,
                                                           int threads, int request_timeout_ms,
                                                           Handler handler);
  // Stops listening and waits for the requests being served.
  ~HttpServer();

  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  // The bound port.
  int port() const { return port_; }

 private:
  explicit HttpServer(Handler handler) : handler_(std::move(handler)) {}
  // civetweb's request callback: reads the request, calls handler_, writes the response.
  static int Serve(mg_connection* connection, void* self);

  const Handler handler_;
  mg_context* context_ = nullptr;
  int port_ = 0;
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_HTTP_SERVER_H_
