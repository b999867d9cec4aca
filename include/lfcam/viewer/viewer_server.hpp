// The viewer on the network: cpp-httplib serving answerRequest (viewer.hpp), with the limits a
// local server left running needs: a fixed thread pool, read and write timeouts, a tiny payload
// limit (the viewer takes no request bodies), and its own line and header limits (414, 431/400).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "lfcam/core/result.hpp"
#include "lfcam/viewer/viewer.hpp"

namespace lfcam {

struct ViewerServerOptions {
  std::string host = "127.0.0.1";  // loopback: the viewer is for this machine unless asked
  int port = 8080;                 // 0: any free port (ViewerServer::port says which)
  int threads = 8;                 // connections served at once
  int timeoutSeconds = 5;          // read/write/keep-alive
};

class ViewerServer {
 public:
  explicit ViewerServer(ViewerSession& session);
  // Any answering function in place of answerRequest (e.g. one fixed page: servePage below).
  explicit ViewerServer(std::function<ViewerAnswer(const ViewerRequest&)> answer);
  ~ViewerServer();
  // Binds the socket (Io error when the address is taken or invalid).
  Status bind(const ViewerServerOptions& options);
  int port() const;
  // Serves until stop() (from another thread or a signal handler's flag).
  Status run();
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Answers GET / and /index.html with `html` (HEAD too), 404 any other path, 405 other methods:
// a living picture (living_picture.hpp) served as it is.
std::function<ViewerAnswer(const ViewerRequest&)> servePage(std::string html);

}  // namespace lfcam
