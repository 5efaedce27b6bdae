#include "view_serve.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <memory>
#include <mutex>
#include <set>
#include <string_view>
#include <thread>
#include <vector>

#include "cli_util.hpp"

namespace antcd::cli {

namespace {

volatile std::sig_atomic_t g_stop = 0;

void on_signal(int /*signal*/) { g_stop = 1; }

// Closes a descriptor on every exit path.
struct Fd {
  int fd = -1;
  explicit Fd(int f) : fd(f) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

constexpr std::size_t kMaxRequest = 16 * 1024;
constexpr std::size_t kMaxClients = 16;

bool send_all(int fd, std::string_view data) {
  while (!data.empty()) {
    const ssize_t n =
        ::send(fd, data.data(), std::min<std::size_t>(data.size(), 1 << 20), MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR && g_stop == 0) continue;
    if (n <= 0) return false;
    data.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

void respond(int fd, int status, const char* reason, const std::string& type, std::string_view body,
             bool head) {
  const std::string header = "HTTP/1.0 " + std::to_string(status) + " " + reason +
                             "\r\nContent-Type: " + type +
                             "\r\nContent-Length: " + std::to_string(body.size()) +
                             "\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n";
  if (send_all(fd, header) && !head) send_all(fd, body);
}

void handle(int fd, const ServedFile* files, std::size_t count) {
  timeval timeout{10, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &timeout, sizeof timeout);
  std::string request;
  char buffer[4096];
  while (request.find("\r\n\r\n") == std::string::npos) {
    if (request.size() > kMaxRequest) {
      respond(fd, 431, "Request Header Fields Too Large", "text/plain", "request too large\n",
              false);
      return;
    }
    const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
    if (n < 0 && errno == EINTR && g_stop == 0) continue;
    if (n <= 0) return;  // closed, timed out or interrupted: drop the connection
    request.append(buffer, static_cast<std::size_t>(n));
  }
  const std::string_view line(request.data(), request.find("\r\n"));
  const std::size_t sp1 = line.find(' ');
  const std::size_t sp2 = sp1 == std::string_view::npos ? sp1 : line.find(' ', sp1 + 1);
  if (sp2 == std::string_view::npos) {
    respond(fd, 400, "Bad Request", "text/plain", "bad request\n", false);
    return;
  }
  const std::string_view method = line.substr(0, sp1);
  std::string_view target = line.substr(sp1 + 1, sp2 - sp1 - 1);
  target = target.substr(0, target.find_first_of("?#"));
  const bool head = method == "HEAD";
  if (method != "GET" && !head) {
    respond(fd, 405, "Method Not Allowed", "text/plain", "only GET and HEAD\n", false);
    return;
  }
  for (std::size_t i = 0; i < count; ++i) {
    if (target == files[i].path || (files[i].path == "/" && target == "/index.html")) {
      respond(fd, 200, "OK", files[i].content_type, *files[i].body, head);
      return;
    }
  }
  respond(fd, 404, "Not Found", "text/plain", "not found\n", head);
}

}  // namespace

int serve_files(const ServedFile* files, std::size_t count, std::uint16_t port) {
  Fd server(::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0));
  if (server.fd < 0) throw UsageError(std::string("--serve: socket: ") + std::strerror(errno));
  const int yes = 1;
  ::setsockopt(server.fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(port);
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::bind(server.fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    throw UsageError("--port " + std::to_string(port) +
                     ": cannot listen on 127.0.0.1: " + std::strerror(errno));
  }
  if (::listen(server.fd, 16) != 0) {
    throw UsageError(std::string("--serve: listen: ") + std::strerror(errno));
  }
  socklen_t len = sizeof addr;
  ::getsockname(server.fd, reinterpret_cast<sockaddr*>(&addr), &len);

  g_stop = 0;
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;  // no SA_RESTART: a blocked poll or recv returns EINTR at once
  struct sigaction old_int {};
  struct sigaction old_term {};
  ::sigaction(SIGINT, &action, &old_int);
  ::sigaction(SIGTERM, &action, &old_term);

  std::printf("serving on http://127.0.0.1:%u/ (Ctrl-C stops)\n",
              static_cast<unsigned>(ntohs(addr.sin_port)));
  std::fflush(stdout);
  // One thread per connection, at most kMaxClients at once (browsers open spare connections
  // that may never send a request). On stop, open connections are shut down and joined.
  std::mutex mutex;
  std::set<int> open;
  struct Worker {
    std::thread thread;
    std::shared_ptr<std::atomic<bool>> done;
  };
  std::vector<Worker> workers;
  while (g_stop == 0) {
    std::erase_if(workers, [](Worker& w) {
      if (!w.done->load()) return false;
      w.thread.join();
      return true;
    });
    pollfd p{server.fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, 500);
    if (ready <= 0) continue;  // timeout or EINTR: re-check the stop flag
    const int fd = ::accept4(server.fd, nullptr, nullptr, SOCK_CLOEXEC);
    if (fd < 0) continue;
    std::unique_lock lock(mutex);
    if (open.size() >= kMaxClients) {
      lock.unlock();
      respond(fd, 503, "Service Unavailable", "text/plain", "too many connections\n", false);
      ::close(fd);
      continue;
    }
    open.insert(fd);
    lock.unlock();
    auto done = std::make_shared<std::atomic<bool>>(false);
    workers.push_back({std::thread([fd, files, count, done, &mutex, &open] {
                         handle(fd, files, count);
                         {
                           const std::lock_guard guard(mutex);
                           open.erase(fd);
                           ::close(fd);
                         }
                         done->store(true);
                       }),
                       done});
  }
  {
    const std::lock_guard guard(mutex);
    for (int fd : open) ::shutdown(fd, SHUT_RDWR);
  }
  for (auto& w : workers) w.thread.join();
  ::sigaction(SIGINT, &old_int, nullptr);
  ::sigaction(SIGTERM, &old_term, nullptr);
  std::fprintf(stderr, "stopped\n");
  return 0;
}

}  // namespace antcd::cli
