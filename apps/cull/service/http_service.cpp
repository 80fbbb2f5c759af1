#include "service/http_service.hpp"

#include <array>
#include <optional>
#include <thread>
#include <vector>

#include <spdlog/spdlog.h>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/strand.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <nlohmann/json.hpp>

#include "requests/cull_request.hpp"

namespace tsr::app {

namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using asio::ip::tcp;

std::chrono::steady_clock::duration deadline(ServiceLimits::Seconds s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(s);
}

bool quietEnd(const beast::error_code& ec) {
  return ec == http::error::end_of_stream || ec == http::error::partial_message ||
         ec == asio::error::connection_reset || ec == asio::error::eof || ec == asio::error::operation_aborted ||
         ec == asio::error::broken_pipe;
}

}  // namespace

// One connection, on its own strand: request headers within their
// deadline, the body within one scaled to its size, the answer (from the
// routes, or later from the cull queue), and the next request within the
// keep-alive deadline. A refused connection gets its 429 or 503, then the
// service reads (and drops) what the client still sends until it closes or
// the linger ends, so the refusal is read, not reset.
class HttpService::Session : public std::enable_shared_from_this<Session> {
 public:
  Session(HttpService& service, tcp::socket socket, const asio::ip::address& address, ClientSlot connection)
      : service_(service),
        limits_(service.options_.limits),
        stream_(std::move(socket)),
        address_(address),
        connection_(std::move(connection)) {}

  ~Session() {
    if (refusing_) --service_.refusing_;
  }
  beast::tcp_stream::executor_type executor() { return stream_.get_executor(); }

  void start(ClientTable::Refusal refusal) {
    if (refusal == ClientTable::Refusal::None) return readRequest(true);
    refusing_ = true;  // counted by admit()
    const std::string who = address_.to_string();
    refuse(refusal == ClientTable::Refusal::Address
               ? httpRefusal(11, http::status::too_many_requests,
                             "too many connections from " + who + " (the limit is " +
                                 std::to_string(limits_.connectionsPerAddress) + "): close one, then retry")
               : httpRefusal(
                     11, http::status::service_unavailable,
                     "the service holds its " + std::to_string(limits_.maxConnections) + " connections: retry later"));
  }

 private:
  void readRequest(bool first) {
    parser_.emplace();
    limitRequest(*parser_, ServiceLimits::kMaxHeaderBytes, ServiceLimits::kMaxBodyBytes);
    stream_.expires_after(deadline(first ? limits_.headerTimeout : limits_.keepAliveTimeout));
    http::async_read_header(stream_, buffer_, *parser_,
                            [self = shared_from_this()](beast::error_code ec, std::size_t) { self->onHeader(ec); });
  }

  void onHeader(beast::error_code ec) {
    if (ec) return readFailed(ec);
    if (parser_->is_done()) return onRequest();
    // The body's deadline grows with its announced size (chunked: the most it may be).
    const std::uint64_t size = parser_->content_length().value_or(ServiceLimits::kMaxBodyBytes);
    stream_.expires_after(
        deadline(limits_.transferDeadline(std::min<std::uint64_t>(size, ServiceLimits::kMaxBodyBytes))));
    http::async_read(stream_, buffer_, *parser_, [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (ec) return self->readFailed(ec);
      self->onRequest();
    });
  }

  void readFailed(const beast::error_code& ec) {
    if (ec == beast::error::timeout) {
      ++service_.timedOut_;
      return;  // the stream closed itself
    }
    if (quietEnd(ec)) return;
    keepAlive_ = false;
    send(httpReply(11, http::status::bad_request, "bad request: " + ec.message() + "\n"));
  }

  void onRequest() {
    HttpRequest request = parser_->release();
    keepAlive_ = request.keep_alive();
    Route route = service_.routes_.route(request);
    switch (route.kind) {
      case Route::Kind::Reply:
        return send(std::move(route.reply));
      case Route::Kind::Cull:
        return cull(route.query, request.version());
      case Route::Kind::Preview:
        return preview(std::move(request));
    }
  }

  void cull(const CullQuery& query, unsigned version) {
    if (service_.clients_.take(address_, SlotKind::Request, request_) != ClientTable::Refusal::None) {
      ++service_.refusedRequests_;
      return send(httpRefusal(version, http::status::too_many_requests,
                              "too many /v1/cull requests in flight from " + address_.to_string() + " (the limit is " +
                                  std::to_string(limits_.requestsPerAddress) + "): wait for an answer, then retry"));
    }
    auto job = std::make_shared<CullJob>();
    job->query = query;
    job->done = [self = shared_from_this(), version](const CullAnswer* answer, const std::string& error) {
      HttpResponse r = answer ? httpReply(version, http::status::ok, cullAnswerJson(*answer), "application/json")
                              : httpReply(version, http::status::internal_server_error, "failed: " + error + "\n");
      asio::post(self->stream_.get_executor(), [self, r = std::move(r)]() mutable { self->answered(std::move(r)); });
    };
    if (!service_.queue_.push(job)) {
      request_.release();
      return send(httpRefusal(
          version, http::status::service_unavailable,
          "the ranking queue is full (" + std::to_string(limits_.cullQueue) + " requests wait): retry later"));
    }
    job_ = std::move(job);
    watchForLeaving();
  }

  // While a ranking waits, the connection is watched: a client that closes
  // it has its request dropped from the queue.
  void watchForLeaving() {
    stream_.socket().async_wait(tcp::socket::wait_read, [self = shared_from_this()](beast::error_code ec) {
      if (ec || !self->job_) return;  // answered meanwhile
      std::array<char, 1> byte;
      auto& socket = self->stream_.socket();
      socket.non_blocking(true, ec);
      const std::size_t n = socket.receive(asio::buffer(byte), tcp::socket::message_peek, ec);
      if (ec == asio::error::would_block) return self->watchForLeaving();
      if (!ec && n > 0) return;  // its next request, pipelined: still there
      self->job_->gone = true;
      self->job_.reset();
      self->request_.release();
      self->stream_.close();
    });
  }

  void answered(HttpResponse response) {
    if (!job_) return;  // the client left meanwhile
    job_.reset();
    request_.release();
    beast::error_code ec;
    stream_.socket().cancel(ec);  // the watch
    send(std::move(response));
  }

  void preview(HttpRequest request) {
    ClientSlot stream;
    if (service_.clients_.take(address_, SlotKind::Preview, stream) != ClientTable::Refusal::None) {
      ++service_.refusedPreviews_;
      keepAlive_ = false;
      return send(httpRefusal(request.version(), http::status::too_many_requests,
                              "too many previews from " + address_.to_string() + " (the limit is " +
                                  std::to_string(limits_.previewsPerAddress) + "): close one, then retry"));
    }
    beast::error_code ec;
    stream_.socket().set_option(asio::socket_base::keep_alive(true), ec);
    service_.previews_.serve(std::move(stream_), std::move(request), std::move(connection_), std::move(stream));
  }

  void send(HttpResponse response) {
    if (!keepAlive_) response.keep_alive(false);
    auto out = std::make_shared<HttpResponse>(std::move(response));
    stream_.expires_after(deadline(limits_.transferDeadline(out->body().size())));
    http::async_write(stream_, *out, [self = shared_from_this(), out](beast::error_code ec, std::size_t) {
      if (ec == beast::error::timeout) ++self->service_.timedOut_;
      if (ec) return;
      if (out->keep_alive()) return self->readRequest(false);
      self->linger();
    });
  }

  void refuse(HttpResponse response) {
    auto out = std::make_shared<HttpResponse>(std::move(response));
    stream_.expires_after(deadline(limits_.lingerTime));
    http::async_write(stream_, *out, [self = shared_from_this(), out](beast::error_code ec, std::size_t) {
      if (!ec) self->linger();
    });
  }

  // After a last reply: the sending side closes, and what the client still
  // sends is read and dropped for a moment, so the reply reaches it instead
  // of a reset (closing with unread input resets the connection).
  void linger() {
    beast::error_code ec;
    stream_.socket().shutdown(tcp::socket::shutdown_send, ec);
    stream_.expires_after(deadline(limits_.lingerTime));
    drain();
  }

  void drain() {
    stream_.async_read_some(asio::buffer(scratch_), [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (!ec) self->drain();
    });
  }

  HttpService& service_;
  const ServiceLimits& limits_;
  beast::tcp_stream stream_;
  const asio::ip::address address_;
  ClientSlot connection_, request_;
  beast::flat_buffer buffer_{ServiceLimits::kMaxHeaderBytes + ServiceLimits::kMaxBodyBytes};
  std::optional<http::request_parser<http::string_body>> parser_;
  std::shared_ptr<CullJob> job_;  // the ranking this connection waits for
  std::array<char, 512> scratch_;
  bool keepAlive_ = true, refusing_ = false;
};

HttpService::HttpService(CullService& cull, PreviewStreams& previews, const WebFiles& web, HttpOptions options)
    : cull_(cull),
      previews_(previews),
      options_(std::move(options)),
      token_(options_.token),
      routes_(*this, web, token_, options_.maxObjects),
      clients_(options_.limits.connectionsPerAddress, options_.limits.requestsPerAddress,
               options_.limits.previewsPerAddress, options_.limits.maxConnections),
      queue_(cull, options_.limits.cullQueue) {}

void HttpService::serve(tcp::acceptor& acceptor) {
  accept(acceptor);
  auto& io = static_cast<asio::io_context&>(acceptor.get_executor().context());
  const auto run = [&io] {
    for (;;) {
      try {
        io.run();
        return;
      } catch (const std::exception& e) {
        spdlog::error("a network handler failed: {}", e.what());
      }
    }
  };
  std::vector<std::thread> threads;
  for (int i = 1; i < options_.limits.ioThreads; ++i) threads.emplace_back(run);
  run();
  for (auto& t : threads) t.join();
}

void HttpService::accept(tcp::acceptor& acceptor) {
  acceptor.async_accept(asio::make_strand(acceptor.get_executor()),
                        [this, &acceptor](beast::error_code ec, tcp::socket socket) {
                          if (ec == asio::error::operation_aborted) return;
                          if (ec) return pauseAccepting(acceptor, ec);
                          admit(std::move(socket));
                          // Refusing costs a socket too: with as many refusals under
                          // way as connections allowed, new ones wait in the backlog.
                          if (refusing_.load() >= options_.limits.maxConnections) return pauseAccepting(acceptor, {});
                          accept(acceptor);
                        });
}

// A moment's pause, the backlog waiting: out of file descriptors (said at
// most every 10 s, a flood must not flood the log too) or refusing too many.
void HttpService::pauseAccepting(tcp::acceptor& acceptor, const beast::error_code& ec) {
  const auto now = std::chrono::steady_clock::now().time_since_epoch();
  if (ec && now - std::chrono::steady_clock::duration(lastAcceptWarning_.load()) >= std::chrono::seconds(10)) {
    lastAcceptWarning_ = now.count();
    spdlog::warn("accepting failed ({}): pausing; raise the open-file limit or lower --max-connections", ec.message());
  }
  auto pause = std::make_shared<asio::steady_timer>(acceptor.get_executor(), std::chrono::milliseconds(50));
  pause->async_wait([this, &acceptor, pause](beast::error_code) { accept(acceptor); });
}

void HttpService::admit(tcp::socket socket) {
  beast::error_code ec;
  const auto remote = socket.remote_endpoint(ec);
  if (ec) return;  // gone already
  ClientSlot connection;
  const auto refusal = clients_.take(remote.address(), SlotKind::Connection, connection);
  if (refusal != ClientTable::Refusal::None) ++refusedConnections_;
  auto session = std::make_shared<Session>(*this, std::move(socket), remote.address(), std::move(connection));
  if (refusal != ClientTable::Refusal::None) ++refusing_;  // counted before the next accept looks
  asio::dispatch(session->executor(), [session, refusal] { session->start(refusal); });
}

std::string HttpService::sceneJson() const { return cull_.sceneJson(previews_.enabled()); }

std::optional<std::vector<std::uint8_t>> HttpService::objectGlb(sg::ContainerId id) const {
  return cull_.objectGlb(id);
}

std::string HttpService::statusJson() const {
  const ServiceLimits& l = options_.limits;
  const CullQueueStatus q = queue_.status();
  return nlohmann::json{{"connections",
                         {{"open", clients_.connections()},
                          {"addresses", clients_.addresses()},
                          {"limit", l.maxConnections},
                          {"per_address", l.connectionsPerAddress},
                          {"refused", refusedConnections_.load()},
                          {"timed_out", timedOut_.load()}}},
                        {"cull",
                         {{"waiting", q.waiting},
                          {"capacity", q.capacity},
                          {"ranking", q.ranking},
                          {"in_flight", clients_.held(SlotKind::Request)},
                          {"per_address", l.requestsPerAddress},
                          {"answered", q.answered},
                          {"dropped", q.dropped},
                          {"refused", q.refused + refusedRequests_.load()},
                          {"oldest_wait_ms", q.oldestWaitMs},
                          {"recent_ranking_ms", q.recentRankingMs}}},
                        {"previews",
                         {{"streams", previews_.active()},
                          {"limit", previews_.enabled() ? previews_.limit() : 0},
                          {"per_address", l.previewsPerAddress},
                          {"refused", refusedPreviews_.load()}}}}
      .dump();
}

}  // namespace tsr::app
