// WebServer: HTTP and WebSocket on one port of 127.0.0.1 (websocketpp over standalone asio), for
// the viewer page. HTTP GETs go to a handler; WebSocket clients (path /ws) receive what the
// owner publishes, in two kinds:
//   Append: a log every client receives whole and in order (trajectory batches, dense chunks), a
//     client that connects late or reads slowly catching up at its own pace;
//   Replace: the latest message under a key (the image, the sparse map, stats); a client gets
//     only the newest one, so a slow client skips versions instead of queueing them.
// A client whose unsent bytes exceed kMaxBacklogBytes gets nothing more until it has read them:
// a slow or stalled browser costs memory up to that bound, never time on the publisher's side.
// Publishing is thread-safe and returns at once; the network runs on the server's own thread.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace drvslam {

// What the server has handed to WebSocket clients since it started (all clients together).
struct WebTraffic {
  std::size_t connections = 0;  // WebSocket connections opened
  std::size_t messages = 0;     // messages handed to a client's connection
  std::uint64_t bytes = 0;      // their payload bytes
};

struct HttpResponse {
  int status = 200;
  std::string content_type = "text/plain; charset=utf-8";
  std::string body;
};

class WebServer {
 public:
  // The handler gets the request's path (query string removed); nullopt answers 404.
  using HttpHandler = std::function<std::optional<HttpResponse>(const std::string& path)>;

  static constexpr std::size_t kMaxBacklogBytes = 8u << 20;

  // Listens on 127.0.0.1:port (0: a free port, see Port()). Throws Error naming the port when
  // it cannot listen (in use, or not allowed).
  WebServer(int port, HttpHandler handler);
  ~WebServer();  // Stop
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  int Port() const;

  void Append(std::string message);
  void Replace(const std::string& key, std::string message);

  // Waits up to timeout_ms until every connected client has been sent the whole log and the
  // latest messages (used before stopping, so the last update reaches the page).
  void Flush(int timeout_ms);
  std::size_t Clients() const;
  WebTraffic Traffic() const;
  // Messages not sent to some client because it was over kMaxBacklogBytes (a pump skipped it).
  std::size_t Throttled() const;
  void Stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace drvslam
