// Plain HTTP/1.0 requests for tests of membraned's metrics endpoint and HTTP API.
#ifndef MEMBRANE_TESTS_SERVER_HTTP_GET_H_
#define MEMBRANE_TESTS_SERVER_HTTP_GET_H_

#include <string>

namespace membrane::testing {

// The body of `GET path` from 127.0.0.1:`port`, or "" when the request fails or the status is
// not 200. Waits at most a few seconds.
std::string HttpGet(int port, const std::string& path);

// What one HTTP request got: the status (0 when the request failed), the header lines and the
// body.
struct HttpReply {
  int status = 0;
  std::string headers;
  std::string body;
};

// `method path` to 127.0.0.1:`port`, with "Authorization: `authorization`" when that is not
// empty. Waits at most `seconds` for the answer.
HttpReply HttpCall(int port, const std::string& method, const std::string& path,
                   const std::string& authorization = "", double seconds = 30);

// The value of the sample `series` (a metric name with its labels, as the text format writes
// them, e.g. `membrane_jobs_finished_total{code="OK",state="SUCCEEDED"}`) in a Prometheus text
// exposition; -1 when absent.
double MetricValue(const std::string& exposition, const std::string& series);

// A connection to 127.0.0.1:`port` that sends the start of a GET and no more, as a stalled or
// hostile client would; its descriptor, or -1.
int OpenHalfSentRequest(int port);

// Whether the server ends the connection `fd` (closes it, or answers and closes) within
// `seconds`; closes `fd` either way.
bool ServerEndsConnection(int fd, double seconds);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SERVER_HTTP_GET_H_
