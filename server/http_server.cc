#include "server/http_server.h"

#include <civetweb.h>

#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"

namespace membrane::server {

absl::StatusOr<std::unique_ptr<HttpServer>> HttpServer::Start(const std::string& address,
                                                             int threads, int request_timeout_ms,
                                                             Handler handler) {
  std::unique_ptr<HttpServer> server(new HttpServer(std::move(handler)));
  const std::string thread_count = absl::StrCat(threads);
  const std::string timeout = absl::StrCat(request_timeout_ms);
  // No document root: nothing but the handler's answers is served.
  const char* options[] = {"listening_ports", address.c_str(),
                           "num_threads", thread_count.c_str(),
                           "request_timeout_ms", timeout.c_str(),
                           "enable_keep_alive", "no",
                           nullptr};
  mg_callbacks callbacks{};
  // civetweb prints its errors to stderr without this; the status below says what failed.
  callbacks.log_message = [](const mg_connection*, const char*) { return 1; };
  mg_init_data init{};
  init.callbacks = &callbacks;
  init.user_data = server.get();
  init.configuration_options = options;
  unsigned code = 0;
  char text[256] = "";
  mg_error_data error{&code, text, sizeof text};
  server->context_ = mg_start2(&init, &error);
  if (server->context_ == nullptr) {
    return absl::UnavailableError(absl::StrCat("cannot serve HTTP on ", address,
                                               " (--http-listen): ", text));
  }
  mg_set_request_handler(server->context_, "/", &HttpServer::Serve, server.get());
  mg_server_port ports[4];
  const int n = mg_get_server_ports(server->context_, 4, ports);
  server->port_ = n > 0 ? ports[0].port : 0;
  return server;
}

HttpServer::~HttpServer() {
  if (context_ != nullptr) mg_stop(context_);
}

int HttpServer::Serve(mg_connection* connection, void* self) {
  const mg_request_info* info = mg_get_request_info(connection);
  HttpRequest request;
  request.method = info->request_method != nullptr ? info->request_method : "";
  request.path = info->local_uri != nullptr ? info->local_uri : "";
  request.query = info->query_string != nullptr ? info->query_string : "";
  if (const char* authorization = mg_get_header(connection, "Authorization")) {
    request.authorization = authorization;
  }
  request.peer = absl::StrCat(info->remote_addr, ":", info->remote_port);
  const HttpResponse response = static_cast<HttpServer*>(self)->handler_(request);
  const absl::string_view body = response.Body();
  std::string head = absl::StrCat("HTTP/1.1 ", response.status, " ",
                                  mg_get_response_code_text(connection, response.status),
                                  "\r\nContent-Type: ", response.content_type,
                                  "\r\nContent-Length: ", body.size(),
                                  "\r\nX-Content-Type-Options: nosniff\r\nConnection: close\r\n");
  for (const auto& [name, value] : response.headers) absl::StrAppend(&head, name, ": ", value, "\r\n");
  head += "\r\n";
  mg_write(connection, head.data(), head.size());
  if (request.method != "HEAD") mg_write(connection, body.data(), body.size());
  return response.status;
}

}  // namespace membrane::server
