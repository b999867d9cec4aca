// ViewerServer: cpp-httplib around answerRequest. Every route goes through answerRequest, so
// the server itself has no file handler and no path of a request reaches the file system.
// Debian builds cpp-httplib as a library (compiled limits: request line 8 KiB -> 414, header
// line 8 KiB -> 400), found through pkg-config with the definitions its ABI needs.
#include <httplib.h>
#include <netinet/in.h>
#include <netinet/tcp.h>

#include "lfcam/viewer/viewer_server.hpp"

namespace lfcam {

struct ViewerServer::Impl {
  std::function<ViewerAnswer(const ViewerRequest&)> answer;
  httplib::Server server;
  int port = 0;
  explicit Impl(std::function<ViewerAnswer(const ViewerRequest&)> a) : answer(std::move(a)) {}
};

ViewerServer::ViewerServer(ViewerSession& session)
    : ViewerServer([&session](const ViewerRequest& request) { return answerRequest(session, request); }) {}

ViewerServer::ViewerServer(std::function<ViewerAnswer(const ViewerRequest&)> answer)
    : impl_(std::make_unique<Impl>(std::move(answer))) {
  httplib::Server& server = impl_->server;
  auto handle = [this](const httplib::Request& request, httplib::Response& response) {
    ViewerAnswer reply = impl_->answer({request.method, request.path, request.params});
    response.status = reply.status;
    for (const auto& [name, value] : reply.headers) response.set_header(name, value);
    response.set_header("X-Content-Type-Options", "nosniff");
    response.set_content(std::move(reply.body), reply.contentType);
  };
  server.Get(".*", handle);
  server.Post(".*", handle);
  server.Put(".*", handle);
  server.Delete(".*", handle);
  server.Patch(".*", handle);
  server.Options(".*", handle);
  server.set_exception_handler([](const httplib::Request&, httplib::Response& response, std::exception_ptr) {
    response.status = 500;
    response.set_content("internal error\n", "text/plain");
  });
  // The viewer takes no bodies: anything larger than a few bytes is refused (413).
  server.set_payload_max_length(1024);
  // Nagle off (accepted sockets inherit it on Linux): a photograph's last bytes leave at once
  // instead of waiting for the client's delayed acknowledgement.
  server.set_socket_options([](socket_t socket) {
    httplib::default_socket_options(socket);
    int yes = 1;
    setsockopt(socket, IPPROTO_TCP, TCP_NODELAY, &yes, sizeof yes);
  });
}

ViewerServer::~ViewerServer() = default;

Status ViewerServer::bind(const ViewerServerOptions& options) {
  httplib::Server& server = impl_->server;
  const int threads = std::max(1, options.threads);
  server.new_task_queue = [threads] { return new httplib::ThreadPool(std::size_t(threads)); };
  server.set_read_timeout(options.timeoutSeconds, 0);
  server.set_write_timeout(options.timeoutSeconds, 0);
  server.set_keep_alive_timeout(options.timeoutSeconds);
  server.set_keep_alive_max_count(100);
  const std::string where = options.host + ":" + std::to_string(options.port);
  if (options.port < 0 || options.port > 65535) return makeError(ErrorCode::Usage, where + ": no such port");
  if (options.port == 0) {
    impl_->port = server.bind_to_any_port(options.host);
    if (impl_->port <= 0) return makeError(ErrorCode::Io, where + ": cannot listen there");
  } else {
    if (!server.bind_to_port(options.host, options.port))
      return makeError(ErrorCode::Io, where + ": cannot listen there (address in use or not this machine's)");
    impl_->port = options.port;
  }
  return {};
}

int ViewerServer::port() const { return impl_->port; }

Status ViewerServer::run() {
  if (!impl_->server.listen_after_bind()) return makeError(ErrorCode::Io, "the server stopped with an error");
  return {};
}

void ViewerServer::stop() { impl_->server.stop(); }

std::function<ViewerAnswer(const ViewerRequest&)> servePage(std::string html) {
  return [html = std::move(html)](const ViewerRequest& request) {
    ViewerAnswer answer;
    if (request.method != "GET" && request.method != "HEAD") {
      answer.status = 405;
      answer.body = "method not allowed\n";
    } else if (request.path != "/" && request.path != "/index.html") {
      answer.status = 404;
      answer.body = "not found\n";
    } else {
      answer.contentType = "text/html; charset=utf-8";
      answer.body = html;
    }
    return answer;
  };
}

}  // namespace lfcam
