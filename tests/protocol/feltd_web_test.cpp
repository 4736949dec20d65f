// feltd serve --web: the page's files over HTTP and felt.v1 over a WebSocket at /ws. A
// WebSocket session is a session like any other (Hello, limits, events with TCP clients, frames,
// the reply backlog, shutdown), and bad input over it gets what it gets over TCP.

#include <cmath>
#include <filesystem>
#include <fstream>

#include <boost/asio/connect.hpp>
#include <boost/asio/read.hpp>
#include <boost/asio/write.hpp>

#include "feltd_fixture.hpp"
#include "support/websocket_client.hpp"
#include "wire/message_codec.hpp"

namespace felt::test {
namespace {

namespace asio = boost::asio;

/// A page folder the test writes, and a file beside it that must never be served.
class PageFolder {
 public:
  PageFolder() {
    root_ = std::filesystem::temp_directory_path() /
            ("felt-web-test-" + std::to_string(::getpid()) + "-" + std::to_string(count_++));
    std::filesystem::create_directories(root_ / "page" / "assets");
    write("page/index.html", "<!doctype html><title>felt</title>");
    write("page/assets/app.js", "console.log('felt');");
    write("secret.txt", "not for the web");
    // a link inside the folder that leads out of it
    std::filesystem::create_symlink(root_ / "secret.txt", root_ / "page" / "escape.txt");
  }
  ~PageFolder() { std::filesystem::remove_all(root_); }
  std::string page() const { return (root_ / "page").string(); }

 private:
  void write(const std::string& relative, const std::string& text) {
    std::ofstream(root_ / relative) << text;
  }
  static inline int count_ = 0;
  std::filesystem::path root_;
};

/// The status line and body of one raw HTTP request to `port` (the request exactly as given).
std::pair<std::string, std::string> http_request(std::uint16_t port, const std::string& request) {
  asio::io_context io;
  asio::ip::tcp::socket socket(io);
  socket.connect({asio::ip::make_address("127.0.0.1"), port});
  asio::write(socket, asio::buffer(request));
  std::string response;
  boost::system::error_code ec;
  std::array<char, 4096> buffer;
  while (true) {
    const std::size_t n = socket.read_some(asio::buffer(buffer), ec);
    response.append(buffer.data(), n);
    if (ec) break;
  }
  const std::size_t line_end = response.find("\r\n");
  const std::size_t body = response.find("\r\n\r\n");
  return {response.substr(0, line_end), body == std::string::npos ? "" : response.substr(body + 4)};
}

std::string get(std::uint16_t port, const std::string& target, const std::string& method = "GET") {
  return http_request(port, method + " " + target +
                                " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n")
      .first;
}

class FeltdWebTest : public FeltdTest {
 protected:
  std::vector<std::string> extra_args() const override {
    return {"--web", "127.0.0.1:0", "--web-root", page_.page()};
  }
  std::unique_ptr<WebSocketClient> browser(const std::string& name) {
    auto client = std::make_unique<WebSocketClient>();
    client->connect("127.0.0.1", server_->web_port());
    client->hello(name);
    return client;
  }
  /// Waits for the next message that is not a frame or an event.
  static v1::ServerMessage next_reply(WebSocketClient& client) {
    while (true) {
      auto message = client.receive(scaled(5s));
      if (!message) throw std::runtime_error("no reply within 5 s");
      if (!message->has_frame() && !message->has_event()) return *message;
    }
  }
  /// Expects the server's Error `code` with request id 0, then the end of the connection.
  static void expect_closed_with(WebSocketClient& client, v1::ErrorCode code) {
    const v1::ServerMessage error = next_reply(client);
    ASSERT_TRUE(error.has_error()) << error.ShortDebugString();
    EXPECT_EQ(error.error().code(), code) << error.error().message();
    EXPECT_EQ(error.request_id(), 0u);
    EXPECT_THROW(
        while (true) { client.receive(scaled(5s)); }, ClientError);
  }

  PageFolder page_;
};

TEST_F(FeltdWebTest, ServesOnlyThePagesFiles) {
  const std::uint16_t port = server_->web_port();
  const auto [status, body] =
      http_request(port, "GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(status, "HTTP/1.1 200 OK");
  EXPECT_EQ(body, "<!doctype html><title>felt</title>");
  EXPECT_EQ(get(port, "/assets/app.js?v=2"), "HTTP/1.1 200 OK");
  EXPECT_EQ(get(port, "/index.html", "HEAD"), "HTTP/1.1 200 OK");
  for (const std::string target :
       {"/nope.js", "/../secret.txt", "/assets/../../secret.txt", "/%2e%2e/secret.txt",
        "/escape.txt", "/assets", "//etc/passwd", "/./index.html", "index.html"}) {
    EXPECT_EQ(get(port, target), "HTTP/1.1 404 Not Found") << target;
  }
  EXPECT_EQ(get(port, "/", "POST"), "HTTP/1.1 405 Method Not Allowed");
  EXPECT_EQ(get(port, "/ws"), "HTTP/1.1 400 Bad Request");
}

TEST_F(FeltdWebTest, AWebSocketSessionIsASessionLikeAnyOther) {
  auto watcher = greeted("tcp-watcher");
  WebSocketClient page;
  page.connect("127.0.0.1", server_->web_port());
  v1::ClientMessage stats;
  stats.mutable_get_stats();
  expect_error([&] { page.request(stats); }, v1::ERROR_CODE_HELLO_REQUIRED);
  const v1::Welcome welcome = page.hello("browser");
  EXPECT_NE(welcome.scene_id(), 0u);  // in the server's first scene, as over TCP
  // the TCP client hears the browser join, by its name
  const auto joined = watcher->wait_event(v1::EVENT_KIND_CLIENT_JOINED, 5s);
  ASSERT_TRUE(joined);
  EXPECT_EQ(joined->client_name(), "browser");
  EXPECT_EQ(joined->client_id(), welcome.client_id());
  // the README's touch: 1 cm into the curtain at 400 N/m
  const v1::ForceUpdate force = page.proxy_update(0, {0, 1.2, 0.01});
  EXPECT_TRUE(force.in_contact());
  EXPECT_NEAR(force.force().z(), 4.0, 0.5);
  // frames, 16-bit deltas as the page asks for them, each a binary message of its own
  v1::ClientMessage subscribe;
  subscribe.mutable_subscribe_frames()->set_max_rate_hz(60);
  subscribe.mutable_subscribe_frames()->set_normals(true);
  subscribe.mutable_subscribe_frames()->set_encoding(v1::FRAME_ENCODING_QUANTIZED16);
  subscribe.mutable_subscribe_frames()->set_deltas(true);
  EXPECT_TRUE(page.request(subscribe).has_subscribed());
  int frames = 0;
  while (frames < 3) {
    auto message = page.receive(scaled(5s));
    ASSERT_TRUE(message);
    if (!message->has_frame()) continue;
    ++frames;
    const v1::BodyFrame& body = message->frame().bodies(0);
    EXPECT_EQ(body.vertex_count(), 400u);
    EXPECT_EQ(body.triangles_size() > 0, frames == 1);  // triangles once
  }
  // a proxy update and a stats request pipelined: both answered, in order
  EXPECT_EQ(page.stats().scene().clients(), 2u);
  page.send_raw("");  // an empty binary message is an empty ClientMessage
  const v1::ServerMessage unknown = next_reply(page);
  EXPECT_EQ(unknown.error().code(), v1::ERROR_CODE_UNKNOWN_MESSAGE);
}

TEST_F(FeltdWebTest, BadInputOverAWebSocketIsRefusedAsOverTcpWhileOthersAreServed) {
  auto other = browser("other");
  // answered (the touches push the curtain away, so not always in contact)
  const auto still_served = [&] {
    const v1::ForceUpdate force = other->proxy_update(0, {0, 1.2, 0.01});
    EXPECT_TRUE(std::isfinite(force.force().z()));
    EXPECT_GT(other->stats().scene().clients(), 0u);
  };
  {
    auto garbage = browser("garbage");
    garbage->send_raw(std::string("\xff\xff\xff\xff\x0f garbage", 10));
    expect_closed_with(*garbage, v1::ERROR_CODE_MALFORMED_FRAME);
    EXPECT_EQ(garbage->close_code(), 1000);  // closed with the closing handshake
  }
  still_served();
  {
    auto text = browser("text");
    v1::ClientMessage hello;
    hello.mutable_hello()->set_protocol_version(1);
    text->send_raw(hello.SerializeAsString(), false);  // a valid message, but as text
    expect_closed_with(*text, v1::ERROR_CODE_MALFORMED_FRAME);
  }
  still_served();
  {
    auto oversized = browser("oversized");
    oversized->send_raw(std::string((4u << 20) + 1, '\0'));
    expect_closed_with(*oversized, v1::ERROR_CODE_FRAME_TOO_LARGE);
  }
  still_served();
  {
    // exactly the limit is taken (and is no ClientMessage)
    auto limit = browser("limit");
    limit->send_raw(std::string(4u << 20, '\x01'));
    expect_closed_with(*limit, v1::ERROR_CODE_MALFORMED_FRAME);
  }
  still_served();
  // a page of another site cannot open a session; the page's own origin can
  WebSocketClient foreign;
  EXPECT_THROW(foreign.connect("127.0.0.1", server_->web_port(), "http://evil.example"),
               ClientError);
  WebSocketClient same;
  same.connect("127.0.0.1", server_->web_port(),
               "http://127.0.0.1:" + std::to_string(server_->web_port()));
  EXPECT_TRUE(same.hello("same-origin").scene_id() != 0);
  EXPECT_TRUE(server_->running());
}

class SmallWebLimits : public FeltdWebTest {
  std::vector<std::string> extra_args() const override {
    auto args = FeltdWebTest::extra_args();
    for (const char* arg : {"--max-clients", "2", "--max-reply-backlog", "65536"}) {
      args.push_back(arg);
    }
    return args;
  }
};

TEST_F(SmallWebLimits, ClientLimitAndReplyBacklogHoldForWebSockets) {
  auto tcp = greeted("tcp");
  auto page = browser("page");
  WebSocketClient third;  // over --max-clients, whatever the transport
  third.connect("127.0.0.1", server_->web_port());
  expect_closed_with(third, v1::ERROR_CODE_LIMIT_EXCEEDED);
  // a page that never reads its replies is dropped past the backlog, and only it
  v1::ClientMessage stats;
  stats.mutable_get_stats();
  try {
    for (int i = 0; i < 100'000; ++i) page->send(stats);
  } catch (const ClientError&) {
    // the server hung up while the requests were still being written
  }
  ASSERT_TRUE(tcp->wait_event(v1::EVENT_KIND_CLIENT_LEFT, 10s));
  EXPECT_TRUE(tcp->proxy_update(0, {0, 1.2, 0.01}).in_contact());
}

TEST_F(FeltdWebTest, ShutdownTellsWebSocketClientsAndClosesCleanly) {
  auto page = browser("page");
  ::kill(server_->pid(), SIGTERM);
  bool told = false;
  try {
    while (true) {
      auto message = page->receive(scaled(5s));
      if (!message) break;
      if (message->has_event() && message->event().kind() == v1::EVENT_KIND_SERVER_SHUTDOWN) {
        told = true;
      }
    }
  } catch (const ClientError&) {
  }
  EXPECT_TRUE(told);
  EXPECT_EQ(page->close_code(), 1000);
  EXPECT_EQ(server_->stop(SIGTERM, 5s).value_or(-1), 0);  // it has exited: the status
}

}  // namespace
}  // namespace felt::test
