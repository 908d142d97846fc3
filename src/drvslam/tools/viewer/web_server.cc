#include "drvslam/tools/viewer/web_server.h"

#include <atomic>
#include <cerrno>
#include <chrono>
#include <map>
#include <mutex>
#include <thread>
#include <vector>
#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include "drvslam/core/error.h"
#include "drvslam/core/thread_name.h"

namespace drvslam {
namespace {

using Server = websocketpp::server<websocketpp::config::asio>;
using Handle = websocketpp::connection_hdl;
using Message = std::shared_ptr<const std::string>;

// Resumes clients that were over the backlog bound once their buffers drain.
constexpr long kPumpIntervalMs = 50;

std::string PathOf(const std::string& resource) {
  const std::size_t query = resource.find('?');
  return query == std::string::npos ? resource : resource.substr(0, query);
}

}  // namespace

struct WebServer::Impl {
  struct Client {
    std::size_t next_log = 0;                   // index into the log
    std::map<std::string, std::uint64_t> sent;  // Replace key -> version sent
  };

  Server server;
  HttpHandler handler;
  std::thread thread;
  int port = 0;

  mutable std::mutex mutex;  // guards everything below
  std::vector<Message> log;
  std::map<std::string, std::pair<std::uint64_t, Message>> latest;
  std::uint64_t version = 0;
  std::map<Handle, Client, std::owner_less<Handle>> clients;

  std::atomic<bool> pump_posted{false};
  std::atomic<bool> all_sent{true};
  std::atomic<std::size_t> client_count{0};
  std::atomic<std::size_t> throttled{0};
  std::atomic<std::size_t> connections{0};
  std::atomic<std::size_t> messages{0};
  std::atomic<std::uint64_t> bytes{0};
  std::atomic<bool> stopped{false};

  void OnHttp(Handle handle);
  void Pump();                                                                // io thread
  void Send(Server::connection_ptr& connection, const std::string& message);  // io thread
  void SchedulePump();
  void Tick();  // io thread: pumps every kPumpIntervalMs
};

void WebServer::Impl::OnHttp(Handle handle) {
  Server::connection_ptr connection = server.get_con_from_hdl(handle);
  std::optional<HttpResponse> response;
  try {
    response = handler(PathOf(connection->get_resource()));
  } catch (const std::exception& error) {
    response = HttpResponse{500, "text/plain; charset=utf-8", error.what()};
  }
  if (!response) response = HttpResponse{404, "text/plain; charset=utf-8", "not found"};
  connection->set_status(static_cast<websocketpp::http::status_code::value>(response->status));
  connection->replace_header("Content-Type", response->content_type);
  connection->replace_header("Cache-Control", "no-store");
  connection->set_body(std::move(response->body));
}

void WebServer::Impl::Send(Server::connection_ptr& connection, const std::string& message) {
  const std::error_code error = connection->send(message, websocketpp::frame::opcode::text);
  if (error) return;
  ++messages;
  bytes += message.size();
}

void WebServer::Impl::Pump() {
  pump_posted = false;
  std::lock_guard<std::mutex> lock(mutex);
  bool everything_sent = true;
  for (auto& [handle, client] : clients) {
    std::error_code error;
    Server::connection_ptr connection = server.get_con_from_hdl(handle, error);
    if (error || connection->get_state() != websocketpp::session::state::open) continue;
    const auto room = [&] { return connection->get_buffered_amount() < kMaxBacklogBytes; };
    while (client.next_log < log.size() && room()) {
      Send(connection, *log[client.next_log]);
      ++client.next_log;
    }
    for (const auto& [key, entry] : latest) {
      std::uint64_t& sent = client.sent[key];
      if (sent >= entry.first) continue;
      if (!room()) {
        ++throttled;
        everything_sent = false;
        continue;
      }
      Send(connection, *entry.second);
      sent = entry.first;
    }
    if (client.next_log < log.size() || connection->get_buffered_amount() > 0) {
      everything_sent = false;
    }
  }
  all_sent = everything_sent;
}

void WebServer::Impl::SchedulePump() {
  all_sent = false;
  if (pump_posted.exchange(true)) return;
  asio::post(server.get_io_service(), [this] { Pump(); });
}

void WebServer::Impl::Tick() {
  if (stopped) return;
  Pump();
  server.set_timer(kPumpIntervalMs, [this](const std::error_code& error) {
    if (!error) Tick();
  });
}

WebServer::WebServer(int port, HttpHandler handler) : impl_(std::make_unique<Impl>()) {
  if (port < 0 || port > 65535) {
    throw Error("port " + std::to_string(port) + " is not a TCP port (0..65535)");
  }
  Impl& s = *impl_;
  s.handler = std::move(handler);
  s.server.clear_access_channels(websocketpp::log::alevel::all);
  s.server.clear_error_channels(websocketpp::log::elevel::all);
  s.server.init_asio();
  s.server.set_reuse_addr(false);
  s.server.set_http_handler([&s](Handle handle) { s.OnHttp(handle); });
  s.server.set_validate_handler([&s](Handle handle) {
    return PathOf(s.server.get_con_from_hdl(handle)->get_resource()) == "/ws";
  });
  s.server.set_open_handler([&s](Handle handle) {
    {
      std::lock_guard<std::mutex> lock(s.mutex);
      s.clients[handle] = Impl::Client{};
      s.client_count = s.clients.size();
    }
    ++s.connections;
    s.Pump();
  });
  s.server.set_close_handler([&s](Handle handle) {
    std::lock_guard<std::mutex> lock(s.mutex);
    s.clients.erase(handle);
    s.client_count = s.clients.size();
  });
  const asio::ip::tcp::endpoint endpoint(asio::ip::make_address("127.0.0.1"),
                                         static_cast<unsigned short>(port));
  std::error_code error;
  s.server.listen(endpoint, error);
  if (!error) s.server.start_accept(error);
  if (error) {
    const std::string where = "127.0.0.1:" + std::to_string(port);
    // asio reports the system's errno value in its own category.
    if (error.value() == EADDRINUSE) {
      throw Error("port " + std::to_string(port) + " is in use (" + where +
                  ": address already in use); choose another port");
    }
    throw Error("cannot listen on " + where + ": " + error.message());
  }
  s.port = s.server.get_local_endpoint(error).port();
  s.server.set_timer(kPumpIntervalMs, [&s](const std::error_code& e) {
    if (!e) s.Tick();
  });
  s.thread = std::thread([&s] {
    NameCurrentThread("drv-web");
    s.server.run();
  });
}

WebServer::~WebServer() { Stop(); }

int WebServer::Port() const { return impl_->port; }

void WebServer::Append(std::string message) {
  {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    impl_->log.push_back(std::make_shared<const std::string>(std::move(message)));
  }
  impl_->SchedulePump();
}

void WebServer::Replace(const std::string& key, std::string message) {
  {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    impl_->latest[key] = {++impl_->version,
                          std::make_shared<const std::string>(std::move(message))};
  }
  impl_->SchedulePump();
}

void WebServer::Flush(int timeout_ms) {
  if (impl_->stopped) return;
  impl_->SchedulePump();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  while (!impl_->all_sent && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

std::size_t WebServer::Clients() const { return impl_->client_count; }

WebTraffic WebServer::Traffic() const {
  WebTraffic traffic;
  traffic.connections = impl_->connections;
  traffic.messages = impl_->messages;
  traffic.bytes = impl_->bytes;
  return traffic;
}

std::size_t WebServer::Throttled() const { return impl_->throttled; }

void WebServer::Stop() {
  Impl& s = *impl_;
  if (s.stopped.exchange(true)) return;
  asio::post(s.server.get_io_service(), [&s] {
    std::error_code error;
    s.server.stop_listening(error);
    std::vector<Handle> handles;
    {
      std::lock_guard<std::mutex> lock(s.mutex);
      for (const auto& [handle, client] : s.clients) handles.push_back(handle);
    }
    for (const Handle& handle : handles) {
      s.server.close(handle, websocketpp::close::status::going_away, "run finished", error);
    }
  });
  // Lets the close handshakes go out before the loop stops.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(500);
  while (s.client_count > 0 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  s.server.stop();
  if (s.thread.joinable()) s.thread.join();
}

}  // namespace drvslam
